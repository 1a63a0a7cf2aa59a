"""The class server under a lecture hall's load (issue 22's benchmark; docs/benchmarks.md).

    python scripts/bench_class.py [--students 300] [--workers 2] [--spread 60] [--burst 50]
    python scripts/bench_class.py --flood [--tokens 40] [--games 12] [--workers 2]
    python scripts/bench_class.py --debrief [--students 300] [--runs 5] [--workers 2]

Starts a real `evapcool class` on 127.0.0.1, opens a challenge, lets every student join,
then sends one game per student (real recordings of the autopilot, perturbed so that each
is a different game, one in ten forged): once as a burst (`--burst` students at a time, as
the load test does), once spread over `--spread` seconds (students finishing at random
moments of a minute, as in a lecture). Prints verified games per second and the p50/p95
latency from submit to the acknowledgement and to the leaderboard's stream. Traffic goes to
127.0.0.1 only.

--flood (issue 33): one address (127.0.0.1) floods the verifier with the longest games the
challenge allows (claiming a win they never reach, so each is replayed to its last frame)
from `--tokens` student tokens, each keeping as many in flight as it may; meanwhile an
honest student on another address (127.0.0.2, loopback too) sends `--games` games one
after another. Prints the median and spread of the honest acknowledgement time, idle and
under the flood, and their ratio (target: within 3x).
"""

from __future__ import annotations

import argparse
import asyncio
import random
import statistics
import sys
import tempfile
import time
from pathlib import Path

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from classhelp import (
    SEED,
    SETTINGS,
    Server,
    open_challenge,
    start_server,
    student_games,
    variant,
    watch_board,
)

from evapcool.game.replay import Recording, encode

#: The honest student's address: another computer, as the server sees it (loopback).
HONEST_ADDRESS = "127.0.0.2"


def quantile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


async def send_all(server: Server, challenge: object, entries, starts: list[float], gate: int):
    """Each student joins, waits for its start time, submits; returns the timings."""
    sent: dict[str, float] = {}
    acked: dict[str, float] = {}
    seen: dict[str, float] = {}
    bad: list[str] = []
    limit = asyncio.Semaphore(gate)

    async def join(client: httpx.AsyncClient, name: str) -> dict[str, str]:
        joined = await client.post(server.base + "/api/join", json={"name": name})
        return {"Authorization": f"Bearer {joined.json()['token']}"}

    async def student(client: httpx.AsyncClient, name: str, code: str, honest: bool, at: float):
        who = tokens[name]
        await asyncio.sleep(max(0.0, at - (time.perf_counter() - t0)))
        async with limit:
            sent[name] = time.perf_counter()
            answer = await client.post(
                server.base + "/api/submit",
                headers=who,
                json={"challenge": challenge, "code": code},
            )
            acked[name] = time.perf_counter()
        if answer.status_code != (200 if honest else 422):
            bad.append(f"{name}: {answer.status_code}")

    limits = httpx.Limits(max_connections=gate + 20)
    async with httpx.AsyncClient(timeout=600, limits=limits) as client:
        # Everyone joins first (names are picked before games end); then the clock runs.
        names = [n for n, _, _ in entries]
        tokens = dict(
            zip(names, await asyncio.gather(*(join(client, n) for n in names)), strict=True)
        )
        watcher = asyncio.create_task(watch_board(client, server, seen))
        await asyncio.sleep(0.3)
        t0 = time.perf_counter()
        await asyncio.gather(
            *(student(client, n, c, h, at) for (n, c, h), at in zip(entries, starts, strict=True))
        )
        took = time.perf_counter() - t0
        await asyncio.sleep(1.0)
        watcher.cancel()
    return sent, acked, seen, took, bad


def report(label: str, entries, result) -> None:
    sent, acked, seen, took, bad = result
    honest = [n for n, _, h in entries if h]
    ack = [acked[n] - sent[n] for n in honest]
    board = [seen[n] - sent[n] for n in honest if n in seen]
    print(
        f"{label}: {len(entries)} games in {took:.1f} s; "
        f"submit->200 p50 {quantile(ack, 0.5):.3f} s, p95 {quantile(ack, 0.95):.3f} s; "
        f"submit->leaderboard p50 {quantile(board, 0.5):.3f} s, p95 {quantile(board, 0.95):.3f} s"
        f" ({len(board)}/{len(honest)} seen); wrong answers: {len(bad)}"
    )


