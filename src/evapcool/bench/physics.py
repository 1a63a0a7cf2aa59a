"""Bench section 'physics': the classic 49-atom start, physics time per frame."""

from __future__ import annotations

import argparse
import statistics
import time

from evapcool import Simulation


def frame_times(engine: str, frames: int, seed: int = 1) -> tuple[list[float], int, float]:
    """Per-frame wall times (s) of advance(1) at the classic start, H = 450."""
    sim = Simulation.classic(seed=seed, engine=engine, trap_height=450.0)
    sim.advance(1.0)  # warm-up (compiles the fast engine if needed)
    c0 = sim.collision_count
    times = []
    for _ in range(frames):
        t = time.perf_counter()
        sim.advance(1.0)
        times.append(time.perf_counter() - t)
    return times, sim.collision_count - c0, sum(times)


def run(args: argparse.Namespace) -> None:
    """Print the median physics time per frame and collisions per second."""
    engine = args.engine
    frames = 300 if args.quick else 900
    times, collisions, total = frame_times(engine, frames)
    sim_engine = Simulation.classic(seed=1, engine=engine).engine
    med = statistics.median(times) * 1e3
    p95 = sorted(times)[int(0.95 * len(times))] * 1e3
    print(f"[physics] classic start (49 atoms, R = 12, H = 450), engine={sim_engine}")
    print(f"  physics time per frame: median {med:.3f} ms, p95 {p95:.3f} ms over {frames} frames")
    print(
        f"  collisions: {collisions} in {frames} frames = {collisions / frames:.1f} per frame, "
        f"{collisions / total:,.0f} per second of compute"
    )
