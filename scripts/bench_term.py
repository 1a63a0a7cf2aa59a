"""A department's term (issue 46's benchmark; `python scripts/bench_class.py --term`).

`--classes` classes of `--students` phones on two server processes sharing one PostgreSQL
(1 verifying worker each); the first `--shared` classes are each a lecture hall behind one
address of its own (127.0.0.10 + c: every phone of the class shares it, as behind a NAT),
the others' phones each on an address of their own (127.0.1.x, 127.0.2.x, ...). Every phone
joins, follows its class's board on its token's stream, and sends one game at a moment
spread over `--spread` seconds (10 x 300 over 120 s: 25 games a second); a projector per
class on each process. Then every class closes within one minute (`--closing` seconds),
and each phone reads its debrief as soon as its stream says its class closed. --kill: the
first process killed -9 halfway through the closes (its phones go to the other).

Prints p95 submit -> every projector, the debrief's delay after its class's close (p95 and
the slowest), the honest calls refused (429, 5xx) and, with --kill, acknowledged games not
on their boards. Traffic goes to 127.0.0.0/8 only. The targets: p95 < 1 s at 25 games/s,
every debrief within 2 s of the close, 0 refusals, 0 acknowledged games lost.
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import json
import random
import re
import time
from collections import Counter
from typing import Any

import httpx
from classhelp import SEED, SETTINGS, Server, variant

from evapcool.game.replay import encode

#: The board's state when its round is closed, as the stream writes it (json.dumps).
CLOSED = re.compile(r'"open": false')


def games_of(c: int, students: int) -> list[str]:
    """Class c's games: different winning games on a seed of its own (the copy check spans
    the server, so two classes on one start could not both send the same game)."""
    wins = (rec for k in range(1, 10 * students + 1) if (rec := variant(SEED + c, k)).won)
    return [encode(rec) for _, rec in zip(range(students), wins, strict=False)]


def address(c: int, i: int, shared: int) -> str:
    """The address phone i of class c comes from."""
    return f"127.0.0.{10 + c}" if c < shared else f"127.{1 + i // 250}.{c}.{1 + i % 250}"


class Term:
    """The run's state: the servers, the classes, what was measured."""

    def __init__(self, servers: list[Server], classes: list[dict[str, Any]]) -> None:
        self.servers = servers
        self.classes = classes
        self.dead: set[int] = set()
        self.sent: dict[tuple[int, int], float] = {}
        self.acked: dict[tuple[int, int], int] = {}
        self.ack_after: list[float] = []
        self.joined = 0
        self.go = asyncio.Event()
        self.t0 = 0.0
        self.seen: list[list[dict[str, float]]] = [[{}, {}] for _ in classes]
        self.closed_at: dict[int, float] = {}
        self.debrief_after: list[float] = []
        self.closed_seen_after: list[float] = []  # the close -> the phone's stream said so
        self.debrief_fetch: list[float] = []  # the phone's GET of its debrief -> the answer
        self.debrief_answers: list[float] = []  # ... -> the answer's head (the server's part)
        self.debrief_bytes: list[int] = []  # the debriefs' bytes as sent (gzip)
        self.loop_lag: list[float] = []  # this process's loop, late by (during the closes)
        self.refused: Counter[str] = Counter()

    def base(self, s: int, c: int) -> str:
        while s % len(self.servers) in self.dead:
            s += 1
        return self.servers[s % len(self.servers)].base + self.classes[c]["base"]

    def count(self, what: str, status: int) -> None:
        if status == 429 or status >= 500:
            self.refused[f"{what} {status}"] += 1


async def open_classes(servers: list[Server], classes: int) -> tuple[list[dict], dict]:
    """A lecturer, `classes` classes each with a challenge open on a seed of its own."""
    admin = {"Authorization": f"Bearer {servers[0].token}"}
    async with httpx.AsyncClient(base_url=servers[0].base, timeout=600) as client:
        made = await client.post("/api/admin/lecturers", json={"name": "Term"}, headers=admin)
        lecturer = {"Authorization": f"Bearer {made.json()['token']}"}
        out = []
        for c in range(classes):
            room = (
                await client.post("/api/classes", json={"name": f"Class {c}"}, headers=lecturer)
            ).json()
            base = f"/c/{room['code']}/"
            rules = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius}
            rules.update(escape=SETTINGS.escape, seed=SEED + c)
            opened = await client.post(base + "api/challenge", json=rules, headers=lecturer)
            out.append(
                {"base": base, "challenge": opened.json()["id"], "projector": room["projector"]}
            )
    return out, lecturer


