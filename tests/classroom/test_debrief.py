"""The debrief after a challenge (issue 36) over real HTTP: paths kept at verification,
archetypes, the lecturer's early look, a student's own place, anonymous mode, a pair."""

from __future__ import annotations

import httpx
from classhelp import SEED, SETTINGS, Server, join, open_challenge, variant

from evapcool.game.path import game_path
from evapcool.game.replay import Recording, decode, encode

#: A game that never wins: the trap held high (taken when the challenge takes lost games).
LOST = Recording(SETTINGS, SEED, ((400.0, 300),), won=False, score=0, frames=300)


def _send(server: Server, who: dict[str, str], challenge: object, rec: Recording) -> int:
    body = {"challenge": challenge, "code": encode(rec)}
    answer = httpx.post(server.base + "/api/submit", json=body, headers=who, timeout=60)
    assert answer.status_code == 200, answer.text
    return int(answer.json()["entry"])


def _class(server: Server) -> tuple[object, dict[str, int], dict[str, dict[str, str]]]:
    """A closed-to-be challenge taking lost games: four students' wins and one lost game."""
    challenge = open_challenge(server, lost=True)["id"]
    wins = [k for k in range(1, 12) if variant(SEED, k).won][:4]
    games = {f"Ada{k}": variant(SEED, k) for k in wins} | {"Lou": LOST}
    tokens = {name: join(server, name) for name in games}
    entries = {name: _send(server, tokens[name], challenge, rec) for name, rec in games.items()}
    return challenge, entries, tokens


def test_debrief_paths_archetypes_and_places(server: Server) -> None:
    challenge, entries, tokens = _class(server)
    url = server.base + "/api/debrief"
    # While open: the lecturer's early look only.
    assert httpx.get(url).status_code == 409
    assert httpx.get(url, headers=tokens["Lou"]).json()["error"]["field"] == "challenge"
    early = httpx.get(url, headers=server.lecturer).json()
    assert len(early["games"]) == 5
    httpx.post(server.base + "/api/challenge/close", headers=server.lecturer)
    doc = httpx.get(url).json()
    assert doc["challenge"] == challenge and doc["you"] is None and doc["lost"] is True
    by_entry = {g["entry"]: g for g in doc["games"]}
    assert set(by_entry) == set(entries.values())
    # Each path is the one computed from the game itself, point for point.
    for name, entry in entries.items():
        rec = LOST if name == "Lou" else variant(SEED, int(name[3:]))
        assert by_entry[entry]["path"] == game_path(rec).to_json()
        assert by_entry[entry]["name"] == name
    won = [g for g in doc["games"] if g["won"]]
    assert [g["rank"] for g in doc["games"]] == [1, 2, 3, 4, 5]
    arche = doc["archetypes"]
    assert arche["best"] == doc["games"][0]["entry"]
    assert arche["fastest"] == min(won, key=lambda g: g["frames"])["entry"]
    assert arche["most_lost"] == min(won, key=lambda g: (g["score"], -g["frames"]))["entry"]
    assert arche["never_won"] == entries["Lou"]
    law = doc["law"]
    assert law["n0"] == SETTINGS.n_atoms and 0 < law["tc0"] < law["t0"]
    assert by_entry[entries["Lou"]]["path"]["t0"] == law["t0"]
    mine = httpx.get(url, headers=tokens["Ada" + str(next(iter(entries)))[3:]]).json()["you"]
    first = next(iter(entries))
    assert mine == {"entry": entries[first], "rank": by_entry[entries[first]]["rank"]}


def test_anonymous_pick_and_pair(server: Server) -> None:
    _, entries, tokens = _class(server)
    httpx.post(server.base + "/api/challenge/close", headers=server.lecturer)
    best = httpx.get(server.base + "/api/debrief").json()["archetypes"]["best"]
    answer = httpx.post(
        server.base + "/api/debrief",
        json={"anonymous": True, "pick": best, "pair": [entries["Lou"], best]},
        headers=server.lecturer,
    )
    assert answer.json() == {"anonymous": True, "pick": best, "pair": [entries["Lou"], best]}
    seen = [
        httpx.get(server.base + "/api/debrief").text,
        httpx.get(server.base + "/api/debrief", headers=tokens["Lou"]).text,
        httpx.get(server.base + "/api/leaderboard").text,
        httpx.get(server.base + "/api/debrief/pair").text,
    ]
    for text in seen:
        for name in entries:
            assert name not in text
    board = httpx.get(server.base + "/api/leaderboard").json()
    assert board["replay"]["entry"] == best and board["debrief"]["pick"] == best
    # The lecturer still sees the names.
    assert "Lou" in httpx.get(server.base + "/api/debrief", headers=server.lecturer).text
    pair = httpx.get(server.base + "/api/debrief/pair").json()["games"]
    assert [g["entry"] for g in pair] == [entries["Lou"], best]
    for g in pair:
        path = g["path"]
        assert path["k"] == list(range(path["frames"] + 1))
        # Its replay code, for the projector to play both in step: the same game.
        assert decode(g["code"]).frames == path["frames"]
        sampled = httpx.get(server.base + "/api/debrief").json()["games"]
        kept = next(s["path"] for s in sampled if s["entry"] == g["entry"])
        at = dict(zip(path["k"], zip(path["n"], path["t"], strict=True), strict=True))
        assert all(at[k] == (n, t) for k, n, t in zip(kept["k"], kept["n"], kept["t"], strict=True))


def test_debrief_refusals(server: Server) -> None:
    url = server.base + "/api/debrief"
    assert httpx.get(url).status_code == 404  # no challenge yet
    _class(server)
    bad = [{"anonymous": "yes"}, {"pair": [1]}, {"pair": [2, 2]}, {"pick": "x"}]
    for body in bad:
        answer = httpx.post(url, json=body, headers=server.lecturer)
        assert answer.status_code == 400, body
        assert answer.json()["error"]["field"] in {"anonymous", "pair", "entry"}
    assert httpx.post(url, json={"pick": 999}, headers=server.lecturer).status_code == 404
    assert httpx.post(url, json={"anonymous": True}).status_code == 403
