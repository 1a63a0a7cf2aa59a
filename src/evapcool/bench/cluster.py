"""[cluster] The Dask engine: speed-up of a 40-run sweep from 1 to 2 workers, per-run costs.

The clusters are started (and their workers warmed) before the clock starts: the figure is
the sweep itself. 1- and 2-worker sweeps are interleaved and repeated; medians are quoted
with the load average, since the machine is shared.
"""

from __future__ import annotations

import os
import statistics
import time

#: A representative lab run: 400 atoms of radius 4, a falling rim, 2400 frames (about 0.3 s).
RUN = dict(n_atoms=400, radius=4.0, schedule="400@0,60@2400", frames=2400, every=60,
           engine="fast", stop_at_win=False)  # fmt: skip
RUNS = 40
GAME = "425@0,162@1788"  # the best linear ramp of the classic game (docs/benchmarks.md)


def _runs() -> list[dict]:
    from dataclasses import asdict

    from evapcool.lab.experiment import LabConfig

    return [asdict(LabConfig(**RUN, seed=s).validated()) for s in range(1, RUNS + 1)]


def _noop(i: int) -> int:
    return i


def _sweep_seconds(
    workers: int, runs: list[dict], overhead_tasks: int = 0
) -> tuple[float, float, list[float], float]:
    """(seconds to start the cluster, seconds for the sweep, CPU seconds of each run,
    seconds per empty task when overhead_tasks > 0)."""
    from evapcool.lab.cluster import TaskError, connect, run_tasks
    from evapcool.lab.sweeps import run_one

    t0 = time.perf_counter()
    with connect(workers=workers) as engine:
        engine.client.wait_for_workers(workers)
        engine.client.run(lambda: None)  # every worker up and warmed
        t1 = time.perf_counter()
        cpu: list[float] = []

        def got(i: int, value: object) -> None:
            if isinstance(value, TaskError):
                raise RuntimeError(value.message)
            cpu.append(value[0]["cpu_seconds"])

        run_tasks(engine, run_one, [(r,) for r in runs], got)
        t2 = time.perf_counter()
        per_task = 0.0
        if overhead_tasks:
            run_tasks(engine, _noop, [(i,) for i in range(overhead_tasks)], lambda i, v: None)
            per_task = (time.perf_counter() - t2) / overhead_tasks
    return t1 - t0, t2 - t1, cpu, per_task


def _big_run_seconds() -> float:
    from evapcool.lab.experiment import run_experiment

    t = time.process_time()
    run_experiment(n_atoms=1500, radius=3.0, schedule="450@0,60@1800", frames=1800, every=60,
                   engine="fast", stop_at_win=False, seed=1)  # fmt: skip
    return time.process_time() - t


def _game_ms(n: int = 60) -> tuple[float, float]:
    """Median CPU ms of one classic game (1800 frames at most) for a ramp and for a policy."""
    from evapcool.game.autopilot import parse_strategy, play

    out = []
    for text in (GAME, "feedback:eta0=6,eta1=4.5,beta=0.5"):
        s = parse_strategy(text)
        play(s, 0)
        costs = []
        for seed in range(1, n + 1):
            t = time.process_time()
            play(s, seed)
            costs.append(time.process_time() - t)
        out.append(1000 * statistics.median(costs))
    return out[0], out[1]


def run(args) -> None:
    from evapcool.lab.cluster import MissingExtraError, require_extra

    try:
        require_extra("sweep")
    except MissingExtraError as exc:
        print(f"[cluster] {exc}")
        return
    repeats = 1 if getattr(args, "quick", False) else 3
    runs = _runs()
    load0 = os.getloadavg()
    print(f"[cluster] {RUNS}-run sweep ({RUN['n_atoms']} atoms, {RUN['frames']} frames each), "
          f"local cluster of 1 and 2 workers, {repeats} interleaved repeats")  # fmt: skip
    times: dict[int, list[float]] = {1: [], 2: []}
    starts: list[float] = []
    cpu: list[float] = []
    overhead: list[float] = []
    for _ in range(repeats):
        for workers in (1, 2):
            start, seconds, costs, per_task = _sweep_seconds(workers, runs, 1000 * (workers - 1))
            times[workers].append(seconds)
            starts.append(start)
            cpu.extend(costs)
            if per_task:
                overhead.append(per_task)
            print(f"  {workers} worker{'s' if workers > 1 else ' '}: {seconds:6.2f} s")
    one, two = statistics.median(times[1]), statistics.median(times[2])
    load1 = os.getloadavg()
    print(f"  median 1 worker {one:.2f} s, 2 workers {two:.2f} s: speed-up {one / two:.2f}x")
    print(f"  per run: median {statistics.median(cpu):.3f} s CPU; cluster start "
          f"(workers warmed) median {statistics.median(starts):.1f} s")  # fmt: skip
    print(f"  Dask overhead: {1000 * statistics.median(overhead):.2f} ms per empty task "
          "(1000 tasks, 2 workers)")  # fmt: skip
    big = _big_run_seconds()
    print(f"  a 1500-atom run (radius 3, 1800 frames): {big:.2f} s CPU")
    ramp, policy = _game_ms()
    print(f"  one classic game of up to 1800 frames (fast engine): ramp {ramp:.1f} ms, "
          f"closed-loop policy {policy:.1f} ms CPU (median of 60)")  # fmt: skip
    print(f"  load average before {load0[0]:.2f}, after {load1[0]:.2f} "
          f"({os.cpu_count()} cores)")  # fmt: skip