async def phone(term: Term, c: int, i: int, game: str, at: float, shared: int) -> None:
    """One phone: join, stream with its token, its game `at` seconds after every phone has
    joined (a class joins before it plays), its debrief at the close."""
    transport = httpx.AsyncHTTPTransport(local_address=address(c, i, shared))
    s = i % 2
    async with httpx.AsyncClient(timeout=600, transport=transport) as client:
        joined = await client.post(term.base(s, c) + "api/join", json={"name": f"P{i}"})
        term.count("join", joined.status_code)
        token = joined.json()["token"]
        head = {"Authorization": f"Bearer {token}"}
        closed = asyncio.Event()
        watching = asyncio.create_task(_watch(term, client, c, s, token, closed))
        term.joined += 1
        await term.go.wait()
        await asyncio.sleep(max(0.0, at - (time.perf_counter() - term.t0)))
        body = {"challenge": term.classes[c]["challenge"], "code": game}
        term.sent[c, i] = time.perf_counter()
        while True:
            try:
                answer = await client.post(term.base(s, c) + "api/submit", json=body, headers=head)
                break
            except httpx.TransportError:
                s += 1  # the page sends again; the proxy reaches the other process
        term.acked[c, i] = answer.status_code
        term.ack_after.append(time.perf_counter() - term.sent[c, i])
        term.count("submit", answer.status_code)
        await closed.wait()
        asked = time.perf_counter()
        term.closed_seen_after.append(asked - term.closed_at[c])
        while True:
            try:
                url = term.base(s, c) + "api/debrief"
                async with client.stream("GET", url, headers=head) as got:
                    term.debrief_answers.append(time.perf_counter() - asked)
                    # The bytes as sent: inflating a megabyte of JSON is a phone's own work,
                    # on its own CPU, not the server's (3 000 phones here share one process).
                    async for chunk in got.aiter_raw():
                        term.debrief_bytes.append(len(chunk))
                break
            except httpx.TransportError:
                s += 1
        term.count("debrief", got.status_code)
        term.debrief_after.append(time.perf_counter() - term.closed_at[c])
        term.debrief_fetch.append(time.perf_counter() - asked)
        watching.cancel()


async def _watch(term: Term, client, c: int, s: int, token: str, closed: asyncio.Event) -> None:
    """The phone's stream (its token's), reconnecting to the other process if one dies."""
    while True:
        try:
            url = term.base(s, c) + f"api/stream?token={token}"
            async with client.stream("GET", url) as events:
                term.count("stream", events.status_code)
                async for line in events.aiter_lines():
                    # A phone's own work, not the server's: 3000 phones in one process parse
                    # only the board's state, not its 300 entries.
                    if line.startswith("data: ") and CLOSED.search(line):
                        closed.set()  # only the lecturer closes it
        except httpx.TransportError:
            s += 1
            await asyncio.sleep(0.5)


async def projector(term: Term, c: int, s: int, shared: int) -> None:
    """Class c's projector on process s: when each phone's name first shows."""
    transport = httpx.AsyncHTTPTransport(local_address=address(c, 0, shared))
    async with httpx.AsyncClient(timeout=600, transport=transport) as client:
        while True:
            try:
                path = term.classes[c]["projector"].replace("/projector", "/api/stream")
                async with client.stream("GET", term.servers[s].base + path) as events:
                    async for line in events.aiter_lines():
                        if line.startswith("data: "):
                            now = time.perf_counter()
                            for e in json.loads(line[6:])["entries"]:
                                term.seen[c][s].setdefault(e["name"], now)
            except httpx.TransportError:
                await asyncio.sleep(0.5)
                if s in term.dead:
                    return


async def loop_lag(term: Term) -> None:
    """How late this process's own loop wakes (every 10 ms) while the classes close: the
    phones' delays include it, as a real phone's would not."""
    while True:
        due = time.perf_counter() + 0.01
        await asyncio.sleep(0.01)
        term.loop_lag.append(max(0.0, time.perf_counter() - due))


async def closes(term: Term, lecturer: dict, closing: float, kill: bool) -> None:
    """Every class closed within `closing` seconds; --kill: process 0 killed halfway."""
    gap = closing / max(1, len(term.classes))
    async with httpx.AsyncClient(timeout=600) as client:
        for c in range(len(term.classes)):
            if kill and c == len(term.classes) // 2:
                term.servers[0].stop(kill=True)
                term.dead.add(0)
            term.closed_at[c] = time.perf_counter()  # the debrief's delay counts from here
            answer = await client.post(term.base(1, c) + "api/challenge/close", headers=lecturer)
            term.count("close", answer.status_code)
            await asyncio.sleep(gap)


async def run(
    term: Term, lecturer: dict, games: list[list[str]], args: argparse.Namespace
) -> float:
    """The term's minute: phones, projectors, games, closes; the games' seconds."""
    rng = random.Random(1)
    projectors = [
        asyncio.create_task(projector(term, c, s, args.shared))
        for c in range(len(term.classes))
        for s in range(len(term.servers))
    ]
    phones = [
        asyncio.create_task(phone(term, c, i, game, rng.uniform(0, args.spread), args.shared))
        for c, class_games in enumerate(games)
        for i, game in enumerate(class_games)
    ]
    while term.joined < len(phones):
        await asyncio.sleep(0.2)
    await asyncio.sleep(2.0)  # the streams' first boards
    t0 = term.t0 = time.perf_counter()
    before = cpu_seconds()
    # 3 000 phones' objects in one process: a full collection over them stopped this loop
    # for a second and more, which no real phone does to another. Kept out of the scans.
    gc.freeze()
    term.go.set()
    while len(term.acked) < len(phones):
        await asyncio.sleep(0.5)
    took = time.perf_counter() - t0
    used = {k: v - before[k] for k, v in cpu_seconds().items()}
    print(
        f"CPU in the games' {took:.0f} s (2 cores: {2 * took:.0f} s): "
        + ", ".join(f"{k} {v:.0f} s" for k, v in used.items()),
        flush=True,
    )
    await asyncio.sleep(2.0)
    lag = asyncio.create_task(loop_lag(term))
    await closes(term, lecturer, args.closing, args.kill)
    await asyncio.gather(*phones)
    lag.cancel()
    for task in projectors:
        task.cancel()
    return took


