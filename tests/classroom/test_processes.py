"""Several server processes on one PostgreSQL (issue 35): a board changed by one process
reaches the streams of another (LISTEN/NOTIFY); rate limits and the copy check hold across
them; kill -9 of one keeps every acknowledged game and the other carries on."""

from __future__ import annotations

import asyncio
import json
import threading
from collections.abc import AsyncIterator, Iterator
from typing import Any

import httpx
import pytest
from classhelp import SEED, SETTINGS, Server, code, start_server
from pghelp import Postgres

#: A generous bound for a board to reach another process's stream (no speed asserted).
ARRIVES = 30.0


@pytest.fixture
def pair(postgres: Postgres) -> Iterator[tuple[Server, Server]]:
    """Two department servers on one new PostgreSQL database."""
    url = postgres.new_database()
    first = start_server(url, extra=("--department",))
    try:
        second = start_server(url, token=first.token, extra=("--department",))
    except BaseException:
        first.stop()
        raise
    yield first, second
    first.stop()
    second.stop()


def a_class(server: Server) -> tuple[str, dict[str, str], int]:
    """(the class's path, its lecturer's header, its open challenge) made through `server`."""
    admin = {"Authorization": f"Bearer {server.token}"}
    made = httpx.post(server.base + "/api/admin/lecturers", json={"name": "Ada"}, headers=admin)
    lecturer = {"Authorization": f"Bearer {made.json()['token']}"}
    room = httpx.post(server.base + "/api/classes", json={"name": "Big"}, headers=lecturer).json()
    base = f"/c/{room['code']}/"
    body = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "escape": SETTINGS.escape}
    opened = httpx.post(
        server.base + base + "api/challenge", json={**body, "seed": SEED}, headers=lecturer
    )
    assert opened.status_code == 200, opened.text
    return base, lecturer, int(opened.json()["id"])


def student(server: Server, base: str, name: str) -> dict[str, str]:
    joined = httpx.post(server.base + base + "api/join", json={"name": name})
    assert joined.status_code == 200, joined.text
    return {"Authorization": f"Bearer {joined.json()['token']}"}


async def _events(client: httpx.AsyncClient, url: str) -> AsyncIterator[dict[str, Any]]:
    async with client.stream("GET", url) as events:
        async for line in events.aiter_lines():
            if line.startswith("data: "):
                yield json.loads(line[6:])


async def _until(client: httpx.AsyncClient, url: str, names: set[str]) -> list[str]:
    """Follow a board's stream until every name is on it; the names seen then."""
    async for board in _events(client, url):
        seen = {e["name"] for e in board["entries"]}
        if names <= seen:
            return sorted(seen)
    raise AssertionError("the stream ended")


def test_a_game_acknowledged_by_one_process_reaches_the_others_projector(
    pair: tuple[Server, Server],
) -> None:
    one, two = pair
    base, _, challenge = a_class(one)
    who = student(two, base, "Far")
    code(SEED, 1)

    async def run() -> list[str]:
        async with httpx.AsyncClient(timeout=60) as client:
            watching = asyncio.create_task(_until(client, one.base + base + "api/stream", {"Far"}))
            await asyncio.sleep(0.5)  # the stream is open on process one
            sent = await client.post(
                two.base + base + "api/submit",
                json={"challenge": challenge, "code": code(SEED, 1)},
                headers=who,
            )
            assert sent.status_code == 200, sent.text
            return await asyncio.wait_for(watching, ARRIVES)

    assert asyncio.run(run()) == ["Far"]


def test_limits_and_the_copy_check_hold_across_processes(pair: tuple[Server, Server]) -> None:
    one, two = pair
    base, _, challenge = a_class(one)
    who = student(one, base, "Quick")
    # 8 submissions alternately to each process: one bucket of 5 refuses some; a bucket per
    # process (4 each) would refuse none.
    answers = [
        httpx.post(server.base + base + "api/submit", json={}, headers=who).status_code
        for server in (one, two) * 4
    ]
    assert 429 in answers, answers
    first, second = student(one, base, "First"), student(two, base, "Second")
    game = {"challenge": challenge, "code": code(SEED, 2)}
    sent = httpx.post(one.base + base + "api/submit", json=game, headers=first, timeout=60)
    assert sent.status_code == 200, sent.text
    copied = httpx.post(two.base + base + "api/submit", json=game, headers=second, timeout=60)
    assert copied.status_code == 422 and copied.json()["error"]["field"] == "code"


STUDENTS = 12
GAMES_EACH = 3
KILL_AFTER = 8


