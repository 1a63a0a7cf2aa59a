"""Predictions: every atom's next real event and next cell crossing, from stored states only.

Each atom keeps two pending events: its real event (the earliest of its wall contact,
or exit if escaped, and its pair contacts with the atoms of the 3 x 3 cells around
it) and its next cell crossing. It is filed in the calendar under the earlier one.
Predictions are functions of stored states only, never of the moment they are made:
that is what makes the events bit-identical to the reference engine's.
"""

from __future__ import annotations

import math

import numpy as np

from evapcool.physics.fast.calendar import file_atom
from evapcool.physics.fast.grid import cell_index, neighbours
from evapcool.physics.fast.jit import K, hot, part
from evapcool.physics.fast.tables import (
    KIND_CROSS_X,
    KIND_CROSS_Y,
    KIND_EXIT,
    KIND_NONE,
    KIND_PAIR,
    KIND_WALL,
    RANK_CROSS,
    RANK_PAIR,
    RANK_SOLO,
)
from evapcool.physics.world import ESCAPED, TRAPPED

INF = math.inf


@hot
def scan(i, x0, x1, y0, y1, tb):
    """Pairs of trapped row i with the atoms of cells [x0, x1] x [y0, y1].

    Contact times are seed Eqs. (15)-(19) (kernels.pair_contact_time); an earlier pair
    replaces i's real event. On a tie the solo event stays and pairs go in (lower,
    higher) World index order, as in the reference engine.
    """
    run = tb.run[0]
    g = run.gravity
    n_cells = tb.cells.shape[0] - tb.state.shape[0]
    me = tb.state[i]
    plan = tb.plan[i]
    best_t = tb.queued[i].real_t
    is_pair = plan.real_rank == RANK_PAIR
    best_lo = plan.real_a
    best_hi = plan.real_b
    best = -1
    for cy in range(y0, y1 + 1):
        for c in range(cell_index(x0, cy, run), cell_index(x1, cy, run) + 1):
            j = tb.cells[c]
            while j >= 0:
                if j != i:
                    other = tb.state[j]
                    t = K.pair_contact_time(
                        me.x, me.y, me.vx, me.vy, me.t,
                        other.x, other.y, other.vx, other.vy, other.t,
                        me.radius + other.radius, g,
                    )  # fmt: skip
                    if t <= best_t:  # rare: only now read the World indices
                        lo = min(me.atom, other.atom)
                        hi = max(me.atom, other.atom)
                        if t < best_t or (
                            is_pair and (lo < best_lo or (lo == best_lo and hi < best_hi))
                        ):
                            best_t = t
                            is_pair = True
                            best_lo = lo
                            best_hi = hi
                            best = j
                j = tb.cells[n_cells + j]
    if best >= 0:
        tb.queued[i].real_t = best_t
        plan.real_rank = RANK_PAIR
        plan.real_a = best_lo
        plan.real_b = best_hi
        plan.real_kind = KIND_PAIR
        plan.partner = best
        plan.partner_count = tb.state[best].count  # the low 32 bits


@hot
def predict_solo(i, tb):
    """Row i's solo event: the wall (SPEC 2.1) if trapped, the exit if escaped, else none."""
    run = tb.run[0]
    s = tb.state[i]
    plan = tb.plan[i]
    t = INF
    kind = KIND_NONE
    if plan.status == TRAPPED:
        t = K.wall_contact_time(s.x, s.y, s.vx, s.vy, s.t, run.curvature, run.gravity)
        kind = KIND_WALL
    elif plan.status == ESCAPED:
        r = s.radius
        t = K.exit_time(
            s.x, s.y, s.vx, s.vy, s.t, run.gravity,
            run.x_left - r, run.x_right + r, run.y_bottom - r,
        )  # fmt: skip
        kind = KIND_EXIT
    tb.queued[i].real_t = t
    plan.real_rank = RANK_SOLO
    plan.real_a = plan.atom
    plan.real_b = 0
    plan.real_kind = kind


