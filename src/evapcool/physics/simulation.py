"""`Simulation`: the public face of the physics (SPEC section 3).

Pure model: NumPy (and Numba through the fast engine), never pygame.
"""

from __future__ import annotations

import numbers
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from evapcool import limits
from evapcool.extras import (
    SLOW_REFERENCE_ATOMS,
    SlowEngineWarning,
    available,
    check,
    slow_engine_message,
)
from evapcool.limits import Range, shown
from evapcool.physics.constants import (
    ATOM_RADIUS,
    BORDER_BOTTOM,
    BORDER_LEFT,
    BORDER_RIGHT,
    BORDER_TOP,
    CUP_DROP,
    CURVATURE,
    FPS,
    GRAVITY,
    N_ATOMS,
    TC_EXPONENT_CUP,
    TC_EXPONENT_SEED,
    TC_LAWS,
    TRAP_HEIGHT,
    WINDOW,
    cup_vertex,
)
from evapcool.physics.loading import load_cup
from evapcool.physics.validation import check_start, check_world
from evapcool.physics.world import (
    ESCAPE_RULES,
    ESCAPED,
    EVENT_NAMES,
    TRAPPED,
    World,
)

if TYPE_CHECKING:
    from evapcool.physics.fast import FastEngine
    from evapcool.physics.reference import ReferenceEngine

#: Public names; the applet's constants are defined in physics/constants.py (below
#: physics/state.py too) and re-exported here, where callers have always found them.
__all__ = [
    "ATOM_RADIUS",
    "AUTO_FAST_MIN_ATOMS",
    "BORDER_BOTTOM",
    "BORDER_LEFT",
    "BORDER_RIGHT",
    "BORDER_TOP",
    "CUP_DROP",
    "CURVATURE",
    "ENGINES",
    "FPS",
    "GRAVITY",
    "N_ATOMS",
    "TC_EXPONENT_CUP",
    "TC_EXPONENT_SEED",
    "TC_LAWS",
    "TRAP_HEIGHT",
    "WINDOW",
    "Simulation",
    "cup_vertex",
]
ENGINES = ("auto", "reference", "fast")
#: engine="auto" uses the fast engine from this many atoms on (docs/benchmarks.md).
AUTO_FAST_MIN_ATOMS = 100


def _bad(name: str, allowed: str, value: object) -> ValueError:
    return ValueError(f"{name} must be {allowed} (got {shown(value)})")


def _flag(name: str, value: object) -> bool:
    """A real bool: "no" or 0 is not False here (issue 18)."""
    if not isinstance(value, (bool, np.bool_)):
        raise _bad(name, "True or False", value)
    return bool(value)


def _choice(name: str, value: object, options: tuple[str, ...]) -> str:
    if not isinstance(value, str) or value not in options:
        raise _bad(name, "one of " + ", ".join(options), value)
    return value


def _floats(name: str, value: object, shape: tuple[int, ...], allowed: str) -> np.ndarray:
    """value as a new float array of this shape; ValueError naming name otherwise."""
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise _bad(name, allowed, value) from None
    if arr.shape != shape or not np.all(np.isfinite(arr)):
        raise _bad(name, allowed, value)
    return arr


def _per_atom(name: str, value: object, n: int, rng: Range) -> np.ndarray:
    """One number for every atom, or n of them, each within rng."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return np.full(n, rng.check(name, value))
    allowed = f"{rng.allowed()}, or {n} such numbers"
    if isinstance(value, (str, bytes, bool)):
        raise _bad(name, allowed, value)
    arr = _floats(name, value, (n,), allowed)
    bad = np.flatnonzero((arr < rng.low) | (arr > rng.high))
    if bad.size:
        i = int(bad[0])
        raise ValueError(f"{name} must be {allowed} (atom {i} has {float(arr[i])!r})")
    return arr


def _window(value: object) -> tuple[int, int]:
    allowed = f"two whole numbers (width, height), each {limits.WINDOW_SIDE.span()}"
    if not isinstance(value, (tuple, list)) or len(value) != 2:
        raise _bad("window", allowed, value)
    side = limits.WINDOW_SIDE
    try:
        return side.check_int("window", value[0]), side.check_int("window", value[1])
    except ValueError:
        raise _bad("window", allowed, value) from None


def _check_engine_size(engine: str, n: int) -> None:
    """The reference engine's N x N table must stay small (limits.REFERENCE_MAX_ATOMS)."""
    if n <= limits.REFERENCE_MAX_ATOMS:
        return
    if engine == "reference":
        raise ValueError(
            f"n_atoms must be at most {limits.REFERENCE_MAX_ATOMS} with engine='reference' "
            f"(its pair table grows as N^2; got {n}); use engine='fast' or 'auto'"
        )
    if engine == "auto" and not _fast_available():
        raise ValueError(
            f"n_atoms must be at most {limits.REFERENCE_MAX_ATOMS} without numba "
            f"(got {n}); install numba for the fast engine"
        )


