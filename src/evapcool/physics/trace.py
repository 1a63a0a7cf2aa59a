"""Event traces: one physics in two languages (the golden traces of web/test/golden/).

A trace is a starting state (physics/state.py), a schedule of steps (dt, trap height), the
events the engine processed over them (kind, atoms, time) and the state after the last
step. The web edition replays the same schedule from the same state (`npm run replay`) and
must process the same events, every time and coordinate bit for bit. Both editions write a
trace with `trace_text`'s layout, so the two texts of one run are identical.

`plan_steps` makes a schedule that ends at the n-th event: whole frames (with the trap
height of each), then a last step to the time of the n-th event (events at exactly that
time come along).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from evapcool.physics.loading import cell_centres
from evapcool.physics.simulation import Simulation
from evapcool.physics.state import json_text, read_json, to_state

TRACE_FORMAT = "evapcool-trace"
TRACE_VERSION = 1
#: A schedule never runs longer than this many frames (a state with no events left).
MAX_FRAMES = 100_000

Step = tuple[float, float]  # (dt frames, trap height px)


def packed_steps(steps: list[Step]) -> list[list[float]]:
    """Runs of equal steps as [dt, height, count] (a trace's "steps")."""
    out: list[list[float]] = []
    for dt, h in steps:
        if out and out[-1][0] == dt and out[-1][1] == h:
            out[-1][2] += 1
        else:
            out.append([dt, h, 1])
    return out


def unpacked_steps(packed: list[list[float]]) -> list[Step]:
    return [(float(dt), float(h)) for dt, h, count in packed for _ in range(int(count))]


def run_steps(state: dict[str, Any], steps: list[Step], engine: str = "reference") -> Simulation:
    """Load state with event recording, then set each step's height and advance its dt."""
    sim = Simulation.from_state(state, engine=engine, record_events=True)
    for dt, height in steps:
        sim.trap_height = height
        sim.advance(dt)
    return sim


def plan_steps(
    state: dict[str, Any],
    n_events: int,
    height_of_frame: Callable[[int], float] | None = None,
    engine: str = "reference",
    height_changes: tuple[tuple[float, float], ...] = (),
) -> list[Step]:
    """Whole frames (split at each (time, height) of height_changes inside one), then a last
    step that ends at the time of the n-th event."""
    sim = Simulation.from_state(state, engine=engine, record_events=True)
    steps: list[Step] = []
    for k in range(MAX_FRAMES):
        if height_of_frame is not None:
            sim.trap_height = float(height_of_frame(k))
        inside = [(t, h) for t, h in height_changes if k < t < k + 1]
        for end, next_height in [*inside, (float(k + 1), None)]:
            height = sim.trap_height
            if len(sim.event_log) >= n_events:  # reached by the knife's cuts alone
                steps.append((0.0, height))
                return steps
            before = sim.time
            sim.advance(end - before)
            if len(sim.event_log) >= n_events:
                steps.append((_dt_to_event(sim, before, n_events), height))
                return steps
            steps.append((end - before, height))
            if next_height is not None:
                sim.trap_height = next_height
    return steps


def _dt_to_event(sim: Simulation, before: float, n_events: int) -> float:
    """The step from before to the time of the n-th event (never short of it by round-off)."""
    t_n = sim.event_log[n_events - 1][3]
    dt = t_n - before
    while before + dt < t_n:
        dt = math.nextafter(dt, math.inf)
    return dt


def summary_of(sim: Simulation) -> dict[str, Any]:
    """What the game and the win read, after the last step."""
    return {
        "n_trapped": sim.n_trapped,
        "n_escaped": sim.n_escaped,
        "temperature": sim.temperature,
        "total_energy": sim.total_energy(),
        "critical_temperature": sim.critical_temperature,
        "won": sim.won,
        "pair_collisions": sim.pair_collision_count,
        "wall_collisions": sim.wall_collision_count,
    }


def make_trace(
    name: str,
    description: str,
    state: dict[str, Any],
    n_events: int,
    height_of_frame: Callable[[int], float] | None = None,
    engine: str = "reference",
    height_changes: tuple[tuple[float, float], ...] = (),
) -> dict[str, Any]:
    """The trace of engine from state over the schedule that reaches n_events."""
    steps = plan_steps(state, n_events, height_of_frame, engine, height_changes)
    sim = run_steps(state, steps, engine)
    return {
        "format": TRACE_FORMAT,
        "version": TRACE_VERSION,
        "case": name,
        "description": description,
        "events_requested": n_events,
        "start": state,
        "steps": packed_steps(steps),
        "events": [list(e) for e in sim.event_log],
        "end": to_state(sim),
        "summary": summary_of(sim),
    }


def replay(trace: dict[str, Any], engine: str) -> dict[str, Any]:
    """The trace that engine produces from trace's start and steps (the same, if it agrees)."""
    sim = run_steps(trace["start"], unpacked_steps(trace["steps"]), engine)
    out = dict(trace)
    out["events"] = [list(e) for e in sim.event_log]
    out["end"] = to_state(sim)
    out["summary"] = summary_of(sim)
    return out


def trace_text(trace: dict[str, Any]) -> str:
    return json_text(trace) + "\n"


def read_trace(text: str) -> dict[str, Any]:
    trace = read_json(text)
    if not isinstance(trace, dict) or trace.get("format") != TRACE_FORMAT:
        raise ValueError(f"trace must be a JSON object with format {TRACE_FORMAT!r}")
    return trace


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
