"""`Simulation`: the public face of the physics (SPEC section 3).

Pure model: NumPy and the compiled core (physics/core.py), never pygame.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from evapcool import limits
from evapcool.extras import (
    SLOW_REFERENCE_ATOMS,
    CoreMissingWarning,
    SlowEngineWarning,
    slow_engine_message,
)
from evapcool.physics.config import (
    ENGINES,
    SimulationConfig,
    check_choice,
    check_engine_size,
)
from evapcool.physics.constants import (
    ATOM_RADIUS,
    CURVATURE,
    FPS,
    GRAVITY,
    N_ATOMS,
    TC_EXPONENT_CUP,
    TC_EXPONENT_SEED,
    TC_LAWS,
    TRAP_HEIGHT,
)
from evapcool.physics.core import CoreEngine, available, missing_note
from evapcool.physics.loading import load_cup
from evapcool.physics.reference import ReferenceEngine
from evapcool.physics.room import CLASSIC_ROOM, Room, check_room
from evapcool.physics.start import random_seed
from evapcool.physics.state import to_state, world_from_state
from evapcool.physics.validation import check_world
from evapcool.physics.world import (
    ESCAPED,
    EVENT_NAMES,
    TRAPPED,
    World,
    world_in,
)

#: Public names; the applet's constants are defined in physics/constants.py (below
#: physics/state.py too) and re-exported here, where callers have always found them.
__all__ = [
    "ATOM_RADIUS",
    "CURVATURE",
    "ENGINES",
    "FPS",
    "GRAVITY",
    "N_ATOMS",
    "TC_EXPONENT_CUP",
    "TC_EXPONENT_SEED",
    "TC_LAWS",
    "TRAP_HEIGHT",
    "Simulation",
]


_said_core_missing = False


def _say_the_core_is_missing() -> None:
    """The first fallback of a process to the reference engine says why (a note, once)."""
    global _said_core_missing
    if not _said_core_missing:
        _said_core_missing = True
        warnings.warn(missing_note(), CoreMissingWarning, stacklevel=6)


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
        room: Room = CLASSIC_ROOM,
        seed: int | None = None,
        engine: str = "auto",
        tc_exponent: float = TC_EXPONENT_SEED,
        escape: str = "rim",
        record_events: bool = False,
        win: bool = True,
        positions: ArrayLike | None = None,
        velocities: ArrayLike | None = None,
    ) -> None:
        self._build(
            SimulationConfig.checked(
                n_atoms=n_atoms,
                radius=radius,
                mass=mass,
                curvature=curvature,
                gravity=gravity,
                trap_height=trap_height,
                room=room,
                seed=seed,
                engine=engine,
                tc_exponent=tc_exponent,
                escape=escape,
                record_events=record_events,
                win=win,
                positions=positions,
                velocities=velocities,
            )
        )

    @classmethod
    def from_config(cls, config: SimulationConfig) -> Simulation:
        """A simulation of a config checked once at the boundary (SimulationConfig.checked);
        nothing is checked again here, but whether the atoms fit the cup (the loader's)."""
        sim = cls.__new__(cls)
        sim._build(config)
        return sim

    def _build(self, c: SimulationConfig) -> None:
        r_ref = float(c.radii[0])  # the trap origin lies this far above the wall's lowest point
        seed = c.seed
        if c.positions is None or c.velocities is None:
            if seed is None:
                seed = random_seed()  # drawn here so that every start can be replayed
            pos, vel = load_cup(c.n_atoms, r_ref, c.curvature, c.room.top(r_ref), seed)
        else:
            pos, vel = c.positions.copy(), c.velocities.copy()
        atoms = (pos, vel, c.radii.copy(), c.masses.copy())
        self._start(world_in(c.room, c, atoms, c.record_events), c.room, seed, c.engine)

    def _start(self, world: World, room: Room, seed: int | None, engine: str) -> None:
        """Run world on engine, its trap at the world's height (the seed: the start's, if drawn)."""
        self.room = room
        self.seed = seed
        self._world = world
        self._engine = self._make_engine(engine, len(world.radius))
        self._engine.set_trap_height(world.trap_height)

    @classmethod
    def classic(cls, seed: int | None = None, **overrides: Any) -> Simulation:
        """The original applet's start: 49 atoms of radius 12 in the cup, H = 400."""
        return cls(n_atoms=N_ATOMS, radius=ATOM_RADIUS, seed=seed, **overrides)

    @classmethod
    def from_world(
        cls, world: World, room: Room = CLASSIC_ROOM, engine: str = "auto"
    ) -> Simulation:
        """A simulation around a ready, validated World (physics/state.py restores states so);
        room: the one whose escape box the world has (recorded, for the view and the state).

        The parameters are checked against the same ranges as a new Simulation's (the
        placement of the atoms is the caller's check, with its round-off tolerance).
        """
        engine = check_choice("engine", engine, ENGINES)
        room = check_room(room)
        check_world(world, placement=False)
        check_engine_size(engine, len(world.radius))
        sim = cls.__new__(cls)
        sim._start(world, room, None, engine)
        return sim

    @classmethod
    def from_state(
        cls, state: dict[str, Any] | str, engine: str = "auto", **kw: bool
    ) -> Simulation:
        """Go on exactly from a state (dict or JSON text, docs/state.md); see physics.state."""
        world, room = world_from_state(state, **kw)
        return cls.from_world(world, room, engine)

    def to_state(self) -> dict[str, Any]:
        """The state as a JSON-ready dict (docs/state.md), resumable with from_state."""
        return to_state(self)

    def _make_engine(self, engine: str, n: int) -> ReferenceEngine | CoreEngine:
        if engine == "auto":
            # The compiled core wherever it is installed: it has no start-up cost and is
            # faster than the NumPy engine at any size (docs/benchmarks.md).
            engine = "fast" if available() else "reference"
            if engine == "reference":
                _say_the_core_is_missing()
                if n >= SLOW_REFERENCE_ATOMS:
                    warnings.warn(slow_engine_message(n), SlowEngineWarning, stacklevel=5)
        if engine == "fast":
            return CoreEngine(self._world)
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
        """Name of the engine in use: 'reference', or 'fast' (the compiled core)."""
        return self._engine.name

    # -- the game's clock (core/play.c; its readable oracle: physics/play.py) -------------
    def play_to(self, end: float, on_frame: Callable[[float], None] | None = None) -> None:
        """Play to `end` frames in pieces that stop at each whole frame: there the height held
        is recorded (`moves`, up to the win), the win seen and the score fixed, then the
        script's or the asked height applied. on_frame(height held): after each recorded
        frame, the state at its end."""
        if math.isnan(end):
            raise ValueError("end must be a number of frames (got nan)")
        self._engine.play_to(end, on_frame)

    def ask_height(self, height: float, now: bool = False) -> bool:
        """Ask for a rim height (within limits.TRAP_HEIGHT, checked by the caller) from the
        next whole frame, at once if `now` (paused) or on one. False, and nothing asked, once
        won, while a script plays, or if it is the height asked already."""
        return self._engine.ask_height(height, now)

    @property
    def asked_height(self) -> float:
        """The rim's height now, or the one it takes at the next whole frame."""
        return self._engine.asked_height

    def hold(self, runs: Sequence[tuple[float, float]]) -> None:
        """Hold these (height, frames) runs' heights (a recording watched): whole frame k
        from the start holds the k-th height; asked heights are refused till it ends.
        No runs: the player's heights again."""
        self._engine.hold(runs)

    def moves(self) -> list[tuple[float, int]]:
        """The (height, frames) runs held so far, up to the frame the win was seen in."""
        return self._engine.moves()

    @property
    def win_frame(self) -> float | None:
        """The whole frame at whose end the win was seen; None before."""
        return self._engine.win_frame

    # -- the game's frame (core/game.c; the reference engine's readable rule is its oracle) --
    @property
    def score(self) -> int | None:
        """Atoms trapped at the end of the whole frame the win was seen in; None before."""
        return self._engine.score

    def replay(self, moves: Sequence[tuple[float, int]], limit: int) -> int:
        """Hold each (height, frames) run's height for that many whole frames (game.c's frame), from
        a whole frame, up to the end of the frame the win is seen in or `limit` frames;
        returns the frames played (the result: `won`, `score`)."""
        runs = np.array(moves, dtype=np.float64).reshape(-1, 2)
        return self._engine.replay(runs, limit)

    def path(
        self, moves: Sequence[tuple[float, int]], limit: int, stride: int, h0: float
    ) -> tuple[int, np.ndarray]:
        """The game's path in the (N, T) plane: (height, frames) runs played as `replay`
        plays them; kept are (k, N, T, h) at frame 0 (height h0), every stride-th whole
        frame, the last and the win's, where N > 0 and T > 0 (game/path.py rounds T).
        Returns the frames played and those rows."""
        runs = np.array(moves, dtype=np.float64).reshape(-1, 2)
        return self._engine.path(runs, limit, stride, h0)

    def out_of_reach(self, lowest: float, height: float) -> int:
        """The reach rule (model.REACH_*), the engine's (core_out_of_reach or its oracle), with
        the lowest rim the player can set and the rim now."""
        return self._engine.out_of_reach(lowest, height)

    # -- the trap ---------------------------------------------------------------
    @property
    def trap_height(self) -> float:
        """Rim height H in px above the lowest centre position."""
        return self._world.trap_height

    @trap_height.setter
    def trap_height(self, value: float) -> None:
        """Move the rim now (the physics' rule: at once, mid-frame too; docs/model.md)."""
        self.set_checked_trap_height(limits.TRAP_HEIGHT.check("trap_height", value))

    def set_checked_trap_height(self, height: float) -> None:
        """Move the rim to height, a float the caller has checked within limits.TRAP_HEIGHT
        (the game's slider range lies inside it): checked once, at the boundary."""
        self._engine.set_trap_height(height)

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

    # -- the room (the view places it: view/screen.py) ------------------------------------
    @property
    def origin_lift(self) -> float:
        """Height of the trap origin above the cup wall's lowest point: the first atom's
        radius (the lowest its centre can reach)."""
        return float(self._world.radius[0])

    def force_win(self) -> None:
        """Declare the gas condensed now (demonstrations and tests)."""
        self._engine.force_win()
