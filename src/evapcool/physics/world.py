"""The complete mutable state of a simulation, shared by both engines.

Arrays hold each atom's state at its own last-event time (lazy update);
scalars hold the clock, the trap, the running sums and the counters. The
engines (reference.py, core.py) move this state forward; nothing else does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from evapcool.physics.kernels import flight_vy, flight_x, flight_y
from evapcool.physics.model import (
    ESCAPE_RULES,
    ESCAPED,
    EV_ESCAPE,
    EV_GONE,
    EV_KNIFE,
    EV_PAIR,
    EV_WALL,
    EVENT_NAMES,
    GONE,
    TRAPPED,
    WALL_MIN_NORMAL_SPEED,
    WIN_DAMPING,
    WIN_DAMPING_MIN_SPEED,
    WIN_NORMAL_SPEED_FLOOR,
)
from evapcool.physics.portable import power
from evapcool.physics.room import Room

# The lifecycle (SPEC 2.3), the event log's kinds, the escape rules and the wall's and the
# win's numbers are the core's (core/evapcool_core.h, generated into model.py).
__all__ = [
    "ESCAPED",
    "ESCAPE_RULES",
    "EVENT_NAMES",
    "EV_ESCAPE",
    "EV_GONE",
    "EV_KNIFE",
    "EV_PAIR",
    "EV_WALL",
    "GONE",
    "TRAPPED",
    "WALL_MIN_NORMAL_SPEED",
    "WIN_DAMPING",
    "WIN_DAMPING_MIN_SPEED",
    "WIN_NORMAL_SPEED_FLOOR",
    "World",
    "WorldRules",
    "world_in",
]


@dataclass
class World:
    """Arrays of atoms plus the global clock, trap and bookkeeping."""

    pos: np.ndarray  # (N, 2) stored position at t_atom
    vel: np.ndarray  # (N, 2) stored velocity at t_atom
    radius: np.ndarray  # (N,)
    mass: np.ndarray  # (N,)
    curvature: float  # a, per px
    gravity: float  # g, px / frame^2
    trap_height: float  # H, px above the lowest centre position
    x_left: float  # window left edge, trap x
    x_right: float  # window right edge, trap x
    y_bottom: float  # window bottom edge, trap y
    tc_exponent: float = 2.0 / 3.0
    escape_rule: str = "rim"
    record_events: bool = False
    win_rule: bool = True  # False: T < Tc never ends the gas (lab runs past Tc)
    t_atom: np.ndarray = field(init=False)
    status: np.ndarray = field(init=False)
    counter: np.ndarray = field(init=False)  # events per atom (lazy invalidation)
    time: float = 0.0
    won: bool = False
    pair_count: int = 0
    wall_count: int = 0
    n_initial: int = field(init=False)
    n_trapped: int = field(init=False)
    energy_sum: float = field(init=False)  # running sum over trapped atoms
    initial_temperature: float = field(init=False)
    tc0: float = field(init=False)
    log: list[tuple[int, int, int, float]] = field(default_factory=list)

    def __post_init__(self) -> None:
        n = len(self.radius)
        self.t_atom = np.zeros(n)
        self.status = np.full(n, TRAPPED, dtype=np.int8)
        self.counter = np.zeros(n, dtype=np.int64)
        self.n_initial = n
        self.n_trapped = n
        self.energy_sum = self.sequential_energy_sum()
        self.initial_temperature = self.energy_sum / n
        # seed Eq. (46): Tc0 is 3/4 of the starting temperature.
        self.tc0 = 0.75 * self.initial_temperature

    # -- derived quantities -------------------------------------------------
    @property
    def rim_half_width(self) -> float:
        """x_rim = sqrt(H / a); the wall ends there."""
        return math.sqrt(self.trap_height / self.curvature)

    @property
    def knife(self) -> bool:
        return self.escape_rule == "knife"

    def energies(self) -> np.ndarray:
        """1/2 m v^2 + m g y of every atom from its stored state (conserved in flight)."""
        v = self.vel
        energies: np.ndarray = 0.5 * self.mass * (v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1]) + (
            self.mass * self.gravity * self.pos[:, 1]
        )
        return energies

    def sequential_energy_sum(self) -> float:
        """Sum of trapped energies, added in index order (engines continue it)."""
        e = self.energies()
        total = 0.0
        for i in np.flatnonzero(self.status == TRAPPED):
            total += float(e[i])
        return total

    def critical_temperature_of(self, n: int) -> float:
        """Tc(N) = Tc0 (N / N0)^p, seed Eq. (46) with exponent p."""
        return self.tc0 * power(n / self.n_initial, self.tc_exponent)

    def win_threshold_of(self, n: int) -> float:
        """The temperature below which N atoms have won: Tc(N), or -inf without the win rule."""
        return self.critical_temperature_of(n) if self.win_rule else -math.inf

    def state_at(self, idx: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities of atoms idx carried to time t (no mutation)."""
        dt = t - self.t_atom[idx]
        p = self.pos[idx]
        v = self.vel[idx]
        out_p = np.empty_like(p)
        out_v = v.copy()
        out_p[:, 0] = flight_x(p[:, 0], v[:, 0], dt)
        out_p[:, 1] = flight_y(p[:, 1], v[:, 1], 0.5 * self.gravity, dt)
        out_v[:, 1] = flight_vy(v[:, 1], self.gravity, dt)
        return out_p, out_v

    def exit_bounds(self, i: int) -> tuple[float, float, float]:
        """Window edges for atom i's centre, pushed out by its radius."""
        r = float(self.radius[i])
        return self.x_left - r, self.x_right + r, self.y_bottom - r


class WorldRules(Protocol):
    """A World's rules by the names a SimulationConfig and a saved state both give them."""

    @property
    def curvature(self) -> float: ...
    @property
    def gravity(self) -> float: ...
    @property
    def trap_height(self) -> float: ...
    @property
    def tc_exponent(self) -> float: ...
    @property
    def escape(self) -> str: ...
    @property
    def win(self) -> bool: ...


def world_in(
    room: Room,
    rules: WorldRules,
    atoms: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    record_events: bool,
) -> World:
    """A World of atoms (positions, velocities, radii, masses) under rules, its escape box
    room's for the first atom's radius (the trap origin's height above the wall)."""
    pos, vel, radius, mass = atoms
    x_left, x_right, y_bottom = room.escape_box(float(radius[0]))
    return World(
        pos=pos,
        vel=vel,
        radius=radius,
        mass=mass,
        curvature=rules.curvature,
        gravity=rules.gravity,
        trap_height=rules.trap_height,
        x_left=x_left,
        x_right=x_right,
        y_bottom=y_bottom,
        tc_exponent=rules.tc_exponent,
        escape_rule=rules.escape,
        record_events=record_events,
        win_rule=rules.win,
    )
