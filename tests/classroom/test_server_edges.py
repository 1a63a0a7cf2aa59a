"""The class competition at its edges (issue 34): a close and a window's end pushed to
every page by the server itself, a student's attempts and standing, the projector's words."""

from __future__ import annotations

import asyncio
import html
import http.client
import json
import shlex
import time
from urllib.parse import urlsplit

import httpx
import pytest
from classhelp import SEED, Server, code, join, open_challenge, variant

from evapcool.classroom.class_cli import _shown_store
from evapcool.classroom.joinaddress import loopback


async def _boards(server: Server, until: object, budget: float) -> list[dict[str, object]]:
    """The stream's boards from connecting until `until(board)` holds (or `budget` s pass);
    nothing but the stream is asked meanwhile: what comes, the server sent by itself."""
    seen: list[dict[str, object]] = []
    async with (
        httpx.AsyncClient(timeout=budget + 30) as client,
        client.stream("GET", server.base + "/api/stream") as events,
    ):
        lines = events.aiter_lines()

        async def follow() -> None:
            async for line in lines:
                if line.startswith("data: "):
                    seen.append(json.loads(line[6:]))
                    if until(seen[-1]):  # type: ignore[operator]
                        return

        await asyncio.wait_for(follow(), budget)
    return seen


def test_the_window_ending_is_pushed_to_every_stream(server: Server) -> None:
    opened = open_challenge(server, minutes=0.1, attempts=2)  # a six-second window
    start = time.time()
    seen = asyncio.run(_boards(server, lambda b: not b["info"]["open"], budget=40))
    arrived = time.time()
    first, last = seen[0]["info"], seen[-1]["info"]
    assert first["open"] and first["id"] == opened["id"] and 0 < first["closes_in"] <= 6
    assert first["attempts"] == 2 and first["settings"] == opened["settings"]
    assert not last["open"] and last["closes_in"] == 0 and not seen[-1]["open"]
    assert arrived - start >= 5  # the close came with the window's end, not before
    # Everything else says the same: no challenge to play, the lecturer's "(closed)".
    assert httpx.get(server.base + "/api/challenge").status_code == 404
    listed = httpx.get(server.base + "/api/entries", headers=server.lecturer).json()
    assert listed["challenge"]["open"] is False


def test_closing_is_pushed_and_a_student_knows_their_standing(server: Server) -> None:
    challenge = open_challenge(server, attempts=3)["id"]
    ada, bob = join(server, "Ada"), join(server, "Bob")
    me = httpx.get(server.base + "/api/me", headers=ada).json()
    assert me == {
        "name": "Ada",
        "challenge": challenge,
        "attempts": 3,
        "lost": False,
        "used": 0,
        "best": None,
        "best_entry": None,
        "rank": None,
        "count": 0,
    }
    games = sorted(
        (k for k in range(6) if variant(SEED, k).won), key=lambda k: -variant(SEED, k).score
    )
    best, worse = games[0], games[-1]
    body = {"challenge": challenge, "code": code(SEED, worse)}
    got = httpx.post(server.base + "/api/submit", json=body, headers=ada, timeout=60).json()
    assert (got["used"], got["attempts"], got["rank"]) == (1, 3, 1)
    body = {"challenge": challenge, "code": code(SEED, best)}
    assert httpx.post(server.base + "/api/submit", json=body, headers=bob, timeout=60).is_success
    # Ada's place follows the board: Bob's better game put her second.
    me = httpx.get(server.base + "/api/me", headers=ada).json()
    assert (me["used"], me["best"], me["rank"]) == (1, variant(SEED, worse).score, 2)
    assert httpx.get(server.base + "/api/me").status_code == 401

    async def close_and_watch() -> list[dict[str, object]]:
        async def close() -> None:
            await asyncio.sleep(1.0)
            async with httpx.AsyncClient() as client:
                answer = await client.post(
                    server.base + "/api/challenge/close", json={}, headers=server.lecturer
                )
                assert answer.status_code == 200

        closing = asyncio.create_task(close())
        seen = await _boards(server, lambda b: not b["info"]["open"], budget=30)
        await closing
        return seen

    seen = asyncio.run(close_and_watch())
    assert seen[0]["info"]["open"] and not seen[-1]["info"]["open"]
    assert [e["name"] for e in seen[-1]["entries"]] == ["Bob", "Ada"]


