"""Golden traces: the golden cases (test fixtures: their starts and schedules), and a tool to
write, check or make the event traces the web engine must replay bit for bit.

    python scripts/golden_traces.py write            # web/test/golden/*.json from the reference
                                                     # engine; the fast engine must agree
    python scripts/golden_traces.py check            # the committed traces still match (exit 1
                                                     # naming the ones that do not)
    python scripts/golden_traces.py run STATE.json --events N [--engine fast]
                                                     # any state: its trace on stdout

`npm run replay -- STATE.json --events N` (in web/) prints the web engine's trace of the same
state in the same format: `diff` the two. See docs/state.md.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from evapcool.fileio import atomic_write_text
from evapcool.physics.loading import cell_centres
from evapcool.physics.simulation import Simulation
from evapcool.physics.state import read_json, to_state
from evapcool.physics.trace import make_trace, replay, trace_text

GOLDEN_DIR = Path(__file__).resolve().parents[1] / "web" / "test" / "golden"


# -- the golden cases ----------------------------------------------------------------------
@dataclass(frozen=True)
class GoldenCase:
    name: str
    description: str
    start: Callable[[], dict[str, Any]]
    height_of_frame: Callable[[int], float] | None = None
    events: int = 2000
    #: (time, height): the rim moves at once at these times, inside a frame
    height_changes: tuple[tuple[float, float], ...] = ()


def _one_atom(x: float, y: float, vx: float, vy: float, height: float = 450.0) -> dict[str, Any]:
    sim = Simulation(
        n_atoms=1, radius=12.0, positions=[[x, y]], velocities=[[vx, vy]],
        trap_height=height, engine="reference",
    )  # fmt: skip
    return to_state(sim)


def _grazing() -> dict[str, Any]:
    a, x = 0.01, 50.0
    norm = math.hypot(1.0, 2 * a * x)
    return _one_atom(x, a * x * x + 1e-9, 3.0 / norm, 3.0 * 2 * a * x / norm)


def _two_atoms() -> dict[str, Any]:
    sim = Simulation(
        n_atoms=2, radius=[12.0, 8.0], mass=[1.0, 3.0],
        positions=[[-14.0, 3.0], [8.0, 2.0]], velocities=[[1.5, 0.5], [-1.0, 0.2]],
        engine="reference",
    )  # fmt: skip
    return to_state(sim)


def _mixed(n: int = 200, seed: int = 11) -> dict[str, Any]:
    """n atoms of radii 4-8 px and masses 0.5-4 on cells of the largest radius."""
    rng = np.random.default_rng(seed)
    centres = cell_centres(n, 8.0, 0.01, 700.0)
    radius = rng.uniform(4.0, 8.0, n)
    mass = rng.uniform(0.5, 4.0, n)
    speed = rng.uniform(2.0, 6.0, n)
    theta = rng.uniform(0.0, 2 * math.pi, n)
    sim = Simulation(
        n_atoms=n, radius=radius, mass=mass, positions=centres,
        velocities=np.column_stack((speed * np.cos(theta), speed * np.sin(theta))),
        engine="reference",
    )  # fmt: skip
    return to_state(sim)


def _mirror(seed: int = 9) -> dict[str, Any]:
    """The classic cells with mirror-image atoms (x -> -x): many events tie exactly, so the
    order of ties (solo by index, pairs by (lower, higher) index) decides the run."""
    rng = np.random.default_rng(seed)
    centres = cell_centres(49, 12.0, 0.01, 532.0)
    pos = centres.copy()
    vel = np.zeros_like(pos)
    for i, (x, y) in enumerate(centres):
        if x < 0.0:
            continue
        dx, dy = rng.uniform(-5.0, 5.0, 2)
        speed, theta = rng.uniform(3.0, 6.0), rng.uniform(0.0, 2 * math.pi)
        v = (speed * math.cos(theta), speed * math.sin(theta))
        if x == 0.0:
            pos[i] = (x, y + dy)
            vel[i] = (0.0, v[1])
            continue
        m = int(np.flatnonzero((centres[:, 0] == -x) & (centres[:, 1] == y))[0])
        pos[i], vel[i] = (x + dx, y + dy), v
        pos[m], vel[m] = (-(x + dx), y + dy), (-v[0], v[1])
    sim = Simulation(n_atoms=49, positions=pos, velocities=vel, engine="reference")
    return to_state(sim)


def _ties_now() -> dict[str, Any]:
    """Events due at once at the start, all at t = 0: two touching pairs closing in and two
    centres on the wall moving outwards. The reference order: the solo events by index,
    then the pairs by (lower, higher) index."""
    a = 0.01
    pos = [[-40.0, 60.0], [-16.0, 60.0], [40.0, 60.0], [64.0, 60.0], [10.0, a * 10.0 * 10.0],
           [-30.0, a * -30.0 * -30.0], [0.0, 120.0]]  # fmt: skip
    vel = [[1.0, 0.0], [-1.0, 0.0], [1.0, 0.0], [-1.0, 0.0], [1.0, -1.0], [-1.0, -1.0],
           [0.5, 2.0]]  # fmt: skip
    return to_state(Simulation(n_atoms=7, positions=pos, velocities=vel, engine="reference"))


def _classic(seed: int, **kw: object) -> Callable[[], dict[str, Any]]:
    return lambda: to_state(Simulation.classic(seed=seed, engine="reference", **kw))


GOLDEN_CASES: tuple[GoldenCase, ...] = (
    GoldenCase("classic-1", "the classic start, seed 1, H = 400", _classic(1)),
    GoldenCase("classic-2", "the classic start, seed 2, H = 400", _classic(2)),
    GoldenCase("classic-3", "the classic start, seed 3, H = 450", _classic(3, trap_height=450.0)),
    GoldenCase("two-atoms", "2 atoms at the bottom, radii 12 and 8, masses 1 and 3", _two_atoms),
    GoldenCase("grazing", "1 atom 1e-9 px above the wall at x = 50, along the tangent", _grazing),
    GoldenCase(
        "resting",
        "1 atom at rest on the vertex: it hops at the floor speed",
        lambda: _one_atom(0.0, 1e-300, 0.0, 0.0),
    ),
    GoldenCase("mirror", "mirror-image atoms: events tie exactly", _mirror),
    GoldenCase("ties-now", "touching pairs and centres on the wall: ties at t = 0", _ties_now),
    GoldenCase("mixed-200", "200 atoms, radii 4-8 px, masses 0.5-4", _mixed),
    GoldenCase(
        "knife",
        "the knife, no win rule, H falling from 300 by 1.5 px a frame",
        _classic(4, escape="knife", win=False, trap_height=300.0),
        lambda k: max(25.0, 300.0 - 1.5 * k),
    ),
    GoldenCase(
        "falling-height",
        "the rim falling from 400 by 3 px a frame to 40: escapes, atoms gone",
        _classic(5),
        lambda k: max(40.0, 400.0 - 3.0 * k),
    ),
    GoldenCase(
        "win-damping",
        "the knife at H = 100 wins at once: damped bounces, the condensate settles",
        _classic(6, escape="knife", trap_height=400.0),
        lambda k: 400.0 if k < 20 else 100.0,
    ),
    GoldenCase(
        "dense-1000",
        "1000 atoms of radius 3, H = 450: the cell grid in earnest",
        lambda: to_state(
            Simulation(n_atoms=1000, radius=3.0, seed=7, trap_height=450.0, engine="reference")
        ),
    ),
    GoldenCase(
        "height-mid-frame",
        "the rim moves inside a frame: H = 400, 200 from t = 7.37, 90 from t = 19.5",
        _classic(7),
        height_changes=((7.37, 200.0), (19.5, 90.0)),
    ),
)


def golden_trace(case: GoldenCase, engine: str = "reference") -> dict[str, Any]:
    return make_trace(
        case.name, case.description, case.start(), case.events, case.height_of_frame, engine,
        case.height_changes,
    )  # fmt: skip


def _fast_available() -> bool:
    return importlib.util.find_spec("evapcool.physics._core") is not None


def _write(out: Path, only: list[str] | None) -> int:
    out.mkdir(parents=True, exist_ok=True)
    fast = _fast_available()
    for case in GOLDEN_CASES:
        if only and case.name not in only:
            continue
        trace = golden_trace(case)
        text = trace_text(trace)
        if fast and trace_text(replay(trace, "fast")) != text:
            print(f"{case.name}: the core disagrees with the reference engine", file=sys.stderr)
            return 1
        atomic_write_text(out / f"{case.name}.json", text)
        print(f"{case.name}: {len(trace['events'])} events, {len(trace['steps'])} steps"
              + (", fast engine agrees" if fast else ""))  # fmt: skip
    return 0


def _check(out: Path, only: list[str] | None) -> int:
    bad = checked = 0
    for case in GOLDEN_CASES:
        if only and case.name not in only:
            continue
        checked += 1
        path = out / f"{case.name}.json"
        fresh = trace_text(golden_trace(case))
        if not path.exists() or path.read_text(encoding="utf-8") != fresh:
            print(f"{case.name}: {path} does not match the engines", file=sys.stderr)
            bad += 1
    if bad:
        return 1
    print(f"golden_traces: all {checked} traces in {out} match the engines")  # silence is no news
    return 0


def _run(state_path: Path, events: int, engine: str) -> int:
    try:
        state = read_json(state_path.read_text(encoding="utf-8"))
        if not isinstance(state, dict):
            raise ValueError("state must be a JSON object")
        trace = make_trace(state_path.stem, f"{events} events from {state_path.name}", state,
                           events, None, engine)  # fmt: skip
    except (OSError, ValueError) as e:
        print(f"golden_traces: {e}", file=sys.stderr)
        return 2
    sys.stdout.write(trace_text(trace))
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    w = sub.add_parser("write", help="write the golden traces")
    w.add_argument("--out", type=Path, default=GOLDEN_DIR)
    w.add_argument("cases", nargs="*", help="only these cases")
    c = sub.add_parser("check", help="check the committed golden traces")
    c.add_argument("--out", type=Path, default=GOLDEN_DIR)
    c.add_argument("cases", nargs="*", help="only these cases")
    r = sub.add_parser("run", help="print the trace of any state file")
    r.add_argument("state", type=Path)
    r.add_argument("--events", type=int, default=2000)
    r.add_argument("--engine", choices=("reference", "fast"), default="reference")
    args = parser.parse_args(argv)
    if args.command == "write":
        return _write(args.out, args.cases)
    if args.command == "check":
        return _check(args.out, args.cases)
    if args.events < 1:
        parser.error("--events must be a whole number >= 1")
    return _run(args.state, args.events, args.engine)


if __name__ == "__main__":
    sys.exit(main())