@hot
def predict_real(i, tb):
    """Row i's real event: its solo event or, if earlier, a pair (trapped, game on)."""
    predict_solo(i, tb)
    plan = tb.plan[i]
    run = tb.run[0]
    if plan.status == TRAPPED and run.won == 0:
        x0, x1, y0, y1 = neighbours(np.int64(plan.cell_x), np.int64(plan.cell_y), run)
        scan(i, x0, x1, y0, y1, tb)


@part
def _crossing_x(s, cx, run):
    """(time, column entered) of the next crossing of a column edge; (inf, 0) if none.

    A straight line to the next edge in the direction of vx; the edge columns have no
    outer edge.
    """
    if s.vx > 0.0 and cx < run.nx - 1:
        return s.t + ((run.grid_x0 + (cx + 1) * run.cell) - s.x) / s.vx, cx + 1
    if s.vx < 0.0 and cx > 0:
        return s.t + ((run.grid_x0 + cx * run.cell) - s.x) / s.vx, cx - 1
    return INF, 0


@part
def _crossing_y(s, cy, taken, run):
    """(time, row entered) of the next crossing of a row edge; (inf, 0) if none.

    Up through the top edge (the first root, if the arc really passes it: a grazing
    arc with equal roots stays below), else down through the bottom edge; roots at or
    before `taken`, the arc's last y crossing, are ones already taken. Roots in the
    cancellation-free form. The top row (the attic) has no top edge, row 0 no bottom.
    """
    g = run.gravity
    vy = s.vy
    if vy > 0.0 and cy < run.ny - 1:
        d = (run.grid_y0 + (cy + 1) * run.cell) - s.y
        disc = vy * vy - 2.0 * g * d
        if disc > 0.0:
            root = math.sqrt(disc)
            t1 = s.t + 2.0 * d / (vy + root)
            t2 = s.t + (vy + root) / g
            if t2 > t1 and t1 > taken:
                return t1, cy + 1
    if cy > 0:
        h = s.y - (run.grid_y0 + cy * run.cell)
        disc = vy * vy + 2.0 * g * h
        if disc < 0.0:
            disc = 0.0
        root = math.sqrt(disc)
        if vy > 0.0:
            t2 = s.t + (vy + root) / g
        elif root - vy > 0.0:
            t2 = s.t + 2.0 * h / (root - vy)
        else:
            t2 = s.t
        if t2 > taken:
            return t2, cy - 1
    return INF, 0


@hot
def predict_crossing(i, tb):
    """Row i's next cell crossing (none unless trapped and the game is on); x first on a tie."""
    run = tb.run[0]
    plan = tb.plan[i]
    t = INF
    axis = KIND_NONE
    to = 0
    if plan.status == TRAPPED and run.won == 0:
        s = tb.state[i]
        t, to = _crossing_x(s, plan.cell_x, run)
        if t < INF:
            axis = KIND_CROSS_X
        ty, to_y = _crossing_y(s, plan.cell_y, tb.queued[i].arc_cross_t, run)
        if ty < t:
            t = ty
            to = to_y
            axis = KIND_CROSS_Y
    tb.queued[i].cross_t = t
    plan.cross_axis = axis
    plan.cross_to = to


@hot
def set_key(i, tb):
    """Row i's key is the earlier of its crossing and its real event; refile it."""
    q = tb.queued[i]
    plan = tb.plan[i]
    if q.cross_t <= q.real_t:  # a crossing goes first on a tie
        q.key_t = q.cross_t
        plan.rank = RANK_CROSS
        plan.tie_a = plan.atom
        plan.tie_b = plan.cross_axis
    else:
        q.key_t = q.real_t
        plan.rank = plan.real_rank
        plan.tie_a = plan.real_a
        plan.tie_b = plan.real_b
    file_atom(i, q.key_t, tb)


@hot
def predict(i, tb):
    """Everything about row i from its stored state; store it and refile it."""
    predict_real(i, tb)
    predict_crossing(i, tb)
    set_key(i, tb)
