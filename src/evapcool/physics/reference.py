"""The reference engine: a full table of pair contact times, in NumPy.

Simple enough to check by reading: after every event the rows of the
atoms involved are recomputed against all others, and the next event is the
minimum of the pair table and the per-atom wall/exit times. O(N) work per
event plus an O(N^2) scan, fine up to a few hundred atoms. The compiled core
(core/*.c, physics/core.py) must reproduce its event sequence exactly.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from evapcool.physics import kernels as k
from evapcool.physics import model
from evapcool.physics import play as clock
from evapcool.physics.play import Play
from evapcool.physics.world import (
    ESCAPED,
    EV_ESCAPE,
    EV_GONE,
    EV_KNIFE,
    EV_PAIR,
    EV_WALL,
    GONE,
    TRAPPED,
    WALL_MIN_NORMAL_SPEED,
    WIN_DAMPING,
    WIN_DAMPING_MIN_SPEED,
    WIN_NORMAL_SPEED_FLOOR,
    World,
)

INF = math.inf


class ReferenceEngine:
    """Event-driven hard disks in a gravitational cup, one event at a time."""

    name = "reference"

    def __init__(self, world: World) -> None:
        self.w = world
        #: Atoms trapped at the end of the whole frame the win was seen in, and that frame.
        self.score: int | None = None
        self.win_frame: float | None = None
        self.play = Play()
        n = len(world.radius)
        self.pair = np.full((n, n), INF)
        self.solo = np.full(n, INF)  # wall time if trapped, exit time if escaped
        for i in range(n):
            self._predict_solo(i)
            if world.status[i] == TRAPPED:
                self.pair[i, :] = self._pair_row(i)
                self.pair[:, i] = self.pair[i, :]

    # -- predictions ----------------------------------------------------------
    def _pair_row(self, i: int) -> np.ndarray:
        """Contact times of atom i with every atom, mirroring kernels.pair_contact_time."""
        w = self.w
        g = w.gravity
        half_g = 0.5 * g
        x1, y1 = w.pos[i]
        vx1, vy1 = w.vel[i]
        t1 = w.t_atom[i]
        t2 = w.t_atom
        tr = np.where(t1 >= t2, t1, t2)
        d1 = tr - t1
        d2 = tr - t2
        rx = (x1 + vx1 * d1) - (w.pos[:, 0] + w.vel[:, 0] * d2)
        ry = (y1 + vy1 * d1 - half_g * d1 * d1) - (
            w.pos[:, 1] + w.vel[:, 1] * d2 - half_g * d2 * d2
        )
        vx = vx1 - w.vel[:, 0]
        vy = (vy1 - g * d1) - (w.vel[:, 1] - g * d2)
        b = rx * vx + ry * vy
        sigma = w.radius[i] + w.radius
        c = rx * rx + ry * ry - sigma * sigma
        vv = vx * vx + vy * vy
        disc = b * b - vv * c
        with np.errstate(invalid="ignore", divide="ignore"):
            t = tr + c / (np.sqrt(disc) - b)
        t = np.where(disc <= 0.0, INF, t)
        t = np.where(c <= 0.0, tr, t)
        t = np.where(b >= 0.0, INF, t)
        t[w.status != TRAPPED] = INF
        t[i] = INF
        return t

    def _predict_solo(self, i: int) -> None:
        w = self.w
        x, y = w.pos[i]
        vx, vy = w.vel[i]
        t0 = w.t_atom[i]
        if w.status[i] == TRAPPED:
            self.solo[i] = k.wall_contact_time(x, y, vx, vy, t0, w.curvature, w.gravity)
        elif w.status[i] == ESCAPED:
            xl, xr, yb = w.exit_bounds(i)
            self.solo[i] = k.exit_time(x, y, vx, vy, t0, w.gravity, xl, xr, yb)
        else:
            self.solo[i] = INF

    def _refresh(self, i: int) -> None:
        """Atom i changed velocity: recompute all its predictions."""
        self._predict_solo(i)
        row = self._pair_row(i)
        self.pair[i, :] = row
        self.pair[:, i] = row

    def _drop_pairs(self, i: int) -> None:
        self.pair[i, :] = INF
        self.pair[:, i] = INF

    # -- state changes --------------------------------------------------------
    def _move(self, i: int, t: float) -> None:
        """Carry atom i's stored state to time t (exact free flight)."""
        w = self.w
        dt = t - w.t_atom[i]
        x, y = w.pos[i]
        vx, vy = w.vel[i]
        w.pos[i, 0] = k.flight_x(x, vx, dt)
        w.pos[i, 1] = k.flight_y(y, vy, 0.5 * w.gravity, dt)
        w.vel[i, 1] = k.flight_vy(vy, w.gravity, dt)
        w.t_atom[i] = t

    def _energy(self, i: int) -> float:
        w = self.w
        return k.atom_energy(w.mass[i], w.pos[i, 1], w.vel[i, 0], w.vel[i, 1], w.gravity)

    def _log(self, kind: int, i: int, j: int, t: float) -> None:
        if self.w.record_events:
            self.w.log.append((kind, i, j, t))

    def _remove(self, i: int, status: int) -> None:
        """Atom i leaves the trapped set (escape over the rim or the knife)."""
        w = self.w
        w.status[i] = status
        w.n_trapped -= 1
        w.energy_sum -= self._energy(i)
        w.counter[i] += 1
        self._drop_pairs(i)
        self._predict_solo(i)
        self._check_win()

    def _check_win(self) -> None:
        """T < Tc(N) with the running energy sum (seed Eqs. 1 and 46)."""
        w = self.w
        if w.won or w.n_trapped == 0:
            return
        if w.energy_sum / w.n_trapped < w.win_threshold_of(w.n_trapped):
            w.won = True

    def _knife(self, i: int, t: float) -> bool:
        """Remove trapped atom i at once if its energy exceeds m g H."""
        w = self.w
        if w.knife and self._energy(i) > w.mass[i] * w.gravity * w.trap_height:
            self._log(EV_KNIFE, i, -1, t)
            self._remove(i, GONE)
            return True
        return False

    def _pair_event(self, i: int, j: int, t: float) -> None:
        w = self.w
        self._move(i, t)
        self._move(j, t)
        rx = w.pos[j, 0] - w.pos[i, 0]
        ry = w.pos[j, 1] - w.pos[i, 1]
        v = k.collide_pair(
            rx, ry, w.vel[i, 0], w.vel[i, 1], w.vel[j, 0], w.vel[j, 1], w.mass[i], w.mass[j]
        )
        w.vel[i, 0], w.vel[i, 1], w.vel[j, 0], w.vel[j, 1] = v
        w.pair_count += 1
        w.counter[i] += 1
        w.counter[j] += 1
        self._log(EV_PAIR, i, j, t)
        for a in (i, j):
            if not self._knife(a, t):
                self._refresh(a)

    def _wall_event(self, i: int, t: float) -> None:
        w = self.w
        self._move(i, t)
        x = w.pos[i, 0]
        if abs(x) > w.rim_half_width:
            self._log(EV_ESCAPE, i, -1, t)
            self._remove(i, ESCAPED)
            return
        vx, vy = w.vel[i]
        speed = math.sqrt(vx * vx + vy * vy)
        if w.won and speed >= WIN_DAMPING_MIN_SPEED:
            # Damped (seed Eq. 34), with a floor on the normal speed (no collapse).
            w.energy_sum -= self._energy(i)
            w.vel[i, 0], w.vel[i, 1] = k.settle_wall(
                x, vx, vy, w.curvature, 1.0 - WIN_DAMPING, WIN_NORMAL_SPEED_FLOOR
            )
            w.energy_sum += self._energy(i)
        elif speed < WALL_MIN_NORMAL_SPEED:  # at rest on the wall: gains up to v_min
            w.energy_sum -= self._energy(i)
            w.vel[i, 0], w.vel[i, 1] = k.bounce_wall(x, vx, vy, w.curvature, WALL_MIN_NORMAL_SPEED)
            w.energy_sum += self._energy(i)
        else:
            w.vel[i, 0], w.vel[i, 1] = k.bounce_wall(x, vx, vy, w.curvature, WALL_MIN_NORMAL_SPEED)
        w.wall_count += 1
        w.counter[i] += 1
        self._log(EV_WALL, i, -1, t)
        self._refresh(i)

    def _exit_event(self, i: int, t: float) -> None:
        w = self.w
        self._move(i, t)
        w.status[i] = GONE
        w.counter[i] += 1
        self.solo[i] = INF
        self._log(EV_GONE, i, -1, t)

    # -- public -----------------------------------------------------------------
    def advance_to(self, t_end: float) -> None:
        """Process every event with time <= t_end in time order, then set the clock."""
        w = self.w
        n = len(self.solo)
        while True:
            i = int(np.argmin(self.solo))
            ts = self.solo[i]
            tp = INF
            if not w.won and n > 1:
                flat = int(np.argmin(self.pair))
                tp = self.pair.flat[flat]
            if tp < ts:
                if tp > t_end:
                    break
                t = max(tp, w.time)
                w.time = t
                a, b = divmod(flat, n)
                self._pair_event(a, b, t)
            else:
                if ts > t_end:
                    break
                t = max(ts, w.time)
                w.time = t
                if w.status[i] == TRAPPED:
                    self._wall_event(i, t)
                else:
                    self._exit_event(i, t)
        w.time = t_end

    def force_win(self) -> None:
        """Latch the win now (demonstrations and tests)."""
        self.w.won = True

    def set_trap_height(self, height: float) -> None:
        """New rim height; with the knife rule, atoms above m g H go at once."""
        w = self.w
        w.trap_height = height
        if not w.knife:
            return
        e = w.energies()
        over = np.flatnonzero((w.status == TRAPPED) & (e > w.mass * w.gravity * height))
        for i in over:
            self._log(EV_KNIFE, int(i), -1, w.time)
            self._remove(int(i), GONE)

    # -- the game's clock: physics/play.py, the oracle of core/play.c ------------------------
    def play_to(self, end: float, on_frame: Callable[[float], None] | None) -> None:
        clock.play_to(self, end, on_frame)

    def ask_height(self, height: float, now: bool) -> bool:
        return clock.ask_height(self, height, now)

    @property
    def asked_height(self) -> float:
        return clock.asked_height(self)

    def hold(self, runs: Sequence[tuple[float, float]]) -> None:
        clock.hold(self, runs)

    def moves(self) -> list[tuple[float, int]]:
        return clock.moves(self)

    # -- the game's frame: the readable rule core/game.c runs, its oracle -------------------
    def frame(self, height: float) -> None:
        """One whole frame from a whole frame, the trap at height during it: the height takes
        effect at the frame's start (not after the win: the score is the atoms left), and the
        frame's end sees the win and fixes the score (game/rules.py's rule)."""
        w = self.w
        if not w.won and height != w.trap_height:
            self.set_trap_height(height)
        self.advance_to(math.floor(w.time) + 1.0)
        self.frame_end()

    def frame_end(self) -> None:
        """The end of a whole frame: a win latched during it is seen now and the score fixed
        at the atoms trapped now (one on its way over the rim may still leave; it stays)."""
        if self.w.won and self.score is None:
            self.score = self.w.n_trapped
            self.win_frame = self.w.time

    def replay(self, runs: np.ndarray, limit: int) -> int:
        """Hold each (height, frames) run's height for that many whole frames, from a whole
        frame, up to the end of the frame the win is seen in or `limit` frames: the frames
        played."""
        frames = 0
        for height, n in runs.tolist():
            for _ in range(int(n)):
                if frames >= limit:
                    return frames
                self.frame(height)
                frames += 1
                if self.score is not None:
                    return frames
        return frames

    def path(self, runs: np.ndarray, limit: int, stride: int, h0: float) -> tuple[int, np.ndarray]:
        """The game's path in the (N, T) plane, the oracle of core_path: the runs played as
        `replay` plays them, keeping (k, N, T, h) at frame 0 (height h0), every stride-th
        frame, the last and the win's, where N > 0 and T is finite and positive."""
        w = self.w
        points: list[tuple[float, float, float, float]] = []

        def keep(k: int, h: float) -> None:
            n = w.n_trapped
            t = float(np.sum(w.energies()[w.status == TRAPPED])) / n if n else 0.0
            if n > 0 and math.isfinite(t) and t > 0:
                points.append((k, n, t, h))

        keep(0, h0)
        k = 0
        for height, n_frames in runs.tolist():
            for _ in range(int(n_frames)):
                if k >= limit or self.score is not None:
                    return k, np.array(points, dtype=np.float64).reshape(-1, 4)
                self.frame(height)
                k += 1
                if k % stride == 0 or k == limit or self.score is not None:
                    keep(k, height)
        return k, np.array(points, dtype=np.float64).reshape(-1, 4)

    # -- the reach rule: the readable rule core_out_of_reach runs, its oracle ---------------
    def out_of_reach(self, lowest: float, height: float) -> int:
        """The reach rule (model.REACH_*) with the lowest rim the player can set and the rim
        now; never once won, nor without the win rule (REACH_WITHIN)."""
        w = self.w
        if w.won or not w.win_rule:
            return model.REACH_WITHIN
        n, trapped, g = w.n_trapped, w.status == TRAPPED, w.gravity
        m = float(w.mass[trapped].min()) if n else 1.0
        energy, tc = float(np.sum(w.energies()[trapped])), w.critical_temperature_of(n)
        return out_of_reach(n, energy, tc, m * g * lowest, m * g * height)


def out_of_reach(
    n: int, energy: float, tc: float, escape_energy: float, trap_energy: float | None = None
) -> int:
    """Why T < Tc can no longer be reached by n trapped atoms of total energy E (REACH_*).

    T = E / N (seed Eq. 1) changes only when atoms leave, each carrying more than
    escape_energy = m g H_min (m the lightest mass, H_min the slider's floor); with n >= 2
    and E above it one may leave with nearly all of it. Out of reach: no atom left; one above
    Tc(1) (alone it never collides); T >= Tc(N) with E <= escape_energy. E <= trap_energy
    (m g H now): none can leave until the trap is lowered (REACH_STUCK_HERE, not a loss)."""
    if n <= 0:
        return model.REACH_ALL_ESCAPED
    if energy / n < tc:
        return model.REACH_WITHIN  # condensing now
    if n == 1:
        return model.REACH_ONE_ATOM
    if energy <= escape_energy:
        return model.REACH_STUCK
    if trap_energy is not None and energy <= trap_energy:
        return model.REACH_STUCK_HERE
    return model.REACH_WITHIN
