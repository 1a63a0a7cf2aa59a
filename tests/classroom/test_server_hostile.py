"""The class server against hostile input (issue 22.3): names, sizes, rates, forged games."""

from __future__ import annotations

import dataclasses
import json
import unicodedata

import httpx
from classhelp import SEED, Server, browse, code, join, open_challenge, variant

from evapcool.classroom.store import NAME_MAX
from evapcool.game.replay import encode

HOSTILE_NAMES = [
    "<script>alert(1)</script>",
    '<img src=x onerror="alert(2)">',
    "tab\tbell\x07nul\x00esc\x1b[31m",
    "long" * 2500,
    "\u202eevil\u202c name",
    "\"quotes' & </td></tr>",
]
RAW_MARKUP = ("<script>alert", "<img src", "onerror=", "</td></tr>")


def submit(server: Server, who: dict[str, str], body: dict[str, object]) -> httpx.Response:
    return httpx.post(server.base + "/api/submit", json=body, headers=who, timeout=60)


def refusal(answer: httpx.Response, status: int, field: str) -> None:
    assert answer.status_code == status, answer.text
    error = answer.json()["error"]
    assert error["field"] == field and error["message"], error


def test_hostile_names_are_cleaned_and_never_markup(server: Server) -> None:
    challenge = open_challenge(server)["id"]
    for k, name in enumerate(HOSTILE_NAMES):
        who = join(server, name)
        assert submit(server, who, {"challenge": challenge, "code": code(SEED, k)}).is_success
    board = httpx.get(server.base + "/api/leaderboard")
    assert board.headers["content-type"].startswith("application/json")
    names = [e["name"] for e in board.json()["entries"]]
    assert len(names) == len(HOSTILE_NAMES)
    for name in names:
        assert 1 <= len(name) <= NAME_MAX
        assert not any(unicodedata.category(c).startswith("C") for c in name), name
    assert "long" * 6 in names
    pages = [httpx.get(server.base + "/projector").text]
    pages.append(browse(server.base, "/lecturer", server.token).text)
    for page in pages:
        for bad in RAW_MARKUP:
            assert bad not in page
    listed = httpx.get(server.base + "/api/entries", headers=server.lecturer).json()
    assert sorted(e["name"] for e in listed["entries"]) == sorted(names)


def test_bad_names_and_bodies(server: Server) -> None:
    for bad in ("", "   ", "\u202e\u200f", 42, None):
        refusal(httpx.post(server.base + "/api/join", json={"name": bad}), 400, "name")
    as_json = {"Content-Type": "application/json"}
    join_url = server.base + "/api/join"
    refusal(httpx.post(join_url, content=b"not json", headers=as_json), 400, "body")
    refusal(httpx.post(join_url, content=b"[1, 2]", headers=as_json), 400, "body")
    huge = json.dumps({"name": "x" * 300_000}).encode()
    refusal(httpx.post(join_url, content=huge, headers=as_json), 413, "body")
    open_challenge(server)
    who = {**join(server, "Big"), **as_json}
    huge = json.dumps({"challenge": 1, "code": "EC1." + "A" * 300_000}).encode()
    refusal(httpx.post(server.base + "/api/submit", content=huge, headers=who), 413, "body")


def test_too_fast_a_student_is_told_to_wait(server: Server) -> None:
    challenge = open_challenge(server)["id"]
    who = join(server, "Speedy")
    answers = [submit(server, who, {"challenge": challenge}) for _ in range(12)]
    statuses = [a.status_code for a in answers]
    assert statuses[0] == 400 and 429 in statuses, statuses
    slow = next(a for a in answers if a.status_code == 429)
    assert int(slow.headers["retry-after"]) >= 1
    assert slow.json()["error"]["field"] == "token"
    refusal(
        submit(server, {"Authorization": "Bearer forged"}, {"challenge": challenge}), 401, "token"
    )
    refusal(submit(server, {}, {"challenge": challenge}), 401, "token")


def test_forged_edited_and_damaged_games_are_refused(server: Server) -> None:
    challenge = open_challenge(server)["id"]
    honest = variant(SEED, 0)
    forged = encode(dataclasses.replace(honest, score=honest.score + 1))
    good = code(SEED, 0)
    damaged = good[:40] + ("A" if good[40] != "A" else "B") + good[41:]
    edited = {**honest.to_json(), "frames": honest.frames + 1}
    other_seed = encode(dataclasses.replace(honest, seed=SEED + 1))
    other_atoms = honest.to_json()
    other_atoms["settings"] = {**other_atoms["settings"], "n_atoms": 30}
    cases = [
        ({"code": forged}, "score"),
        ({"code": damaged}, "code"),
        ({"code": "EC9.abc.def"}, "code"),
        ({"recording": edited}, "frames"),
        ({"code": other_seed}, "seed"),
        ({"recording": other_atoms}, "settings.n_atoms"),
    ]
    for i, (game, field) in enumerate(cases):
        who = join(server, f"Mallory {i}")
        refusal(submit(server, who, {"challenge": challenge, **game}), 422, field)
    board = httpx.get(server.base + "/api/leaderboard").json()
    assert board["entries"] == [] and board["rejected"] == len(cases)
    refusal(submit(server, join(server, "No code"), {"challenge": challenge}), 400, "code")
    refusal(submit(server, join(server, "Int"), {"challenge": challenge, "code": 5}), 400, "code")


def test_moves_longer_than_the_challenge_allows(server: Server) -> None:
    challenge = open_challenge(server, max_frames=100)
    assert challenge["max_frames"] == 100 and variant(SEED, 0).frames > 100
    who = join(server, "Marathon")
    refusal(
        submit(server, who, {"challenge": challenge["id"], "code": code(SEED, 0)}), 422, "moves"
    )


def test_bad_challenge_parameters_name_the_field(server: Server) -> None:
    for body, field in (
        ({"n_atoms": 1, "radius": 12}, "n_atoms"),
        ({"n_atoms": 49.5, "radius": 12}, "n_atoms"),
        ({"n_atoms": 49, "radius": "big"}, "radius"),
        ({"n_atoms": 49, "radius": 12, "escape": "door"}, "escape"),
        ({"n_atoms": 49, "radius": 12, "seed": -1}, "seed"),
        ({"n_atoms": 49, "radius": 12, "minutes": 0}, "minutes"),
        ({"n_atoms": 49, "radius": 12, "attempts": True}, "attempts"),
    ):
        answer = httpx.post(server.base + "/api/challenge", json=body, headers=server.lecturer)
        refusal(answer, 400, field)
