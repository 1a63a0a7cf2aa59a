"""What each event does to the stored states: pairs, walls, exits, cell crossings, the knife.

Each handler mirrors the ReferenceEngine method of the same event operation for
operation (the same kernels, the same order of the running energy sum) and says
which rows need new predictions; the driver makes them, in one place.

Kinds and statuses passed to compiled functions are NumPy scalars: Numba compiles a
function once per literal Python int it is called with.
"""

from __future__ import annotations

import math

import numpy as np

from evapcool.physics.fast.grid import link, neighbours, unlink
from evapcool.physics.fast.jit import K, entry, hot, part
from evapcool.physics.fast.predict import predict_crossing, predict_solo, scan, set_key
from evapcool.physics.fast.tables import KIND_CROSS_X
from evapcool.physics.world import (
    ESCAPED,
    EV_ESCAPE,
    EV_GONE,
    EV_KNIFE,
    EV_PAIR,
    EV_WALL,
    GONE,
    WALL_MIN_NORMAL_SPEED,
    WIN_DAMPING,
    WIN_DAMPING_MIN_SPEED,
    WIN_NORMAL_SPEED_FLOOR,
)

INF = math.inf
LOG_PAIR, LOG_WALL, LOG_ESCAPE, LOG_GONE, LOG_KNIFE = (
    np.int64(k) for k in (EV_PAIR, EV_WALL, EV_ESCAPE, EV_GONE, EV_KNIFE)
)
STATUS_ESCAPED, STATUS_GONE = np.int64(ESCAPED), np.int64(GONE)
NO_ATOM = np.int64(-1)


# -- small parts ----------------------------------------------------------------------
@hot
def move(i, t, tb):
    """Carry row i's stored state to time t (exact free flight, seed Eqs. 3-4)."""
    s = tb.state[i]
    g = tb.run[0].gravity
    dt = t - s.t
    s.x = K.flight_x(s.x, s.vx, dt)
    s.y = K.flight_y(s.y, s.vy, 0.5 * g, dt)
    s.vy = K.flight_vy(s.vy, g, dt)
    s.t = t
    tb.queued[i].arc_cross_t = -INF  # a new arc: none of its y crossings taken yet


@hot
def energy(i, tb):
    """1/2 m v^2 + m g y of row i from its stored state (seed Eq. 1)."""
    s = tb.state[i]
    return K.atom_energy(tb.queued[i].mass, s.y, s.vx, s.vy, tb.run[0].gravity)


@hot
def log_event(kind, a, b, t, tb):
    """One line in the event log (World indices), if the World records events."""
    run = tb.run[0]
    if run.record != 0:
        line = tb.log[run.n_log]
        line.kind = kind
        line.a = a
        line.b = b
        line.t = t
        run.n_log += 1


@hot
def clock_to(t, tb):
    """The event's time, never before the clock (the reference engine's max(t, time))."""
    run = tb.run[0]
    if t < run.time:
        t = run.time
    run.time = t
    return t


# -- leaving the trap -----------------------------------------------------------------
@part
def check_win(tb):
    """T < Tc(N) with the running energy sum (seed Eqs. 1 and 46)."""
    run = tb.run[0]
    n = run.n_trapped
    if run.won != 0 or n == 0:
        return
    if run.energy_sum / n < tb.tc_table[n]:
        run.won = 1


@entry
def leave_trap(i, status, tb):
    """Row i leaves the trapped set (escaped or gone): off the grid, new prediction, win check."""
    run = tb.run[0]
    tb.plan[i].status = status
    run.n_trapped -= 1
    run.energy_sum -= energy(i, tb)
    tb.state[i].count += 1
    unlink(i, tb)
    predict_solo(i, tb)  # off the grid: no pairs, no crossings
    predict_crossing(i, tb)
    set_key(i, tb)
    check_win(tb)


@hot
def knife(i, t, tb):
    """Remove trapped row i at once if its energy exceeds m g H; True if it went."""
    run = tb.run[0]
    if run.knife == 0:
        return False
    if not energy(i, tb) > tb.queued[i].mass * run.gravity * run.trap_height:
        return False
    log_event(LOG_KNIFE, tb.state[i].atom, NO_ATOM, t, tb)
    leave_trap(i, STATUS_GONE, tb)
    return True


