"""300 students at once (issue 22.3): honest games all ranked, forged ones all refused.

Prints the 95th-percentile latency of submit -> 200 and of submit -> seen on the stream
(pytest -s); timing is measured, not asserted (shared machines vary).
"""

from __future__ import annotations

import asyncio
import statistics
import time
from pathlib import Path

import httpx
from classhelp import Server, open_challenge, start_server, student_games, watch_board

STUDENTS = 300
FORGED_EVERY = 10  # one student in ten claims more than their game gives
CONCURRENCY = 50


def games() -> list[tuple[str, str, bool]]:
    """(name, code, honest) of every student; honest ones are all different games."""
    return student_games(STUDENTS, FORGED_EVERY)


def p95(values: list[float]) -> float:
    return statistics.quantiles(values, n=20)[-1] if len(values) > 1 else values[0]


async def _run(server: Server, challenge: object, entries: list[tuple[str, str, bool]]) -> dict:
    sent: dict[str, float] = {}
    acked: dict[str, float] = {}
    seen: dict[str, float] = {}
    statuses: dict[str, int] = {}
    gate = asyncio.Semaphore(CONCURRENCY)

    async def student(client: httpx.AsyncClient, name: str, game: str) -> None:
        async with gate:
            joined = await client.post(server.base + "/api/join", json={"name": name})
            who = {"Authorization": f"Bearer {joined.json()['token']}"}
            sent[name] = time.perf_counter()
            answer = await client.post(
                server.base + "/api/submit",
                headers=who,
                json={"challenge": challenge, "code": game},
            )
            acked[name] = time.perf_counter()
            statuses[name] = answer.status_code

    limits = httpx.Limits(max_connections=CONCURRENCY + 10)
    async with httpx.AsyncClient(timeout=300, limits=limits) as client:
        watcher = asyncio.create_task(watch_board(client, server, seen))
        await asyncio.sleep(0.2)
        start = time.perf_counter()
        await asyncio.gather(*(student(client, n, g) for n, g, _ in entries))
        took = time.perf_counter() - start
        await asyncio.sleep(0.5)
        watcher.cancel()
    return {"sent": sent, "acked": acked, "seen": seen, "statuses": statuses, "took": took}


def test_three_hundred_students(tmp_path: Path) -> None:
    entries = games()
    server = start_server(tmp_path / "class.sqlite", workers=2)
    try:
        challenge = open_challenge(server)["id"]
        got = asyncio.run(asyncio.wait_for(_run(server, challenge, entries), 600))
        board = httpx.get(server.base + "/api/leaderboard").json()
    finally:
        server.stop()
    honest = {n for n, _, h in entries if h}
    forged = {n for n, _, h in entries if not h}
    assert all(got["statuses"][n] == 200 for n in honest)
    assert all(got["statuses"][n] == 422 for n in forged)
    assert {e["name"] for e in board["entries"]} == honest
    assert board["rejected"] == len(forged)
    to_ack = [got["acked"][n] - got["sent"][n] for n in honest]
    to_seen = [got["seen"][n] - got["sent"][n] for n in honest if n in got["seen"]]
    print(
        f"\n{STUDENTS} students in {got['took']:.1f} s: "
        f"{STUDENTS / got['took']:.1f} verified games/s; p95 submit->200 {p95(to_ack):.2f} s, "
        f"p95 submit->seen on the stream {p95(to_seen):.2f} s ({len(to_seen)} seen)"
    )