def test_lecturer_sees_ranks_and_the_replay_on_the_projector(server: Server) -> None:
    challenge = open_challenge(server)["id"]
    names = ["Cy", "Di", "Ed"]
    for k, name in zip((0, 1, 2), names, strict=True):
        who = join(server, name)
        body = {"challenge": challenge, "code": code(SEED, k)}
        assert httpx.post(server.base + "/api/submit", json=body, headers=who, timeout=60)
    listed = httpx.get(server.base + "/api/entries", headers=server.lecturer).json()
    # Best first, ranked 1, 2, 3 (not the entries' numbers, which follow arrival).
    assert [e["rank"] for e in listed["entries"]] == [1, 2, 3]
    assert listed["showing"] is None
    entry = listed["entries"][1]["entry"]
    shown = httpx.post(server.base + "/api/show", json={"entry": entry}, headers=server.lecturer)
    assert shown.status_code == 200
    listed = httpx.get(server.base + "/api/entries", headers=server.lecturer).json()
    assert listed["showing"] == entry
    off = httpx.post(server.base + "/api/show", json={"entry": None}, headers=server.lecturer)
    assert off.json() == {"replay": None}
    assert (
        httpx.get(server.base + "/api/entries", headers=server.lecturer).json()["showing"] is None
    )


def test_the_projector_warns_of_a_loopback_join_address(server: Server) -> None:
    """Its fix is the command that started the server with --lan added: the same port and
    store (issue 49.6: `evapcool class --lan` alone made a new file and lecturer link)."""
    page = httpx.get(server.base + "/projector").text
    assert 'id="loopback"' in page
    port = server.base.rsplit(":", 1)[1]
    option = "--db" if isinstance(server.data, str) else "--data"
    store = html.escape(shlex.quote(_shown_store(str(server.data))))
    words = [("", "evapcool class"), ("", "--port"), (" value", port), ("", option)]
    words += [(" value", store), ("", "--workers"), (" value", "1"), ("", "--lan")]
    assert " ".join(f'<span class="command{k}">{w}</span>' for k, w in words) in page
    german = httpx.get(server.base + "/projector", headers={"Accept-Language": "de"}).text
    assert "Telefone erreichen diese Adresse nicht" in german


@pytest.mark.parametrize(
    ("url", "unreachable"),
    [
        ("http://127.0.0.1:8765/", True),
        ("http://127.4.5.6:8765/", True),
        ("http://localhost:8765/", True),
        ("http://[::1]:8765/", True),
        ("http://192.168.1.20:8765/", False),
        ("http://10.0.0.7:8765/", False),
        ("http://hall-pc.local:8765/", False),
    ],
)
def test_loopback_addresses_are_the_ones_phones_cannot_reach(url: str, unreachable: bool) -> None:
    assert loopback(url) is unreachable


# One store: the keep-alive is uvicorn's, whichever store answers.
@pytest.mark.parametrize("store_at", ["sqlite"], indirect=True)
def test_an_idle_connection_outlives_uvicorns_default_keep_alive(server: Server) -> None:
    """A connection idle past uvicorn's default 5 s still carries the next request: the server
    does not close it under a client that may be sending (class_cli.KEEP_ALIVE_SECONDS)."""
    address = urlsplit(server.base)
    conn = http.client.HTTPConnection(address.hostname or "", address.port, timeout=30)
    try:
        for wait in (0.0, 6.5):
            time.sleep(wait)
            conn.request("GET", "/api/leaderboard")
            answer = conn.getresponse()
            answer.read()
            assert answer.status == 200
    finally:
        conn.close()
