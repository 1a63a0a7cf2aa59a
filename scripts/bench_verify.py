"""Verification cost per classic game (issue 22): replay of autopilot recordings, median ms.

Run: python scripts/bench_verify.py [GAMES]  (fast and reference engines interleaved).
"""

from __future__ import annotations

import statistics
import sys
import time

from evapcool.game.replay import Settings, record_autopilot, verify


def main() -> None:
    games = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    recs = [record_autopilot("demo", Settings(), seed=s, engine="fast") for s in range(games)]
    verify(recs[0], engine="fast")  # compile once
    cost: dict[str, list[float]] = {"fast": [], "reference": []}
    for rec in recs:
        for engine in cost:
            t = time.perf_counter()
            verify(rec, engine=engine)
            cost[engine].append((time.perf_counter() - t) * 1e3)
    frames = statistics.median(r.frames for r in recs)
    for engine, ms in cost.items():
        med = statistics.median(ms)
        print(
            f"{engine:>9}: median {med:.0f} ms per game ({frames:.0f} frames), "
            f"{1e3 / med:.1f} games/s on one core, n={len(ms)}"
        )


if __name__ == "__main__":
    main()
