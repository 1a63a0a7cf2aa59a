"""A department's servers while their PostgreSQL is away, really stopped and started again:
each request is answered at once (503, Retry-After, the catalog's words; not after the
pool's wait), the server says once that the database went and once that it came back, a
challenge whose time ran out meanwhile is closed once it is back, and games and boards flow
between the two processes again."""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import Iterator
from typing import Any

import httpx
import pytest
from classhelp import SEED, SETTINGS, Server, code, start_server
from pghelp import Postgres, running_postgres

pytestmark = pytest.mark.slow
#: A generous bound for the database to be found back and a board to arrive (no speed
#: asserted: the old behaviour took 30 s per request, and never recovered its timers).
WAIT = 30.0
AWAY = "No answer from the database"


@pytest.fixture
def postgres_of_its_own() -> Iterator[Postgres]:
    """A PostgreSQL this test may stop (the session's is shared)."""
    with running_postgres("evapcool-pg-away-") as running:
        yield running


def _class(server: Server) -> tuple[str, dict[str, str]]:
    """A new class's base URL on `server` and its lecturer's header."""
    admin = {"Authorization": f"Bearer {server.token}"}
    made = httpx.post(server.base + "/api/admin/lecturers", json={"name": "Ada"}, headers=admin)
    lecturer = {"Authorization": f"Bearer {made.json()['token']}"}
    room = httpx.post(server.base + "/api/classes", json={"name": "Hall"}, headers=lecturer)
    assert room.status_code == 200, room.text
    return f"/c/{room.json()['code']}", lecturer


def _challenge(url: str, lecturer: dict[str, str], **more: Any) -> int:
    body = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "seed": SEED, **more}
    opened = httpx.post(url + "/api/challenge", json=body, headers=lecturer)
    assert opened.status_code == 200, opened.text
    return int(opened.json()["id"])


def _open_in_database(url: str, challenge: int) -> int:
    import psycopg

    with psycopg.connect(url) as conn:
        row = conn.execute("SELECT open FROM challenge WHERE id = %s", (challenge,)).fetchone()
    assert row is not None
    return int(row[0])


async def _seen_on(url: str, name: str) -> None:
    """Follow a class's board stream until `name` is on it."""
    async with (
        httpx.AsyncClient(timeout=WAIT) as client,
        client.stream("GET", url + "/api/stream") as events,
    ):
        async for line in events.aiter_lines():
            if line.startswith("data: ") and name in _names(line):
                return


def _names(line: str) -> set[str]:
    return {e["name"] for e in json.loads(line[6:])["entries"]}


def test_the_database_away_and_back(postgres_of_its_own: Postgres) -> None:
    pg = postgres_of_its_own
    db = pg.new_database()
    first = start_server(db, extra=("--department",))
    second = start_server(db, token=first.token, extra=("--department",))
    try:
        base, lecturer = _class(first)
        a, b = first.base + base, second.base + base
        due = _challenge(a, lecturer, minutes=0.1)  # closes 6 s from now: while away
        pg.stop()
        started = time.monotonic()
        answers = [
            httpx.get(a + "/api/leaderboard", timeout=WAIT)
            if k % 2
            else httpx.post(a + "/api/join", json={"name": f"S{k}"}, timeout=WAIT)
            for k in range(12)
        ]
        # one wait for a connection (3 s) at most, then at once: not 12 x 30 s
        assert time.monotonic() - started < WAIT
        for answer in answers:
            assert answer.status_code == 503, answer.text
            assert answer.headers["retry-after"] == "5"
            assert answer.json()["error"]["message"].startswith("The class's database is not")
        time.sleep(max(0.0, 8.0 - (time.monotonic() - started)))  # the window has ended
        pg.start()
        deadline = time.monotonic() + WAIT
        while httpx.get(a + "/api/leaderboard", timeout=WAIT).status_code != 200:
            assert time.monotonic() < deadline, "the server did not find its database again"
            time.sleep(0.2)
        while _open_in_database(db, due):
            assert time.monotonic() < deadline, "the challenge due meanwhile was not closed"
            time.sleep(0.2)
        # a game sent to one process reaches the other's board stream
        challenge = _challenge(a, lecturer)
        joined = httpx.post(a + "/api/join", json={"name": "Back"})
        assert joined.status_code == 200, joined.text
        who = {"Authorization": f"Bearer {joined.json()['token']}"}

        async def send_and_watch() -> None:
            watching = asyncio.create_task(_seen_on(b, "Back"))
            await asyncio.sleep(0.5)
            game = {"challenge": challenge, "code": code(SEED, 1)}
            async with httpx.AsyncClient(timeout=WAIT) as client:
                sent = await client.post(a + "/api/submit", json=game, headers=who)
            assert sent.status_code == 200, sent.text
            await asyncio.wait_for(watching, WAIT)

        asyncio.run(send_and_watch())
    finally:
        said = {}
        for name, server in (("first", first), ("second", second)):
            server.proc.terminate()
            said[name] = server.proc.stdout.read() if server.proc.stdout else ""
            server.stop()
    assert said["first"].count(AWAY) == 1, said["first"]
    assert said["first"].count("The database answers again.") == 1, said["first"]
    assert "Traceback" not in said["first"] + said["second"], said