class Simulation:
    """Hard disks in a parabolic cup under gravity, advanced event by event, exactly.

    Trap coordinates: x right, y up, origin at the lowest point an atom centre
    can reach; lengths in px, time in frames (1/30 s), mass in atom masses.
    """

    def __init__(
        self,
        n_atoms: int = N_ATOMS,
        radius: float | ArrayLike = ATOM_RADIUS,
        mass: float | ArrayLike = 1.0,
        *,
        curvature: float = CURVATURE,
        gravity: float = GRAVITY,
        trap_height: float = TRAP_HEIGHT,
        window: tuple[int, int] = WINDOW,
        seed: int | None = None,
        engine: str = "auto",
        tc_exponent: float = TC_EXPONENT_SEED,
        escape: str = "rim",
        record_events: bool = False,
        win: bool = True,
        positions: ArrayLike | None = None,
        velocities: ArrayLike | None = None,
    ) -> None:
        # Every check comes before anything is allocated per atom (issue 18).
        n = limits.N_ATOMS.check_int("n_atoms", n_atoms)
        a = limits.CURVATURE.check("curvature", curvature)
        g = limits.GRAVITY.check("gravity", gravity)
        height = limits.TRAP_HEIGHT.check("trap_height", trap_height)
        tc_p = limits.TC_EXPONENT.check("tc_exponent", tc_exponent)
        window = _window(window)
        if seed is not None:
            seed = limits.SEED.check_int("seed", seed)
        win = _flag("win", win)
        record_events = _flag("record_events", record_events)
        engine = _choice("engine", engine, ENGINES)
        escape = _choice("escape", escape, ESCAPE_RULES)
        _check_engine_size(engine, n)
        radii = _per_atom("radius", radius, n, limits.RADIUS)
        masses = _per_atom("mass", mass, n, limits.MASS)

        r_ref = float(radii[0])
        vx_screen, vy_screen = cup_vertex(window)
        origin_sy = vy_screen - r_ref  # screen y of the trap origin
        self.window = window
        self.screen_origin = (vx_screen, origin_sy)
        self.seed = seed
        self.rng = np.random.default_rng(seed)

        if positions is None and velocities is None:
            if not np.all(radii == r_ref):
                raise _bad("radius", "one number unless positions are given", radius)
            pos, vel = load_cup(n, r_ref, a, origin_sy, self.rng)
        elif positions is None or velocities is None:
            missing = "positions" if positions is None else "velocities"
            raise ValueError(f"{missing} must be given together with the other (got None)")
        else:
            pos = _floats("positions", positions, (n, 2), f"a finite array of shape ({n}, 2)")
            vel = _floats("velocities", velocities, (n, 2), f"a finite array of shape ({n}, 2)")
            check_start(pos, vel, radii, a)

        self._world = World(
            pos=pos,
            vel=vel,
            radius=radii,
            mass=masses,
            curvature=a,
            gravity=g,
            trap_height=height,
            x_left=-vx_screen,
            x_right=self.window[0] - vx_screen,
            y_bottom=origin_sy - self.window[1],
            tc_exponent=tc_p,
            escape_rule=escape,
            record_events=record_events,
            win_rule=win,
        )
        self._engine = self._make_engine(engine, n)
        self._engine.set_trap_height(height)

    @classmethod
    def classic(cls, seed: int | None = None, **overrides: Any) -> Simulation:
        """The original applet's start: 49 atoms of radius 12 in the cup, H = 400."""
        return cls(n_atoms=N_ATOMS, radius=ATOM_RADIUS, seed=seed, **overrides)

    @classmethod
    def from_world(
        cls, world: World, window: tuple[int, int] = WINDOW, engine: str = "auto"
    ) -> Simulation:
        """A simulation around a ready, validated World (physics/state.py restores states so).

        The parameters are checked against the same ranges as a new Simulation's (the
        placement of the atoms is the caller's check, with its round-off tolerance).
        """
        engine = _choice("engine", engine, ENGINES)
        window = _window(window)
        check_world(world, placement=False)
        _check_engine_size(engine, len(world.radius))
        sim = cls.__new__(cls)
        vx_screen, vy_screen = cup_vertex(window)
        sim.window = window
        sim.screen_origin = (vx_screen, vy_screen - float(world.radius[0]))
        sim.seed = None
        sim.rng = np.random.default_rng()
        sim._world = world
        sim._engine = sim._make_engine(engine, len(world.radius))
        sim._engine.set_trap_height(world.trap_height)
        return sim

    @classmethod
    def from_state(
        cls, state: dict[str, Any] | str, engine: str = "auto", **kw: bool
    ) -> Simulation:
        """Go on exactly from a state (dict or JSON text, docs/state.md); see physics.state."""
        from evapcool.physics.state import world_from_state

        world, window = world_from_state(state, **kw)
        return cls.from_world(world, window, engine)

    def to_state(self) -> dict[str, Any]:
        """The state as a JSON-ready dict (docs/state.md), resumable with from_state."""
        from evapcool.physics.state import to_state

        return to_state(self)

    def _make_engine(self, engine: str, n: int) -> ReferenceEngine | FastEngine:
        if engine == "auto":
            engine = "fast" if n >= AUTO_FAST_MIN_ATOMS and _fast_available() else "reference"
            if engine == "reference" and n >= SLOW_REFERENCE_ATOMS:
                warnings.warn(slow_engine_message(n), SlowEngineWarning, stacklevel=3)
        if engine == "fast":
            check("numba", "the fast engine")
            from evapcool.physics.fast import FastEngine

            return FastEngine(self._world)
        from evapcool.physics.reference import ReferenceEngine

        return ReferenceEngine(self._world)

    def __repr__(self) -> str:
        """One line for notebooks: atoms, T, Tc, the frame reached and the engine."""
        n = self.n_trapped
        tc = f"{self.critical_temperature:.4g}" if n else "-"
        t = f"{self.temperature:.4g}" if n else "-"
        won = ", condensed" if self.won else ""
        return (
            f"Simulation(atoms {n} of {self.n_atoms}, T {t}, Tc {tc}, "
            f"frame {self.time:g}, engine {self.engine}{won})"
        )

    # -- time -----------------------------------------------------------------
    def advance(self, dt: float) -> None:
        """Advance the simulation by dt frames, processing every event exactly."""
        dt = limits.DT.check("dt", dt)
        self._engine.advance_to(self._world.time + dt)

    @property
    def time(self) -> float:
        """Simulation time in frames."""
        return self._world.time

    @property
    def engine(self) -> str:
        """Name of the engine in use: 'reference' or 'fast'."""
        return self._engine.name

    # -- the trap ---------------------------------------------------------------
    @property
    def trap_height(self) -> float:
        """Rim height H in px above the lowest centre position."""
        return self._world.trap_height

    @trap_height.setter
    def trap_height(self, value: float) -> None:
        self._engine.set_trap_height(limits.TRAP_HEIGHT.check("trap_height", value))

    @property
    def rim_half_width(self) -> float:
        """x_rim = sqrt(H / a): the wall ends at |x| = x_rim."""
        return self._world.rim_half_width

    @property
    def curvature(self) -> float:
        return self._world.curvature

    @property
    def gravity(self) -> float:
        return self._world.gravity

    @property
    def escape_rule(self) -> str:
        """'rim' (fly over the rim) or 'knife' (energy above m g H removed at once)."""
        return self._world.escape_rule

    # -- atoms ------------------------------------------------------------------
    @property
    def n_atoms(self) -> int:
        """Atoms at the start."""
        return self._world.n_initial

    @property
    def n_trapped(self) -> int:
        return self._world.n_trapped

    @property
    def n_escaped(self) -> int:
        """Atoms that left the trap and are still falling inside the window."""
        return int(np.count_nonzero(self._world.status == ESCAPED))

    @property
    def trapped_indices(self) -> np.ndarray:
        return np.flatnonzero(self._world.status == TRAPPED)

    @property
    def escaped_indices(self) -> np.ndarray:
        return np.flatnonzero(self._world.status == ESCAPED)

    @property
    def positions(self) -> np.ndarray:
        """(n_trapped, 2) centres now, trap coordinates (y up), px."""
        return self._world.state_at(self.trapped_indices, self.time)[0]

    @property
    def velocities(self) -> np.ndarray:
        """(n_trapped, 2) velocities now, px / frame."""
        return self._world.state_at(self.trapped_indices, self.time)[1]

    @property
    def escaped_positions(self) -> np.ndarray:
        """(n_escaped, 2) centres of atoms falling out of the window."""
        return self._world.state_at(self.escaped_indices, self.time)[0]

    @property
    def radii(self) -> np.ndarray:
        """Radii of the trapped atoms."""
        radii: np.ndarray = self._world.radius[self.trapped_indices].copy()
        return radii

    @property
    def masses(self) -> np.ndarray:
        """Masses of the trapped atoms."""
        masses: np.ndarray = self._world.mass[self.trapped_indices].copy()
        return masses

    @property
    def escaped_radii(self) -> np.ndarray:
        radii: np.ndarray = self._world.radius[self.escaped_indices].copy()
        return radii

    def energies(self) -> np.ndarray:
        """Energy 1/2 m v^2 + m g y of each trapped atom."""
        energies: np.ndarray = self._world.energies()[self.trapped_indices]
        return energies

    def total_energy(self) -> float:
        """Sum of 1/2 m v^2 + m g y over trapped atoms."""
        return float(np.sum(self.energies()))

    # -- thermodynamics (seed Eqs. 1 and 46) ---------------------------------------
    @property
    def temperature(self) -> float:
        """Mean energy per trapped atom, seed Eq. (1); 0 for an empty cup."""
        n = self.n_trapped
        return self.total_energy() / n if n else 0.0

    @property
    def initial_temperature(self) -> float:
        return self._world.initial_temperature

    @property
    def critical_temperature(self) -> float:
        """Tc(N) = Tc0 (N / N0)^p with Tc0 = 0.75 T(0), seed Eq. (46)."""
        return self._world.critical_temperature_of(self.n_trapped)

    @property
    def tc_exponent(self) -> float:
        return self._world.tc_exponent

    @property
    def won(self) -> bool:
        """True once T < Tc(N) (latched): the gas has condensed. Never with win=False."""
        return self._world.won

    @property
    def win_rule(self) -> bool:
        """False if the game's win rule is off (win=False): the gas stays a gas below Tc."""
        return self._world.win_rule

    # -- counters ---------------------------------------------------------------
    @property
    def pair_collision_count(self) -> int:
        return self._world.pair_count

    @property
    def wall_collision_count(self) -> int:
        return self._world.wall_count

    @property
    def collision_count(self) -> int:
        return self._world.pair_count + self._world.wall_count

    @property
    def event_log(self) -> list[tuple[str, int, int, float]]:
        """(kind, i, j, time) of every event if record_events=True, else []."""
        return [(EVENT_NAMES[e[0]], int(e[1]), int(e[2]), float(e[3])) for e in self._world.log]

    # -- for views --------------------------------------------------------------
    def to_screen(self, xy: np.ndarray) -> np.ndarray:
        """Trap coordinates to window pixels (y down)."""
        ox, oy = self.screen_origin
        xy = np.asarray(xy, dtype=float)
        out = np.empty_like(xy)
        out[..., 0] = ox + xy[..., 0]
        out[..., 1] = oy - xy[..., 1]
        return out

    def force_win(self) -> None:
        """Declare the gas condensed now (demonstrations and tests)."""
        self._world.won = True


def _fast_available() -> bool:
    return available("numba")