async def honest_games(
    server: Server, challenge: object, codes: list[str], first: int = 0
) -> list[float]:
    """Seconds from submit to 200 of each code, one after another, each by a new student
    on HONEST_ADDRESS."""
    took = []
    transport = httpx.AsyncHTTPTransport(local_address=HONEST_ADDRESS)
    async with httpx.AsyncClient(timeout=600, transport=transport) as client:
        for i, code in enumerate(codes):
            name = f"Honest {first + i}"
            joined = await client.post(server.base + "/api/join", json={"name": name})
            who = {"Authorization": f"Bearer {joined.json()['token']}"}
            body = {"challenge": challenge, "code": code}
            start = time.perf_counter()
            answer = await client.post(server.base + "/api/submit", headers=who, json=body)
            took.append(time.perf_counter() - start)
            if answer.status_code != 200:
                raise SystemExit(f"honest game refused: {answer.text}")
            await asyncio.sleep(0.2)
    return took


async def flood(server: Server, challenge: object, code: str, tokens: int, stop) -> dict:
    """Keep the verifier busy from 127.0.0.1 until `stop` is set; counts of the answers."""
    counts: dict[int, int] = {}
    limits = httpx.Limits(max_connections=4 * tokens)
    async with httpx.AsyncClient(timeout=600, limits=limits) as client:
        heads = []
        for i in range(tokens):
            joined = await client.post(server.base + "/api/join", json={"name": f"Flood {i}"})
            heads.append({"Authorization": f"Bearer {joined.json()['token']}"})

        async def one(head: dict[str, str]) -> None:
            body = {"challenge": challenge, "code": code}
            while not stop.is_set():
                answer = await client.post(server.base + "/api/submit", headers=head, json=body)
                counts[answer.status_code] = counts.get(answer.status_code, 0) + 1
                if answer.status_code == 429:
                    await asyncio.sleep(min(float(answer.headers.get("retry-after", 1)), 1.0))

        await asyncio.gather(*(one(head) for head in heads for _ in range(2)))
    return counts


