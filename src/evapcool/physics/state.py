"""The state JSON shared by the Python and web editions (docs/state.md).

A state holds what the physics needs to go on exactly: each atom's stored state at its own
last-event time (positions move lazily), radius, mass and lifecycle, the clock, the trap,
the rules, and what the win needs (the starting temperature; N0 is the number of atoms
listed, gone ones included, so indices stay those of the run). The web edition reads and
writes the same format (web/src/physics/state.ts); both write it as `state_text` does,
floats as 17 significant digits, so the two texts of one state are identical.
"""

from __future__ import annotations

import json
import math
import numbers
from dataclasses import dataclass
from typing import Any, Protocol, TypeGuard

import numpy as np

from evapcool.limits import CONTACT_TOLERANCE, shown
from evapcool.physics.constants import (
    CURVATURE,
    GRAVITY,
    TC_EXPONENT_SEED,
    TRAP_HEIGHT,
)
from evapcool.physics.model import STATUS_NAMES
from evapcool.physics.room import Room
from evapcool.physics.validation import first_overlap
from evapcool.physics.world import ESCAPE_RULES, TRAPPED, World, world_in

STATE_FORMAT = "evapcool-state"
STATE_VERSION = 1

_STATE_KEYS = (
    "format", "version", "time", "trap_height", "curvature", "gravity", "window", "escape",
    "tc_exponent", "win", "won", "initial_temperature", "energy_sum", "pair_collisions",
    "wall_collisions", "atoms",
)  # fmt: skip
_ATOM_KEYS = ("x", "y", "vx", "vy", "t", "radius", "mass", "status")


#: The `window` field (docs/state.md) names the room as the window of the original's layout
#: that shows it: the cup's lowest point in the middle of a play area inside borders of
#: 48 px (left) and 96 px (right), and 128 px above the window's bottom.
WINDOW = (640, 672)
_LEFT_BORDER, _RIGHT_BORDER, _VERTEX_ABOVE_BOTTOM = 48, 96, 128


def room_of_window(window: tuple[int, int]) -> Room:
    """The room that a state's window field names (view/screen.py places it so too)."""
    w, h = window
    x = _LEFT_BORDER + (w - _LEFT_BORDER - _RIGHT_BORDER) / 2.0
    y = float(h - _VERTEX_ABOVE_BOTTOM)
    return Room(left=x, right=w - x, below=h - y, above=y)


def window_of_room(room: Room) -> list[int]:
    """The window field for room; ValueError if no window of the layout gives it."""
    size = (round(room.left + room.right), round(room.below + room.above))
    if room_of_window(size) != room:
        raise ValueError(
            f"room must be one a window gives (view/screen.py) to be written as a state "
            f"(got {room})"
        )
    return [size[0], size[1]]


def _bad(name: str, allowed: str, value: object) -> ValueError:
    text = shown(value)
    if len(text) > 60:
        text = text[:57] + "..."
    return ValueError(f"{name} must be {allowed} (got {text})")


# -- text: JSON with every number as 17 significant digits ---------------------------------
def number_text(v: float) -> str:
    """%.17g: reads back to the same bits (also -0); the web edition writes the same text."""
    if not math.isfinite(v):
        raise ValueError(f"number must be finite to be written as JSON (got {shown(v)})")
    return f"{v:.17g}"


