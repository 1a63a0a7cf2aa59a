"""Interleaved throughput benchmark of two versions of the fast engine (issue 17).

Runs the same measurement for an "old" and a "new" source tree in alternation
(old, new, new, old, ...), each run in a fresh process with that tree first on
PYTHONPATH, so that both versions see the same load on a shared machine, and
prints the median collisions per CPU second at each size.

    python scripts/bench_fast_interleaved.py --old 8ad6db0 --new HEAD
    python scripts/bench_fast_interleaved.py --old main --new .   # "." = this working tree

A side given as a git revision is checked out into a temporary `git worktree`
(removed afterwards); a side given as a directory is used as it is. Each side
gets its own Numba cache directory, warmed by one run before timing starts.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

# One run: collisions per CPU second over `frames` frames after a one-frame
# warm-up, at constant packing (radius = sqrt(10 000 / N)), H = 450, seed 1
# (the scaling table of `evapcool bench --only fast`). Public API only, so the
# same code measures any version.
RUN = """
import json, math, sys, time
from evapcool import Simulation
n, frames = int(sys.argv[1]), int(sys.argv[2])
sim = Simulation(n_atoms=n, radius=math.sqrt(10_000 / n), seed=1, trap_height=450.0,
                 engine="fast")
sim.advance(1.0)
c0 = sim.collision_count
t = time.process_time()
sim.advance(float(frames))
dt = time.process_time() - t
print(json.dumps({"collisions": sim.collision_count - c0, "seconds": dt}))
"""

# The classic start (49 atoms, R = 12, H = 450): median wall time of advance(1) per frame.
CLASSIC = """
import json, statistics, sys, time
from evapcool import Simulation
sim = Simulation(n_atoms=49, radius=12.0, seed=1, trap_height=450.0, engine="fast")
sim.advance(1.0)
times = []
for _ in range(int(sys.argv[1])):
    t = time.perf_counter()
    sim.advance(1.0)
    times.append(time.perf_counter() - t)
print(json.dumps({"ms": statistics.median(times) * 1e3}))
"""

#: atoms -> frames per run (about a second of work each at 1-1.5 M collisions/s; 49:
#: the classic start, frames whose median time is taken).
SIZES = {1_000: 300, 10_000: 30, 100_000: 3, 49: 900}


def _tree(spec: str, repo: Path, tmp: Path, label: str) -> tuple[Path, str]:
    """(source tree, description) for a revision or a directory."""
    if Path(spec).is_dir():
        path = Path(spec).resolve()
        rev = subprocess.run(["git", "-C", str(path), "rev-parse", "--short", "HEAD"],
                             capture_output=True, text=True).stdout.strip()  # fmt: skip
        dirty = subprocess.run(["git", "-C", str(path), "status", "--porcelain", "src"],
                               capture_output=True, text=True).stdout.strip()  # fmt: skip
        return path, f"{path} ({rev}{' + uncommitted changes' if dirty else ''})"
    rev = subprocess.run(["git", "-C", str(repo), "rev-parse", "--short", spec],
                         capture_output=True, text=True, check=True).stdout.strip()  # fmt: skip
    path = tmp / label
    subprocess.run(["git", "-C", str(repo), "worktree", "add", "--detach", str(path), rev],
                   check=True, capture_output=True)  # fmt: skip
    return path, f"{spec} ({rev})"


def _run(tree: Path, cache: Path, n: int, frames: int) -> dict[str, float]:
    """One run of RUN (or of CLASSIC for n = 49) in a fresh process."""
    # OPENBLAS_NUM_THREADS=1: neither engine uses BLAS, but numpy's BLAS threads spin for a
    # while after import, and that CPU time landed in whichever side started timing sooner.
    env = dict(os.environ, PYTHONPATH=str(tree / "src"), NUMBA_CACHE_DIR=str(cache),
               OPENBLAS_NUM_THREADS="1")  # fmt: skip
    args = [CLASSIC, str(frames)] if n == 49 else [RUN, str(n), str(frames)]
    out = subprocess.run([sys.executable, "-c", *args], env=env,
                         capture_output=True, text=True, check=True).stdout  # fmt: skip
    return json.loads(out.strip().splitlines()[-1])


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--old", default="main", help="git revision or directory (default: main)")
    p.add_argument("--new", default=".", help="git revision or directory (default: .)")
    p.add_argument("--runs", type=int, default=5, help="runs of each version per size")
    p.add_argument("--sizes", default="1000,10000,100000,49",
                   help="atom counts, comma-separated (49: the classic frame time)")  # fmt: skip
    args = p.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    repo = Path(__file__).resolve().parents[1]
    tmp = Path(tempfile.mkdtemp(prefix="evapcool-interleave-"))
    added = []
    try:
        sides = {}
        for label, spec in (("old", args.old), ("new", args.new)):
            tree, desc = _tree(spec, repo, tmp, label)
            if tree.parent == tmp:
                added.append(tree)
            sides[label] = (tree, tmp / f"cache-{label}", desc)
            print(f"{label}: {desc}", flush=True)
        for tree, cache, _ in sides.values():  # compile (or load) once, untimed
            _run(tree, cache, 200, 1)
        rates: dict[tuple[str, int], list[float]] = {}
        for k in range(args.runs):
            order = ("old", "new") if k % 2 == 0 else ("new", "old")
            for n in sizes:
                for label in order:
                    tree, cache, _ = sides[label]
                    r = _run(tree, cache, n, SIZES.get(n, max(2, 300_000 // n)))
                    value = r["ms"] if n == 49 else r["collisions"] / r["seconds"]
                    rates.setdefault((label, n), []).append(value)
            print(f"  round {k + 1}/{args.runs} done", file=sys.stderr, flush=True)
        print(f"collisions per CPU second, median of {args.runs} interleaved runs each:")
        print(f"{'atoms':>8} {'old':>12} {'new':>12} {'new/old':>8}   runs old | new (M)")
        for n in sizes:
            if n == 49:
                old = statistics.median(rates["old", n])
                new = statistics.median(rates["new", n])
                each = " ".join(f"{x:.4f}" for x in rates["old", n])
                each += " | " + " ".join(f"{x:.4f}" for x in rates["new", n])
                print(f"classic 49 atoms, ms physics per frame: old {old:.4f}, new {new:.4f}, "
                      f"new/old {new / old:.3f}   runs {each}")  # fmt: skip
                continue
            old = statistics.median(rates["old", n])
            new = statistics.median(rates["new", n])
            each = " ".join(f"{x / 1e6:.3f}" for x in rates["old", n])
            each += " | " + " ".join(f"{x / 1e6:.3f}" for x in rates["new", n])
            print(f"{n:>8,} {old:>12,.0f} {new:>12,.0f} {new / old:>8.3f}   {each}")
    finally:
        for tree in added:
            subprocess.run(["git", "-C", str(repo), "worktree", "remove", "--force", str(tree)],
                           capture_output=True)  # fmt: skip
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
