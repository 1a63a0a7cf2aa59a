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
from typing import Any

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