def json_text(value: object, indent: int = 0) -> str:
    """Canonical JSON: arrays of scalars on one line, objects and nested arrays one item a line."""
    pad = " " * (indent + 2)
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, numbers.Real):
        return number_text(float(value))
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = [f"{pad}{json.dumps(k)}: {json_text(v, indent + 2)}" for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"
    if isinstance(value, (list, tuple, np.ndarray)):
        seq = list(value)
        if all(not isinstance(e, (dict, list, tuple, np.ndarray)) for e in seq):
            return "[" + ", ".join(json_text(e) for e in seq) + "]"
        items = [pad + json_text(e, indent + 2) for e in seq]
        return "[\n" + ",\n".join(items) + "\n" + " " * indent + "]"
    raise TypeError(f"cannot write {type(value).__name__} as JSON")


def read_json(text: str) -> object:
    """JSON text to Python; every number a float, so "-0" stays -0.0."""
    return json.loads(text, parse_int=float)


# -- validation ----------------------------------------------------------------------------
@dataclass
class ParsedState:
    """A validated state with every default filled in."""

    time: float
    trap_height: float
    curvature: float
    gravity: float
    window: tuple[int, int]
    escape: str
    tc_exponent: float
    win: bool
    won: bool
    initial_temperature: float | None
    energy_sum: float | None
    pair_count: int
    wall_count: int
    x: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    t: np.ndarray
    radius: np.ndarray
    mass: np.ndarray
    status: np.ndarray


def _real(v: object) -> TypeGuard[numbers.Real]:
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def _finite(name: str, v: object, default: float, positive: bool = False) -> float:
    """v as a float (default if absent): finite, and > 0 if positive."""
    if v is None:
        return default
    if not _real(v) or not math.isfinite(float(v)) or (positive and float(v) <= 0.0):
        raise _bad(name, "a positive finite number" if positive else "a finite number", v)
    return float(v)


def _count(name: str, v: object) -> int:
    if v is None:
        return 0
    if not _real(v) or not float(v).is_integer() or float(v) < 0 or float(v) > 2**53:
        raise _bad(name, "a whole number >= 0", v)
    return int(float(v))


def _flag(name: str, v: object, default: bool) -> bool:
    if v is None:
        return default
    if not isinstance(v, bool):
        raise _bad(name, "true or false", v)
    return v


def _column(name: str, v: object, n: int | None) -> np.ndarray:
    allowed = f"an array of {n} finite numbers" if n is not None else "an array of finite numbers"
    if not isinstance(v, (list, tuple)) or (n is not None and len(v) != n):
        raise _bad(name, allowed, v)
    for i, e in enumerate(v):
        if not _real(e) or not math.isfinite(float(e)):
            raise _bad(f"{name}[{i}]", "a finite number", e)
    return np.array([float(e) for e in v], dtype=float)


def _per_atom(name: str, v: object, n: int, default: float) -> np.ndarray:
    if v is None or _real(v):
        return np.full(n, _finite(name, v, default, positive=True))
    out = _column(name, v, n)
    bad = np.flatnonzero(out <= 0.0)
    if bad.size:
        raise _bad(f"{name}[{bad[0]}]", "a positive finite number", float(out[bad[0]]))
    return out


def _window(name: str, v: object) -> tuple[int, int]:
    if (
        not isinstance(v, (list, tuple))
        or len(v) != 2
        or not all(_real(s) and float(s).is_integer() and 160 <= float(s) <= 2**31 for s in v)
    ):
        raise _bad(name, "two whole numbers (width, height) of at least 160 x 160 px", v)
    return int(v[0]), int(v[1])


def parse_state(state: object) -> ParsedState:
    """Validate a state (dict or JSON text); ValueError naming the field if it is bad."""
    if isinstance(state, str):
        try:
            state = read_json(state)
        except json.JSONDecodeError as e:
            raise ValueError(f"state must be JSON text ({e})") from None
    if not isinstance(state, dict):
        raise _bad("state", "an object with an atoms table", state)
    for k in state:
        if k not in _STATE_KEYS:
            raise _bad("state", "free of unknown fields", k)
    s = state.get
    if s("format") is not None and s("format") != STATE_FORMAT:
        raise _bad("state.format", json.dumps(STATE_FORMAT), s("format"))
    if s("version") is not None and s("version") != STATE_VERSION:
        raise _bad("state.version", str(STATE_VERSION), s("version"))
    atoms = s("atoms")
    if not isinstance(atoms, dict):
        raise _bad("state.atoms", "an object of per-atom arrays", atoms)
    for k in atoms:
        if k not in _ATOM_KEYS:
            raise _bad("state.atoms", "free of unknown fields", k)
    x = _column("state.atoms.x", atoms.get("x"), None)
    n = len(x)
    if n < 1:
        raise _bad("state.atoms.x", "an array of at least 1 atom", atoms.get("x"))
    time = _finite("state.time", s("time"), 0.0)
    t = np.full(n, time) if atoms.get("t") is None else _column("state.atoms.t", atoms["t"], n)
    late = np.flatnonzero(t > time)
    if late.size:
        raise _bad(
            f"state.atoms.t[{late[0]}]", f"at most the clock {float(time)!r}", float(t[late[0]])
        )
    status = np.zeros(n, dtype=np.int8)
    names = atoms.get("status")
    if names is not None:
        if not isinstance(names, (list, tuple)) or len(names) != n:
            allowed = f'an array of {n} of "trapped", "escaped", "gone"'
            raise _bad("state.atoms.status", allowed, names)
        for i, name in enumerate(names):
            if name not in STATUS_NAMES:
                raise _bad(f"state.atoms.status[{i}]", '"trapped", "escaped" or "gone"', name)
            status[i] = STATUS_NAMES.index(name)
    h = s("trap_height")
    height = math.inf if h == "inf" else _finite("state.trap_height", h, TRAP_HEIGHT, positive=True)
    escape = "rim" if s("escape") is None else s("escape")
    if escape not in ESCAPE_RULES:
        raise _bad("state.escape", "one of " + ", ".join(ESCAPE_RULES), escape)
    t0 = s("initial_temperature")
    esum = s("energy_sum")
    return ParsedState(
        time=time,
        trap_height=height,
        curvature=_finite("state.curvature", s("curvature"), CURVATURE, positive=True),
        gravity=_finite("state.gravity", s("gravity"), GRAVITY, positive=True),
        window=WINDOW if s("window") is None else _window("state.window", s("window")),
        escape=escape,
        tc_exponent=_finite("state.tc_exponent", s("tc_exponent"), TC_EXPONENT_SEED, positive=True),
        win=_flag("state.win", s("win"), True),
        won=_flag("state.won", s("won"), False),
        initial_temperature=None if t0 is None else _finite("state.initial_temperature", t0, 0),
        energy_sum=None if esum is None else _finite("state.energy_sum", esum, 0.0),
        pair_count=_count("state.pair_collisions", s("pair_collisions")),
        wall_count=_count("state.wall_collisions", s("wall_collisions")),
        x=x,
        y=_column("state.atoms.y", atoms.get("y"), n),
        vx=_column("state.atoms.vx", atoms.get("vx"), n),
        vy=_column("state.atoms.vy", atoms.get("vy"), n),
        t=t,
        radius=_per_atom("state.atoms.radius", atoms.get("radius"), n, 12.0),
        mass=_per_atom("state.atoms.mass", atoms.get("mass"), n, 1.0),
        status=status,
    )


def check_placement(
    name: str,
    x: np.ndarray,
    y: np.ndarray,
    radius: np.ndarray,
    trapped: np.ndarray,
    curvature: float,
    tol: float,
    overlaps: bool = True,
) -> None:
    """Trapped centres inside the cup (y >= a x^2) and at least r_i + r_j apart, within a
    relative tolerance tol; ValueError naming the first offending atoms (least indices).
    overlaps=False skips the pairs: after the win, atoms no longer collide with each other."""
    wall = curvature * x * x
    outside = np.flatnonzero(trapped & (y < wall - tol * (1.0 + np.abs(wall))))
    if outside.size:
        i = int(outside[0])
        xi, yi = float(x[i]), float(y[i])
        raise ValueError(
            f"{name}: atom {i} at ({xi!r}, {yi!r}) is outside the cup; centres must be "
            f"inside it or on its wall, y >= a x^2 (a = {float(curvature)!r})"
        )
    idx = np.flatnonzero(trapped)
    if not overlaps or idx.size < 2:
        return
    # The core's grid, linear in N (validation.first_overlap: core/overlap.c, or its oracle).
    pair = first_overlap(np.column_stack((x[idx], y[idx])), radius[idx], tol)
    if pair is not None:
        a, b = int(idx[pair[0]]), int(idx[pair[1]])
        d = math.hypot(x[b] - x[a], y[b] - y[a])
        reach = float(radius[a] + radius[b])
        raise ValueError(
            f"{name}: atoms {a} and {b} overlap (centres {d!r} apart, less than r{a} + r{b} = "
            f"{reach!r}); atoms must be at least r_i + r_j apart"
        )


# -- to and from a Simulation ------------------------------------------------------------
class SimLike(Protocol):
    """What to_state reads of a Simulation (typed here so that this module need not import it)."""

    @property
    def _world(self) -> World: ...

    @property
    def room(self) -> Room: ...


def to_state(sim: SimLike) -> dict[str, Any]:
    """The state of sim as a JSON-ready dict (fields in the order both editions write)."""
    w = sim._world
    return {
        "format": STATE_FORMAT,
        "version": STATE_VERSION,
        "time": float(w.time),
        "trap_height": float(w.trap_height) if math.isfinite(w.trap_height) else "inf",
        "curvature": float(w.curvature),
        "gravity": float(w.gravity),
        "window": window_of_room(sim.room),
        "escape": w.escape_rule,
        "tc_exponent": float(w.tc_exponent),
        "win": bool(w.win_rule),
        "won": bool(w.won),
        "initial_temperature": float(w.initial_temperature),
        "energy_sum": float(w.energy_sum),
        "pair_collisions": int(w.pair_count),
        "wall_collisions": int(w.wall_count),
        "atoms": {
            "x": w.pos[:, 0].tolist(),
            "y": w.pos[:, 1].tolist(),
            "vx": w.vel[:, 0].tolist(),
            "vy": w.vel[:, 1].tolist(),
            "t": w.t_atom.tolist(),
            "radius": w.radius.tolist(),
            "mass": w.mass.tolist(),
            "status": [STATUS_NAMES[s] for s in w.status],
        },
    }


def state_text(sim: SimLike) -> str:
    """The state as JSON text, exactly as the web edition writes it."""
    return json_text(to_state(sim)) + "\n"


def world_from_state(
    state: dict[str, Any] | str, *, record_events: bool = False
) -> tuple[World, Room]:
    """The World (and the room around its cup) that goes on exactly from state (dict or JSON text).

    `Simulation.from_state` runs it on an engine.

    ValueError naming the field if the state is malformed, or if trapped atoms overlap or
    lie outside the cup (up to CONTACT_TOLERANCE of round-off).
    """
    p = parse_state(state)
    dt = p.time - p.t
    xn = p.x + p.vx * dt
    yn = p.y + p.vy * dt - 0.5 * p.gravity * dt * dt
    trapped = p.status == TRAPPED
    # The condensate's atoms no longer collide after the win: they may overlap.
    check_placement(
        "state.atoms", xn, yn, p.radius, trapped, p.curvature, CONTACT_TOLERANCE, not p.won
    )
    room = room_of_window(p.window)
    atoms = (np.column_stack((p.x, p.y)), np.column_stack((p.vx, p.vy)), p.radius, p.mass)
    w = world_in(room, p, atoms, bool(record_events))
    w.t_atom[:] = p.t
    w.status[:] = p.status
    w.n_trapped = int(np.count_nonzero(trapped))
    w.time = p.time
    w.won = p.won
    w.pair_count = p.pair_count
    w.wall_count = p.wall_count
    total = w.sequential_energy_sum()
    if p.energy_sum is not None:
        scale = float(np.sum(np.abs(w.energies()[trapped])))
        if not abs(p.energy_sum - total) <= CONTACT_TOLERANCE * max(1.0, scale):
            allowed = f"the trapped atoms' energy sum, {float(total)!r}"
            raise _bad("state.energy_sum", allowed, p.energy_sum)
        total = p.energy_sum
    w.energy_sum = total
    if p.initial_temperature is not None:
        w.initial_temperature = p.initial_temperature
    else:
        w.initial_temperature = total / w.n_trapped if w.n_trapped else 0.0
    w.tc0 = 0.75 * w.initial_temperature
    return w, room
