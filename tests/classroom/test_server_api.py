"""The class server over real HTTP (issue 22.3): challenge, join, submit, rank, stream, export."""

from __future__ import annotations

import asyncio
import csv
import io
import json

import httpx
from classhelp import (
    SEED,
    Server,
    browse,
    code,
    join,
    open_challenge,
    projector_key,
    variant,
)

from evapcool.classroom.names import NAME_MAX


def submit(server: Server, who: dict[str, str], challenge: object, k: int) -> httpx.Response:
    body = {"challenge": challenge, "code": code(SEED, k)}
    return httpx.post(server.base + "/api/submit", json=body, headers=who, timeout=60)


def test_pages_and_challenge(server: Server) -> None:
    assert httpx.get(server.base + "/api/challenge").status_code == 404
    page = httpx.get(server.base + "/").text
    # The name box takes what the server keeps (one limit everywhere).
    marker = (
        '<script type="application/json" id="evapcool-class">'
        f'{{"api":"/api","name_max":{NAME_MAX}}}</script>'
    )
    assert marker + "</head>" in page
    opened = open_challenge(server, attempts=3, minutes=30)
    got = httpx.get(server.base + "/api/challenge").json()
    assert got == opened
    assert got["seed"] == SEED and got["attempts"] == 3 and got["closes_at"].endswith("Z")
    assert set(got["settings"]) == {"n_atoms", "radius", "escape", "tc_exponent"}
    projector = httpx.get(server.base + "/projector").text
    assert "<svg" in projector and "/api/stream" in projector
    # the students' link printed at start, said short (no scheme: issue 45)
    assert f'Join: <span class="address">{server.base.split("://")[1]}</span><' in projector
    assert browse(server.base, "/lecturer", server.token).status_code == 200


def test_students_rank_stream_export_hide(server: Server) -> None:
    challenge = open_challenge(server)["id"]
    games = {name: k for name, k in (("Ada", 0), ("Bo", 1), ("Cy", 2))}
    tokens = {name: join(server, name) for name in games}
    for name, k in games.items():
        answer = submit(server, tokens[name], challenge, k)
        assert answer.status_code == 200, answer.text
        assert answer.json()["score"] == variant(SEED, k).score
    board = httpx.get(server.base + "/api/leaderboard").json()
    expected = sorted(
        games, key=lambda n: (-variant(SEED, games[n]).score, variant(SEED, games[n]).frames)
    )
    assert [e["name"] for e in board["entries"]] == expected
    assert [e["rank"] for e in board["entries"]] == [1, 2, 3] and board["rejected"] == 0
    exported = httpx.get(server.base + "/api/export.csv", params={"token": server.token})
    rows = list(csv.reader(io.StringIO(exported.text)))
    assert [r[1] for r in rows[1:]] == expected
    first = httpx.get(server.base + "/api/entries", headers=server.lecturer).json()["entries"][0]
    assert (
        httpx.post(
            server.base + "/api/hide", json={"entry": first["entry"]}, headers=server.lecturer
        ).status_code
        == 200
    )
    names = [e["name"] for e in httpx.get(server.base + "/api/leaderboard").json()["entries"]]
    assert first["name"] not in names and len(names) == 2


def test_stream_delivers_an_update_after_a_submit(server: Server) -> None:
    challenge = open_challenge(server)["id"]
    who = join(server, "Streamer")
    code(SEED, 0)  # made before the stream opens

    async def run() -> list[dict[str, object]]:
        seen: list[dict[str, object]] = []
        async with (
            httpx.AsyncClient(timeout=60) as client,
            client.stream("GET", server.base + "/api/stream") as events,
        ):
            lines = events.aiter_lines()
            seen.append(await _next_event(lines))
            body = {"challenge": challenge, "code": code(SEED, 0)}
            sent = asyncio.create_task(
                client.post(server.base + "/api/submit", headers=who, json=body)
            )
            while not seen[-1]["entries"]:
                seen.append(await asyncio.wait_for(_next_event(lines), 60))
            assert (await sent).status_code == 200
        return seen

    seen = asyncio.run(asyncio.wait_for(run(), 90))
    assert seen[0]["entries"] == [] and seen[0]["challenge"] == challenge
    assert [e["name"] for e in seen[-1]["entries"]] == ["Streamer"]  # type: ignore[union-attr]


async def _next_event(lines: object) -> dict[str, object]:
    """The next `data:` event of an SSE line iterator, parsed."""
    async for line in lines:  # type: ignore[attr-defined]
        if line.startswith("data: "):
            doc: dict[str, object] = json.loads(line[6:])
            return doc
    raise AssertionError("the stream ended")


def test_lecturer_actions_need_the_token(server: Server) -> None:
    open_challenge(server)
    wrong = {"Authorization": "Bearer not-the-token"}
    student = join(server, "Eve")
    for headers in ({}, wrong, student):
        for path, body in (
            ("/api/challenge", {"n_atoms": 49, "radius": 12}),
            ("/api/challenge/close", {}),
            ("/api/hide", {"entry": 1}),
            ("/api/show", {"entry": 1}),
        ):
            answer = httpx.post(server.base + path, json=body, headers=headers)
            assert answer.status_code == 403, (path, answer.text)
            assert answer.json()["error"]["field"] == "token"
        assert httpx.get(server.base + "/api/export.csv", headers=headers).status_code == 403
        assert httpx.get(server.base + "/api/entries", headers=headers).status_code == 403
    assert httpx.get(server.base + "/lecturer?token=nope").status_code == 403
    assert httpx.get(server.base + "/lecturer").status_code == 403


def test_closed_challenge_and_attempts_refused(server: Server) -> None:
    challenge = open_challenge(server, attempts=1)["id"]
    who = join(server, "Finn")
    assert submit(server, who, challenge, 0).status_code == 200
    again = submit(server, who, challenge, 1)
    assert again.status_code == 409 and again.json()["error"]["field"] == "attempts"
    other = join(server, "Gil")
    wrong = submit(server, other, challenge + 1, 1)
    assert wrong.status_code == 409 and wrong.json()["error"]["field"] == "challenge"
    closed = httpx.post(server.base + "/api/challenge/close", json={}, headers=server.lecturer)
    assert closed.status_code == 200
    late = submit(server, other, challenge, 1)
    assert late.status_code == 409 and late.json()["error"]["field"] == "challenge"
    assert httpx.get(server.base + "/api/challenge").status_code == 404
    board = httpx.get(server.base + "/api/leaderboard").json()
    assert board["open"] is False and [e["name"] for e in board["entries"]] == ["Finn"]


def test_replay_on_projector(server: Server) -> None:
    challenge = open_challenge(server)["id"]
    who = join(server, "Hal")
    entry = submit(server, who, challenge, 0).json()["entry"]
    shown = httpx.post(server.base + "/api/show", json={"entry": entry}, headers=server.lecturer)
    assert shown.status_code == 200 and shown.json()["replay"]["code"] == code(SEED, 0)
    key = projector_key(server)
    keyed = httpx.get(server.base + "/api/leaderboard", params={"key": key}).json()["replay"]
    assert keyed["name"] == "Hal" and keyed["code"] == code(SEED, 0)
    assert keyed["summary"]["frames"] == variant(SEED, 0).frames
    assert "code" not in httpx.get(server.base + "/api/leaderboard").json()["replay"]
    page = httpx.get(server.base + "/projector", params={"key": key})
    assert page.status_code == 200
    assert httpx.get(server.base + "/projector", params={"key": "0" * 32}).status_code == 403