async def flood_run(server: Server, challenge: dict, codes: list[str], tokens: int):
    """The honest times idle, then under the flood."""
    idle = await honest_games(server, challenge["id"], codes[: len(codes) // 2])
    longest = int(challenge["max_frames"])
    height = variant(SEED, 0).moves[0][0]
    slow = encode(Recording(SETTINGS, SEED, ((height, longest),), True, 20, longest))
    stop = asyncio.Event()
    flooding = asyncio.create_task(flood(server, challenge["id"], slow, tokens, stop))
    await asyncio.sleep(3.0)  # the queue fills
    half = len(codes) // 2
    loaded = await honest_games(server, challenge["id"], codes[half:], first=half)
    stop.set()
    counts = await flooding
    return idle, loaded, counts, longest


def flood_bench(args: argparse.Namespace) -> None:
    codes = [c for _, c, honest in student_games(2 * args.games + 4) if honest][: 2 * args.games]
    with tempfile.TemporaryDirectory() as tmp:
        server = start_server(Path(tmp) / "class.sqlite", workers=args.workers)
        try:
            challenge = open_challenge(server)
            time.sleep(2.0)
            idle, loaded, counts, longest = asyncio.run(
                flood_run(server, challenge, codes, args.tokens)
            )
        finally:
            server.stop()

    def spread(xs: list[float]) -> str:
        ms = [x * 1000 for x in xs]
        return f"median {statistics.median(ms):.0f} ms (min {min(ms):.0f}, max {max(ms):.0f})"

    print(f"longest allowed game: {longest} frames; flood answers by status: {counts}")
    print(f"honest acknowledgement, idle ({len(idle)} games): {spread(idle)}")
    print(f"honest acknowledgement, under the flood ({len(loaded)} games): {spread(loaded)}")
    print(f"ratio of medians: {statistics.median(loaded) / statistics.median(idle):.2f}x")


async def send_codes(server: Server, challenge: object, tokens: list[str], codes: list[str]) -> int:
    """Each student (a token) sends their code, 50 at a time; the games accepted."""
    limit = asyncio.Semaphore(50)

    async def one(client: httpx.AsyncClient, token: str, code: str) -> bool:
        async with limit:
            answer = await client.post(
                server.base + "/api/submit",
                headers={"Authorization": f"Bearer {token}"},
                json={"challenge": challenge, "code": code},
            )
            return answer.status_code == 200

    async with httpx.AsyncClient(timeout=600) as client:
        done = await asyncio.gather(
            *(one(client, t, c) for t, c in zip(tokens, codes, strict=True))
        )
    return sum(done)


def debrief_bench(args: argparse.Namespace) -> None:
    """Close-to-first-draw of the projector's debrief, `args.runs` times; prints the median."""
    import json
    import re
    import subprocess

    web = Path(__file__).resolve().parents[1] / "web"
    codes = [code for _, code, _ in student_games(args.students, forged_every=10**9)]
    took: list[float] = []
    with tempfile.TemporaryDirectory() as tmp:
        server = start_server(Path(tmp) / "class.sqlite", workers=args.workers)
        try:
            page = httpx.get(server.base + "/lecturer", params={"token": server.token}).text
            found = re.search(r'href="/projector\?key=([0-9a-f]+)"', page)
            assert found, "no projector link on the lecturer's page"
            names = [f"Student {i:03d}" for i in range(len(codes))]
            tokens = [
                httpx.post(server.base + "/api/join", json={"name": n}).json()["token"]
                for n in names
            ]
            for run in range(args.runs):
                challenge = open_challenge(server)["id"]
                time.sleep(2.0)
                taken = asyncio.run(send_codes(server, challenge, tokens, codes))
                # Two variants may share their moves up to the win: a copy, refused.
                assert taken >= 0.99 * len(codes), f"{taken} of {len(codes)} games taken"
                cmd = ["node", "test/e2e/bench-debrief.mjs", server.base, found.group(1)]
                proc = subprocess.Popen(cmd, cwd=web, stdout=subprocess.PIPE, text=True)
                assert proc.stdout is not None and proc.stdout.readline().strip() == "ready"
                close_at = time.time() * 1000.0
                httpx.post(server.base + "/api/challenge/close", headers=server.lecturer)
                got = json.loads(proc.stdout.readline())
                proc.wait(60)
                took.append((got["drawn_at"] - close_at) / 1000.0)
                print(
                    f"run {run + 1}: {got['curves']} curves drawn {took[-1]:.3f} s after the close"
                )
        finally:
            server.stop()
    print(
        f"debrief, {args.students} games: close -> first draw "
        f"median {statistics.median(took):.3f} s "
        f"(min {min(took):.3f}, max {max(took):.3f}, {len(took)} runs)"
    )


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--students", type=int, default=300)
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--spread", type=float, default=60.0)
    p.add_argument("--burst", type=int, default=50)
    p.add_argument("--flood", action="store_true", help="the flood benchmark (issue 33)")
    p.add_argument("--tokens", type=int, default=40, help="flooding tokens (--flood)")
    p.add_argument("--games", type=int, default=12, help="honest games idle and flooded")
    p.add_argument("--debrief", action="store_true", help="the debrief's first draw (issue 36)")
    p.add_argument("--runs", type=int, default=5, help="closes measured (--debrief)")
    args = p.parse_args()
    if args.flood:
        flood_bench(args)
        return 0
    if args.debrief:
        debrief_bench(args)
        return 0
    entries = student_games(args.students)
    rng = random.Random(1)
    for label, starts, gate in (
        (f"burst of {args.burst} at a time", [0.0] * args.students, args.burst),
        (
            f"spread over {args.spread:g} s",
            sorted(rng.uniform(0, args.spread) for _ in entries),
            args.students,
        ),
    ):
        with tempfile.TemporaryDirectory() as tmp:
            server = start_server(Path(tmp) / "class.sqlite", workers=args.workers)
            try:
                challenge = open_challenge(server)["id"]
                time.sleep(2.0)  # the workers' engines warm before the first game
                result = asyncio.run(send_all(server, challenge, entries, starts, gate))
            finally:
                server.stop()
        report(label, entries, result)
        if label.startswith("burst"):
            print(f"  verified games per second (burst): {args.students / result[3]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