async def _flow(servers: tuple[Server, Server], base: str, students: list, challenge: int) -> dict:
    """Games sent to both processes at once (student i to process i % 2); kill -9 of the
    first after KILL_AFTER acknowledgements. The games acknowledged: entry -> name."""
    acked: dict[int, str] = {}
    enough = asyncio.Event()

    async def one(client: httpx.AsyncClient, i: int, g: int) -> None:
        server = servers[i % 2]
        body = {"challenge": challenge, "code": code(SEED, 1 + i * GAMES_EACH + g)}
        try:
            answer = await client.post(
                server.base + base + "api/submit", json=body, headers=students[i][1]
            )
        except httpx.TransportError:
            return
        if answer.status_code == 200:
            acked[answer.json()["entry"]] = students[i][0]
            if len(acked) >= KILL_AFTER:
                enough.set()

    async with httpx.AsyncClient(timeout=60) as client:
        tasks = [
            asyncio.create_task(one(client, i, g))
            for g in range(GAMES_EACH)
            for i in range(STUDENTS)
        ]
        await asyncio.wait_for(enough.wait(), 180)
        servers[0].stop(kill=True)
        await asyncio.gather(*tasks)
    return acked


def test_kill_9_of_one_process_keeps_every_game_and_the_other_carries_on(
    pair: tuple[Server, Server],
) -> None:
    one, two = pair
    for k in range(STUDENTS * GAMES_EACH + 2):
        code(SEED, k)
    base, lecturer, challenge = a_class(one)
    students = [(f"S{i}", student(one, base, f"S{i}")) for i in range(STUDENTS)]
    acked = asyncio.run(_flow((one, two), base, students, challenge))
    assert one.proc.returncode == -9 and len(acked) >= KILL_AFTER
    listed = httpx.get(two.base + base + "api/entries", headers=lecturer).json()["entries"]
    kept = {e["entry"]: e["name"] for e in listed}
    assert all(kept.get(entry) == name for entry, name in acked.items()), (acked, kept)
    # A projector that followed the killed process reconnects to the survivor: all there.
    on_board = {e["name"] for e in httpx.get(two.base + base + "api/leaderboard").json()["entries"]}
    assert set(acked.values()) <= on_board
    # The killed process restarted (same port) joins in: a game sent to the survivor
    # reaches its stream.
    port = one.base.rsplit(":", 1)[1]
    again = start_server(one.data, port=int(port), token=one.token, extra=("--department",))
    try:
        late = student(again, base, "Late")

        async def run() -> list[str]:
            async with httpx.AsyncClient(timeout=60) as client:
                watching = asyncio.create_task(
                    _until(client, again.base + base + "api/stream", {"Late"})
                )
                await asyncio.sleep(0.5)
                sent = await client.post(
                    two.base + base + "api/submit",
                    json={"challenge": challenge, "code": code(SEED, 0)},
                    headers=late,
                )
                assert sent.status_code == 200, sent.text
                return await asyncio.wait_for(watching, ARRIVES)

        assert "Late" in asyncio.run(run())
    finally:
        again.stop()


def test_processes_starting_together_make_the_schema_once(postgres: Postgres) -> None:
    from evapcool.classroom.pgstore import SCHEMA_VERSION, PostgresStore

    url = postgres.new_database()
    opened: list[PostgresStore] = []
    failed: list[BaseException] = []

    def start() -> None:
        try:
            opened.append(PostgresStore(url, 1))
        except BaseException as exc:  # the test reports it
            failed.append(exc)

    starting = [threading.Thread(target=start) for _ in range(4)]
    for thread in starting:
        thread.start()
    for thread in starting:
        thread.join(60)
    try:
        assert not failed and len(opened) == 4
        assert [r["id"] for r in opened[0].rooms()] == [1]
        versions = opened[0]._rows("SELECT version FROM schema_version")
        assert versions == [(SCHEMA_VERSION,)]
    finally:
        for store in opened:
            store.close()


def test_the_projectors_replay_and_the_debrief_hold_across_processes(
    pair: tuple[Server, Server],
) -> None:
    one, two = pair
    base, lecturer, challenge = a_class(one)
    who = student(one, base, "Shown")
    sent = httpx.post(
        one.base + base + "api/submit",
        json={"challenge": challenge, "code": code(SEED, 3)},
        headers=who,
        timeout=60,
    )
    assert sent.status_code == 200, sent.text
    entry = sent.json()["entry"]
    shown = httpx.post(two.base + base + "api/show", json={"entry": entry}, headers=lecturer)
    assert shown.status_code == 200, shown.text
    board = httpx.get(one.base + base + "api/leaderboard").json()
    assert board["replay"]["entry"] == entry and "code" not in board["replay"]
    hidden = httpx.post(two.base + base + "api/debrief", json={"anonymous": True}, headers=lecturer)
    assert hidden.status_code == 200, hidden.text
    board = httpx.get(one.base + base + "api/leaderboard").json()
    assert board["debrief"]["anonymous"] is True
    assert [e["name"] for e in board["entries"]] == [None]
