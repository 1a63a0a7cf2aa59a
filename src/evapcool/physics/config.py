"""SimulationConfig: every parameter of a new Simulation, checked once at the boundary
(issue 26.2). `Simulation(...)` builds one from its keywords; a caller that holds one
(the game, the lab) passes it down with `Simulation.from_config`, and nothing below
checks it again. Ranges come from limits.py; errors are ParameterErrors naming the
parameter, so each command line can name its own option from a table.
"""

from __future__ import annotations

import inspect
import numbers
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from evapcool import limits
from evapcool.limits import ParameterError, Range, bad_value
from evapcool.physics.core import available
from evapcool.physics.room import Room, check_room
from evapcool.physics.validation import check_start
from evapcool.physics.world import ESCAPE_RULES

ENGINES = ("auto", "reference", "fast")


@dataclass(frozen=True, eq=False)
class SimulationConfig:
    """A checked set of Simulation parameters (build it with `checked`).

    radii, masses: one per atom; positions, velocities: (n_atoms, 2) trap coordinates, or
    both None for the cup's loading (SPEC 1).
    """

    n_atoms: int
    radii: np.ndarray
    masses: np.ndarray
    curvature: float
    gravity: float
    trap_height: float
    tc_exponent: float
    room: Room
    seed: int | None
    engine: str
    escape: str
    record_events: bool
    win: bool
    positions: np.ndarray | None = None
    velocities: np.ndarray | None = None

    @classmethod
    def checked(
        cls,
        *,
        n_atoms: object,
        radius: object,
        mass: object,
        curvature: object,
        gravity: object,
        trap_height: object,
        room: object,
        seed: object,
        engine: object,
        tc_exponent: object,
        escape: object,
        record_events: object,
        win: object,
        positions: ArrayLike | None = None,
        velocities: ArrayLike | None = None,
    ) -> SimulationConfig:
        """Each parameter checked once, before anything is allocated per atom (issue 18)."""
        n = limits.N_ATOMS.check_int("n_atoms", n_atoms)
        a = limits.CURVATURE.check("curvature", curvature)
        engine = check_choice("engine", engine, ENGINES)
        check_engine_size(engine, n)
        radii = _per_atom("radius", radius, n, limits.RADIUS)
        config = cls(
            n_atoms=n,
            radii=radii,
            masses=_per_atom("mass", mass, n, limits.MASS),
            curvature=a,
            gravity=limits.GRAVITY.check("gravity", gravity),
            trap_height=limits.TRAP_HEIGHT.check("trap_height", trap_height),
            tc_exponent=limits.TC_EXPONENT.check("tc_exponent", tc_exponent),
            room=check_room(room),
            seed=None if seed is None else limits.SEED.check_int("seed", seed),
            engine=engine,
            escape=check_choice("escape", escape, ESCAPE_RULES),
            record_events=_flag("record_events", record_events),
            win=_flag("win", win),
        )
        if positions is None and velocities is None:
            if not np.all(radii == radii[0]):
                raise bad_value("radius", "one number unless positions are given", radius)
            return config
        if positions is None or velocities is None:
            missing = "positions" if positions is None else "velocities"
            raise ParameterError(missing, "must be given together with the other (got None)")
        return config.with_start(positions, velocities)

    def with_start(self, positions: ArrayLike, velocities: ArrayLike) -> SimulationConfig:
        """The same parameters with a given start, checked (bounds, in the cup, no overlap)."""
        n = self.n_atoms
        shape = f"a finite array of shape ({n}, 2)"
        pos = _floats("positions", positions, (n, 2), shape)
        vel = _floats("velocities", velocities, (n, 2), shape)
        check_start(pos, vel, self.radii, self.curvature)
        return SimulationConfig(
            **{**self.__dict__, "positions": pos, "velocities": vel},
        )


#: The keywords SimulationConfig.checked takes: a caller's own config passes those of its
#: fields on by name (game/rules.py), so the list is written once, there.
CHECKED_KEYWORDS = frozenset(inspect.signature(SimulationConfig.checked).parameters)


def check_engine_size(engine: str, n: int) -> None:
    """The reference engine's N x N table must stay small (limits.REFERENCE_MAX_ATOMS)."""
    if n <= limits.REFERENCE_MAX_ATOMS:
        return
    if engine == "reference":
        raise ParameterError(
            "n_atoms",
            f"must be at most {limits.REFERENCE_MAX_ATOMS} with engine='reference' "
            f"(its pair table grows as N^2; got {n}); use engine='fast' or 'auto'",
        )
    if engine == "auto" and not available():
        raise ParameterError(
            "n_atoms",
            f"must be at most {limits.REFERENCE_MAX_ATOMS} without the compiled core "
            f"(got {n}); reinstall evapcool with a C compiler for it",
        )


def check_choice(name: str, value: object, options: tuple[str, ...]) -> str:
    if not isinstance(value, str) or value not in options:
        raise bad_value(name, "one of " + ", ".join(options), value)
    return value


def _flag(name: str, value: object) -> bool:
    """A real bool: "no" or 0 is not False here (issue 18)."""
    if not isinstance(value, (bool, np.bool_)):
        raise bad_value(name, "True or False", value)
    return bool(value)


def _floats(name: str, value: object, shape: tuple[int, ...], allowed: str) -> np.ndarray:
    """value as a new float array of this shape; ParameterError naming name otherwise."""
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise bad_value(name, allowed, value) from None
    if arr.shape != shape or not np.all(np.isfinite(arr)):
        raise bad_value(name, allowed, value)
    return arr


def _per_atom(name: str, value: object, n: int, rng: Range) -> np.ndarray:
    """One number for every atom, or n of them, each within rng."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return np.full(n, rng.check(name, value))
    allowed = f"{rng.allowed()}, or {n} such numbers"
    if isinstance(value, (str, bytes, bool)):
        raise bad_value(name, allowed, value)
    arr = _floats(name, value, (n,), allowed)
    bad = np.flatnonzero((arr < rng.low) | (arr > rng.high))
    if bad.size:
        i = int(bad[0])
        raise ParameterError(name, f"must be {allowed} (atom {i} has {float(arr[i])!r})")
    return arr
