"""The class server under a lecture hall's load (issue 22's benchmark; docs/benchmarks.md).

    python scripts/bench_class.py [--students 300] [--workers 2] [--spread 60] [--burst 50]
    python scripts/bench_class.py --flood [--tokens 40] [--games 12] [--workers 2]
    python scripts/bench_class.py --department [--classes 10] [--students 300] [--spread 120]
        [--arrivals burst,spread]
    python scripts/bench_class.py --department --kill [--classes 10] [--spread 120]
    python scripts/bench_class.py --debrief [--students 300] [--runs 5] [--workers 2]
    python scripts/bench_class.py --term [--classes 10] [--students 300] [--shared 3]
        [--spread 120] [--closing 60] [--kill]      (scripts/bench_term.py)

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

--department (issue 35): `--classes` classes of `--students` each on one department server:
one process with 2 verifying workers on SQLite, then 2 processes with 1 worker each on one
PostgreSQL (started in a temporary folder); every class has a projector on each process and
its students behind an address of their own (127.0.0.10 + class). Each setup runs a burst
(`--burst` games in flight: verified games per second) and games spread over `--spread`
seconds (p95 from submit to every projector of the class). --kill: the PostgreSQL spread
run, with the first process killed -9 halfway; its students send again to the other and
its projectors reconnect there; then every game acknowledged is looked for on its board,
and the killed process is restarted and asked the same.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import random
import statistics
import sys
import tempfile
import time
from dataclasses import dataclass
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


# -- a department: several classes, two processes over PostgreSQL (issue 35) ----------------


@dataclass
class Department:
    """Running department servers on one store, its classes and their students."""

    servers: list[Server]
    classes: list[dict]  # code, base, challenge, projector path (with key), students
    store: str


def start_department(store: Path | str, processes: int, workers: int) -> list[Server]:
    first = start_server(store, workers=workers, extra=("--department",))
    servers = [first]
    for _ in range(processes - 1):
        servers.append(
            start_server(store, workers=workers, token=first.token, extra=("--department",))
        )
    return servers


def hall(c: int) -> str:
    """The address class c's students and projector come from (a lecture hall's NAT)."""
    return f"127.0.0.{10 + c}"


async def join(
    client: httpx.AsyncClient, server: Server, room: dict, name: str
) -> tuple[str, dict[str, str]]:
    got = await client.post(server.base + room["base"] + "api/join", json={"name": name})
    return name, {"Authorization": f"Bearer {got.json()['token']}"}


async def setup_department(servers: list[Server], classes: int, names: list[str]) -> list[dict]:
    """A lecturer, `classes` classes each with an open challenge and every student joined."""
    first = servers[0]
    admin = {"Authorization": f"Bearer {first.token}"}
    async with httpx.AsyncClient(timeout=600) as client:
        made = await client.post(
            first.base + "/api/admin/lecturers", json={"name": "Bench"}, headers=admin
        )
        lecturer = {"Authorization": f"Bearer {made.json()['token']}"}
        out = []
        for c in range(classes):
            room = (
                await client.post(
                    first.base + "/api/classes", json={"name": f"Class {c}"}, headers=lecturer
                )
            ).json()
            base = f"/c/{room['code']}/"
            body = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius}
            body.update(escape=SETTINGS.escape, seed=SEED + c)  # games_of(c)'s start
            opened = await client.post(
                first.base + base + "api/challenge", json=body, headers=lecturer
            )
            out.append(
                {
                    "base": base,
                    "challenge": opened.json()["id"],
                    "projector": room["projector"],
                    "tokens": {},
                }
            )
    for c, room in enumerate(out):
        transport = httpx.AsyncHTTPTransport(local_address=hall(c))
        async with httpx.AsyncClient(timeout=600, transport=transport) as client:
            joined = await asyncio.gather(
                *(join(client, servers[i % len(servers)], room, n) for i, n in enumerate(names))
            )
            room["tokens"] = dict(joined)
    return out


async def follow(
    client: httpx.AsyncClient, servers: list[Server], s: int, path: str, seen: dict, stop
) -> None:
    """A projector on server s: note when each name first shows; on a lost connection
    reconnect (as EventSource does) to the next live server."""
    while not stop.is_set():
        server = servers[s % len(servers)]
        try:
            async with client.stream("GET", server.base + path) as events:
                async for line in events.aiter_lines():
                    if line.startswith("data: "):
                        now = time.perf_counter()
                        for e in json.loads(line[6:])["entries"]:
                            seen.setdefault(e["name"], now)
        except (httpx.TransportError, httpx.HTTPStatusError):
            pass
        s += 1  # the next process, as a proxy would send the reconnection elsewhere
        await asyncio.sleep(0.5)


async def department_run(dept: Department, entries, starts, gate: int, kill_at: float | None):
    """Every class's students send their games (entries[c]) at `starts` (each class the same
    moments, shifted); two projectors per class (one on each process). kill_at: seconds after the
    start to kill -9 the first process (its students and projectors go to the other)."""
    servers = dept.servers
    sent: dict = {}
    acked: dict = {}
    seen: list[list[dict]] = [[{} for _ in servers] for _ in dept.classes]
    bad: list[str] = []
    retried = [0]
    limit = asyncio.Semaphore(gate)
    dead: set[int] = set()
    stop = asyncio.Event()

    async def student(client, c, i, name, code, honest, at):
        room = dept.classes[c]
        await asyncio.sleep(max(0.0, at - (time.perf_counter() - t0)))
        async with limit:
            sent[c, name] = time.perf_counter()
            s = i % len(servers)
            while True:
                if s in dead:
                    s = (s + 1) % len(servers)
                try:
                    answer = await client.post(
                        servers[s].base + room["base"] + "api/submit",
                        headers=room["tokens"][name],
                        json={"challenge": room["challenge"], "code": code},
                    )
                    break
                except httpx.TransportError:
                    retried[0] += 1  # the page sends again, reaching the other process
                    s = (s + 1) % len(servers)
                    await asyncio.sleep(1.0)
            acked[c, name] = (time.perf_counter(), answer.status_code)
        if answer.status_code != (200 if honest else 422):
            bad.append(f"{c}/{name}: {answer.status_code} {answer.text[:80]}")

    async def killer():
        await asyncio.sleep(kill_at)
        servers[0].stop(kill=True)
        dead.add(0)

    clients = [
        httpx.AsyncClient(
            timeout=600,
            transport=httpx.AsyncHTTPTransport(local_address=hall(c)),
            limits=httpx.Limits(max_connections=gate + 20),
        )
        for c in range(len(dept.classes))
    ]
    try:
        watchers = [
            asyncio.create_task(
                follow(
                    clients[c],
                    servers,
                    s,
                    room["projector"].replace("/projector", "/api/stream"),
                    seen[c][s],
                    stop,
                )
            )
            for c, room in enumerate(dept.classes)
            for s in range(len(servers))
        ]
        await asyncio.sleep(1.0)
        t0 = time.perf_counter()
        tasks = [
            student(clients[c], c, i, n, code, h, at + c * 0.0137)
            for c in range(len(dept.classes))
            for i, ((n, code, h), at) in enumerate(zip(entries[c], starts, strict=True))
        ]
        if kill_at is not None:
            tasks.append(killer())
        await asyncio.gather(*tasks)
        took = time.perf_counter() - t0
        await asyncio.sleep(3.0)
        stop.set()
        for w in watchers:
            w.cancel()
    finally:
        for client in clients:
            await client.aclose()
    return sent, acked, seen, took, bad, retried[0]


def department_report(label: str, dept: Department, entries, result) -> dict:
    sent, acked, seen, took, bad, retried = result
    lag, missing = [], 0
    for c in range(len(dept.classes)):
        for n in (n for n, _, h in entries[c] if h):
            times = [s.get(n) for s in seen[c]]
            if any(t is None for t in times):
                missing += 1
                continue
            lag.append(max(times) - sent[c, n])
    ack = [acked[k][0] - sent[k] for k in acked]
    games = len(acked)
    print(
        f"{label}: {games} games in {took:.1f} s ({games / took:.1f}/s); submit->200 p50 "
        f"{quantile(ack, 0.5):.3f} s, p95 {quantile(ack, 0.95):.3f} s; submit->every projector "
        f"p50 {quantile(lag, 0.5):.3f} s, p95 {quantile(lag, 0.95):.3f} s "
        f"({len(lag)} seen, {missing} not on every projector); wrong answers {len(bad)}; "
        f"sent again after a lost connection {retried}",
        flush=True,
    )
    for line in bad[:5]:
        print("   ", line)
    return {"games_per_s": games / took, "p95": quantile(lag, 0.95) if lag else None}


def kept_after(dept: Department, acked: dict, server: Server) -> tuple[int, int]:
    """(games acknowledged 200, how many of them are on their class's board after)."""
    on_board = 0
    wanted = [k for k, (_, status) in acked.items() if status == 200]
    boards = {}
    for c, room in enumerate(dept.classes):
        answer = httpx.get(server.base + room["base"] + "api/leaderboard", timeout=60)
        boards[c] = {e["name"] for e in answer.json()["entries"]}
    for c, name in wanted:
        on_board += name in boards[c]
    return len(wanted), on_board


def department_bench(args: argparse.Namespace) -> None:
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from pghelp import start_postgres

    # A seed per class: the copy check spans the server, so two classes on one start could
    # not both send the same game.
    entries = [student_games(args.students, seed=SEED + c) for c in range(args.classes)]
    names = [n for n, _, _ in entries[0]]
    rng = random.Random(1)
    spread = sorted(rng.uniform(0, args.spread) for _ in names)
    burst = [0.0] * len(names)
    with (
        tempfile.TemporaryDirectory(prefix="evapcool-bench-") as tmp,
        tempfile.TemporaryDirectory(prefix="evapcool-pg-") as pg_folder,
    ):
        pg = start_postgres(Path(pg_folder))  # a folder of its own: the postgres user owns it
        try:
            runs = [
                ("SQLite, 1 process, 2 workers", None, 1, 2, burst, args.burst, None),
                ("SQLite, 1 process, 2 workers", None, 1, 2, spread, len(names), None),
                ("PostgreSQL, 2 processes, 1 worker each", pg, 2, 1, burst, args.burst, None),
                ("PostgreSQL, 2 processes, 1 worker each", pg, 2, 1, spread, len(names), None),
            ]
            runs = [r for r in runs if ("burst" if r[4] is burst else "spread") in args.arrivals]
            if args.kill:
                runs = [
                    (
                        "PostgreSQL, 2 processes, kill -9 of one",
                        pg,
                        2,
                        1,
                        spread,
                        len(names),
                        args.spread / 2,
                    )
                ]
            for n, (label, db, processes, workers, starts, gate, kill_at) in enumerate(runs):
                store = db.new_database() if db else str(Path(tmp) / f"dept{n}.sqlite")
                store_at: Path | str = store if db else Path(store)
                servers = start_department(store_at, processes, workers)
                try:
                    classes = asyncio.run(setup_department(servers, args.classes, names))
                    dept = Department(servers, classes, str(store))
                    time.sleep(2.0)
                    result = asyncio.run(department_run(dept, entries, starts, gate, kill_at))
                    arrivals = "burst" if starts is burst else f"spread over {args.spread:g} s"
                    department_report(f"{label}, {arrivals}", dept, entries, result)
                    if kill_at is not None:
                        wanted, kept = kept_after(dept, result[1], servers[1])
                        print(
                            f"  acknowledged 200: {wanted}; on their boards after the kill: {kept}"
                        )
                        again = start_server(
                            store_at,
                            workers=workers,
                            port=int(servers[0].base.rsplit(":", 1)[1]),
                            token=servers[0].token,
                            extra=("--department",),
                        )
                        servers[0] = again
                        wanted, kept = kept_after(dept, result[1], again)
                        print(f"  the killed process restarted: it shows {kept} of {wanted}")
                finally:
                    for server in servers:
                        server.stop()
        finally:
            pg.stop()


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
    p.add_argument("--department", action="store_true", help="classes on 2 processes (issue 35)")
    p.add_argument("--classes", type=int, default=10, help="classes at once (--department)")
    p.add_argument("--kill", action="store_true", help="kill -9 of one process (--department)")
    p.add_argument(
        "--arrivals", default="burst,spread", help="which runs (--department): burst, spread"
    )
    p.add_argument("--debrief", action="store_true", help="the debrief's first draw (issue 36)")
    p.add_argument("--runs", type=int, default=5, help="closes measured (--debrief)")
    p.add_argument("--term", action="store_true", help="a department's term (issue 46)")
    p.add_argument("--shared", type=int, default=3, help="classes behind one address (--term)")
    p.add_argument("--closing", type=float, default=60.0, help="seconds of closes (--term)")
    args = p.parse_args()
    if args.term:
        from bench_term import term_bench

        term_bench(args)
        return 0
    if args.flood:
        flood_bench(args)
        return 0
    if args.department:
        department_bench(args)
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