# -- the events -----------------------------------------------------------------------
@hot
def pair_event(i, te, tb):
    """Row i's pair event at te: (first row to predict, second row), or (i, -1) if stale.

    The second row is knife-tested and predicted after the first, as in the
    reference engine (lower World index first).
    """
    run = tb.run[0]
    j = np.int64(tb.plan[i].partner)
    # partner_count holds the low 32 bits of the partner's count then.
    if run.won != 0 or (tb.state[j].count - tb.plan[i].partner_count) & 0xFFFFFFFF != 0:
        run.stale += 1  # the partner moved on (or pairs are over)
        return i, NO_ATOM
    lo, hi = (j, i) if tb.state[j].atom < tb.state[i].atom else (i, j)
    t = clock_to(te, tb)
    move(lo, t, tb)
    move(hi, t, tb)
    a = tb.state[lo]
    b = tb.state[hi]
    v = K.collide_pair(
        b.x - a.x, b.y - a.y, a.vx, a.vy, b.vx, b.vy, tb.queued[lo].mass, tb.queued[hi].mass
    )
    a.vx, a.vy, b.vx, b.vy = v
    run.pairs += 1
    a.count += 1
    b.count += 1
    log_event(LOG_PAIR, a.atom, b.atom, t, tb)
    if knife(lo, t, tb):
        return NO_ATOM, hi
    return lo, hi


@hot
def wall_event(i, te, tb):
    """Row i meets the wall at te: escape over the rim (SPEC 2.3) or bounce; row to predict."""
    run = tb.run[0]
    t = clock_to(te, tb)
    move(i, t, tb)
    s = tb.state[i]
    if abs(s.x) > run.x_rim:  # over the rim: escaped
        log_event(LOG_ESCAPE, s.atom, NO_ATOM, t, tb)
        leave_trap(i, STATUS_ESCAPED, tb)
        return NO_ATOM
    speed = math.sqrt(s.vx * s.vx + s.vy * s.vy)
    damped = run.won != 0 and speed >= WIN_DAMPING_MIN_SPEED  # seed Eq. (34)
    changes = damped or speed < WALL_MIN_NORMAL_SPEED  # the energy changes
    if changes:
        run.energy_sum -= energy(i, tb)
    if damped:  # with a floor on the normal speed (no collapse)
        w = K.settle_wall(s.x, s.vx, s.vy, run.curvature, 1.0 - WIN_DAMPING, WIN_NORMAL_SPEED_FLOOR)
    else:  # at least WALL_MIN_NORMAL_SPEED along the normal (no stall)
        w = K.bounce_wall(s.x, s.vx, s.vy, run.curvature, WALL_MIN_NORMAL_SPEED)
    s.vx, s.vy = w
    if changes:
        run.energy_sum += energy(i, tb)
    run.walls += 1
    s.count += 1
    log_event(LOG_WALL, s.atom, NO_ATOM, t, tb)
    return i


@hot
def exit_event(i, te, tb):
    """Escaped row i leaves the window at te: gone."""
    t = clock_to(te, tb)
    move(i, t, tb)
    tb.plan[i].status = STATUS_GONE
    tb.state[i].count += 1
    log_event(LOG_GONE, tb.state[i].atom, NO_ATOM, t, tb)


@hot
def crossing_event(i, te, tb):
    """Row i enters the next cell at te: refile it and scan the cells that came in reach.

    Only the row or column of cells beyond the new cell needs scanning (Smallenburg
    2022): pairs with the other neighbours are already held by i or by the partner.
    Changes no stored state; after the condensation the grid is no longer kept.
    """
    run = tb.run[0]
    run.crossings += 1
    if run.won != 0:
        return
    p = tb.plan[i]
    cx = np.int64(p.cell_x)
    cy = np.int64(p.cell_y)
    to = np.int64(p.cross_to)
    unlink(i, tb)
    if p.cross_axis == KIND_CROSS_X:
        link(i, to, cy, tb)
        beyond = 2 * to - cx
        _, _, y0, y1 = neighbours(beyond, cy, run)
        if 0 <= beyond < run.nx:
            scan(i, beyond, beyond, y0, y1, tb)
    else:
        link(i, cx, to, tb)
        tb.queued[i].arc_cross_t = te
        beyond = 2 * to - cy
        x0, x1, _, _ = neighbours(cx, beyond, run)
        if 0 <= beyond < run.ny:
            scan(i, x0, x1, beyond, beyond, tb)
