"""Rounds kept (issue 45) over real HTTP: a closed round's board, podium and debrief stay
reachable after a new round opens (no 409), the projector's history lists them, and each
round exports as CSV (every game, its path's summary and archetypes) and JSON (paths)."""

from __future__ import annotations

import csv
import io

import httpx
from classhelp import SEED, SETTINGS, Server, join, open_challenge, projector_key, variant

from evapcool.game.path import game_path
from evapcool.game.replay import Recording, encode

LOST = Recording(SETTINGS, SEED, ((400.0, 300),), won=False, score=0, frames=300)


def _send(server: Server, who: dict[str, str], challenge: object, rec: Recording) -> int:
    body = {"challenge": challenge, "code": encode(rec)}
    answer = httpx.post(server.base + "/api/submit", json=body, headers=who, timeout=60)
    assert answer.status_code == 200, answer.text
    return int(answer.json()["entry"])


def _first_round(server: Server) -> tuple[object, dict[str, list[int]]]:
    """Three students' wins (Bo twice) and Lou's lost game, in a round taking lost games."""
    challenge = open_challenge(server, lost=True)["id"]
    wins = [k for k in range(1, 14) if variant(SEED, k).won][:4]
    plan = {"Ada": [wins[0]], "Bo": [wins[1], wins[2]], "Cy": [wins[3]]}
    entries: dict[str, list[int]] = {}
    for name, ks in plan.items():
        who = join(server, name)
        entries[name] = [_send(server, who, challenge, variant(SEED, k)) for k in ks]
    entries["Lou"] = [_send(server, join(server, "Lou"), challenge, LOST)]
    return challenge, entries


def test_a_closed_round_keeps_board_debrief_and_exports(server: Server) -> None:
    first, entries = _first_round(server)
    url = server.base + "/api"
    live = httpx.get(url + "/leaderboard").json()
    assert live["players"] == 4 == len(live["entries"])
    assert httpx.get(url + "/leaderboard", params={"challenge": first}).status_code == 409
    second = open_challenge(server)["id"]  # closes the first
    # The new round is open: its debrief waits, the first's stays reachable.
    assert httpx.get(url + "/debrief").status_code == 409
    doc = httpx.get(url + "/debrief", params={"challenge": first}).json()
    assert doc["challenge"] == first and len(doc["games"]) == 4
    board = httpx.get(url + "/leaderboard", params={"challenge": first}).json()
    assert board["challenge"] == first and board["open"] is False and board["players"] == 4
    assert [e["name"] for e in board["entries"]][-1] == "Lou"
    assert board["replay"] is None
    assert httpx.get(url + "/leaderboard", params={"challenge": 999}).status_code == 404
    # The history: the projector's key or the lecturer; closed rounds only.
    key = projector_key(server)
    assert httpx.get(url + "/rounds").status_code == 403
    rounds = httpx.get(url + "/rounds", params={"key": key}).json()["rounds"]
    assert [r["id"] for r in rounds] == [first]
    assert rounds[0]["students"] == 4 and rounds[0]["games"] == 5
    assert httpx.get(url + "/rounds", headers=server.lecturer).json()["rounds"] == rounds
    assert second != first
    # CSV: every game sent, the store's columns, then archetypes and the path's summary.
    got = httpx.get(url + "/export.csv", params={"token": server.token, "challenge": first})
    assert got.status_code == 200
    assert f"evapcool-class-{first}.csv" in got.headers["content-disposition"]
    rows = list(csv.DictReader(io.StringIO(got.text)))
    assert len(rows) == 5
    by_entry = {int(r["entry"]): r for r in rows}
    arche = doc["archetypes"]
    assert by_entry[arche["best"]]["archetype"].split()[0] == "best"
    assert by_entry[entries["Lou"][0]]["archetype"] == "never_won"
    assert by_entry[entries["Lou"][0]]["won"] == "no"
    for name, ids in entries.items():
        for entry in ids:
            row = by_entry[entry]
            assert row["name"] == name and int(row["path_points"]) > 1
            assert int(row["start_atoms"]) == SETTINGS.n_atoms
    # JSON: every entry with its path, the one computed from the game itself.
    doc_json = httpx.get(url + "/export.json", headers=server.lecturer, params={"challenge": first})
    assert doc_json.status_code == 200
    assert f"evapcool-class-{first}.json" in doc_json.headers["content-disposition"]
    exported = doc_json.json()
    assert exported["challenge"]["id"] == first
    paths = {e["entry"]: e for e in exported["entries"]}
    assert set(paths) == {e for ids in entries.values() for e in ids}
    assert paths[entries["Lou"][0]]["path"] == game_path(LOST).to_json()
    assert paths[arche["best"]]["archetypes"][0] == "best"
    # Only the lecturer exports.
    assert httpx.get(url + "/export.json", params={"challenge": first}).status_code == 403
    assert httpx.get(url + "/export.json", params={"token": "x" * 20}).status_code == 403
