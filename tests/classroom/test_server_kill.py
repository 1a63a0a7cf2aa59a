"""kill -9 under load (issue 22.3): every acknowledged game survives, the challenge stays open."""

from __future__ import annotations

import asyncio
from pathlib import Path

import httpx
from classhelp import SEED, Server, code, join, open_challenge, start_server

STUDENTS = 12
GAMES_EACH = 3
#: Acknowledged games before the kill (the rest are in flight or not sent yet).
KILL_AFTER = 8


async def _submit_all(server: Server, students: list[dict[str, str]], challenge: object) -> dict:
    """Submit every game concurrently; kill -9 the server after KILL_AFTER acknowledgements."""
    acked: dict[int, int] = {}  # entry -> score
    enough = asyncio.Event()

    async def one(client: httpx.AsyncClient, who: dict[str, str], k: int) -> None:
        body = {"challenge": challenge, "code": code(SEED, k)}
        try:
            answer = await client.post(server.base + "/api/submit", json=body, headers=who)
        except httpx.TransportError:
            return
        if answer.status_code == 200:
            acked[answer.json()["entry"]] = answer.json()["score"]
            if len(acked) >= KILL_AFTER:
                enough.set()

    async with httpx.AsyncClient(timeout=60) as client:
        jobs = [
            one(client, who, 1 + i * GAMES_EACH + g)
            for i, who in enumerate(students)
            for g in range(GAMES_EACH)
        ]
        tasks = [asyncio.create_task(job) for job in jobs]
        await asyncio.wait_for(enough.wait(), 120)
        server.stop(kill=True)
        await asyncio.gather(*tasks)
    return acked


def test_acknowledged_games_survive_kill_9(tmp_path: Path) -> None:
    data = tmp_path / "class.sqlite"
    for i in range(STUDENTS * GAMES_EACH + 1):
        code(SEED, i)  # all games made before the server starts
    server = start_server(data)
    try:
        challenge = open_challenge(server)["id"]
        students = [join(server, f"Student {i}") for i in range(STUDENTS)]
        acked = asyncio.run(_submit_all(server, students, challenge))
    finally:
        server.stop(kill=True)
    assert server.proc.returncode == -9
    assert len(acked) >= KILL_AFTER
    again = start_server(data, token=server.token)
    try:
        assert httpx.get(again.base + "/api/challenge").json()["id"] == challenge
        listed = httpx.get(again.base + "/api/entries", headers=again.lecturer).json()
        kept = {e["entry"]: e["score"] for e in listed["entries"]}
        assert all(kept.get(entry) == score for entry, score in acked.items()), (acked, kept)
        print(f"\n{len(acked)} acknowledged before kill -9, {len(kept)} stored after restart")
        # the students' tokens still work after the restart
        answer = httpx.post(
            again.base + "/api/submit",
            headers=students[0],
            timeout=60,
            json={"challenge": challenge, "code": code(SEED, 0)},
        )
        assert answer.status_code == 200, answer.text
    finally:
        again.stop()