def cpu_seconds() -> dict[str, float]:
    """CPU seconds so far of the servers (with their verifying workers), PostgreSQL and this
    process (the phones and projectors): who used the two cores."""
    import os
    import resource

    tick = os.sysconf("SC_CLK_TCK")
    mine = os.getpid()
    out = {"servers": 0.0, "postgres": 0.0}
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/stat") as f:
                stat = f.read()
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                cmd = f.read()
        except OSError:
            continue
        fields = stat.rsplit(")", 1)[1].split()
        used = (int(fields[11]) + int(fields[12])) / tick
        if b"postgres" in cmd:
            out["postgres"] += used
        elif b"evapcool" in cmd or b"multiprocessing" in cmd:
            out["servers"] += used if int(pid) != mine else 0.0
    usage = resource.getrusage(resource.RUSAGE_SELF)
    out["phones"] = usage.ru_utime + usage.ru_stime
    return out


def report(term: Term, took: float) -> None:
    from bench_class import quantile

    lag, missing = [], 0
    alive = [s for s in range(len(term.servers)) if s not in term.dead]
    for (c, i), at in term.sent.items():
        if term.acked.get((c, i)) != 200:
            continue
        times = [term.seen[c][s].get(f"P{i}") for s in alive]
        if None in times:
            missing += 1
        else:
            lag.append(max(t for t in times if t is not None) - at)
    games = len(term.acked)
    after = term.debrief_after
    print(
        f"{games} games in {took:.1f} s ({games / took:.1f}/s); submit->200 p50 "
        f"{quantile(term.ack_after, 0.5):.3f} s, p95 {quantile(term.ack_after, 0.95):.3f} s; "
        f"submit->every projector p50 {quantile(lag, 0.5):.3f} s, p95 "
        f"{quantile(lag, 0.95):.3f} s ({missing} not seen on every projector); debrief after "
        f"the close p95 {quantile(after, 0.95):.2f} s, slowest {max(after):.2f} s; honest calls "
        f"refused: {sum(term.refused.values())} {dict(term.refused)}",
        flush=True,
    )
    seen, fetch = term.closed_seen_after, term.debrief_fetch
    print(
        f"  of the debrief's delay: the close -> the phone's stream says so p50 "
        f"{quantile(seen, 0.5):.2f} s, p95 {quantile(seen, 0.95):.2f} s, "
        f"slowest {max(seen):.2f} s; "
        f"the phone's GET -> its debrief p50 {quantile(fetch, 0.5):.2f} s, p95 "
        f"{quantile(fetch, 0.95):.2f} s, slowest {max(fetch):.2f} s (its head p95 "
        f"{quantile(term.debrief_answers, 0.95):.2f} s); "
        f"{sum(term.debrief_bytes) / max(1, len(fetch)) / 1e3:.0f} kB a debrief as sent; "
        f"the phones' own loop late by p95 {quantile(term.loop_lag, 0.95):.3f} s, most "
        f"{max(term.loop_lag):.2f} s",
        flush=True,
    )
    if term.dead:
        survivor = next(s for s in range(len(term.servers)) if s not in term.dead)
        wanted = lost = 0
        for c, room in enumerate(term.classes):
            url = term.servers[survivor].base + room["base"] + "api/leaderboard"
            names = {e["name"] for e in httpx.get(url, timeout=60).json()["entries"]}
            for (cc, i), status in term.acked.items():
                if cc == c and status == 200:
                    wanted += 1
                    lost += f"P{i}" not in names
        print(f"  acknowledged 200: {wanted}; not on their boards after the kill: {lost}")


def term_bench(args: argparse.Namespace) -> None:
    """Two processes on a PostgreSQL of their own in a temporary folder (see the top)."""
    import tempfile
    from pathlib import Path

    from bench_class import start_department
    from pghelp import start_postgres

    games = [games_of(c, args.students) for c in range(args.classes)]
    with tempfile.TemporaryDirectory(prefix="evapcool-pg-") as folder:
        pg = start_postgres(Path(folder))
        try:
            servers = start_department(pg.new_database(), 2, 1)
            try:
                classes, lecturer = asyncio.run(open_classes(servers, args.classes))
                term = Term(servers, classes)
                took = asyncio.run(run(term, lecturer, games, args))
                report(term, took)
            finally:
                for server in servers:
                    server.stop()
        finally:
            pg.stop()
