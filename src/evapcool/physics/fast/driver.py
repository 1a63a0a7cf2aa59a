"""The compiled entry points: the event loop, setting up, upkeep, and copying to and from the World.

`advance` processes events in key order until t_end and mirrors
ReferenceEngine.advance_to event for event. It returns to Python when the log
buffer is nearly full or upkeep is due (`maintain`, compiled only when first
needed), so neither weighs on the loop or on the first start.
"""

from __future__ import annotations

import math

import numpy as np

from evapcool.physics.fast.calendar import bin_width, next_bin, refile_all, walk_ahead
from evapcool.physics.fast.events import (
    NO_ATOM,
    crossing_event,
    exit_event,
    knife,
    pair_event,
    wall_event,
)
from evapcool.physics.fast.grid import cell_at, link
from evapcool.physics.fast.jit import K, entry, hot, part
from evapcool.physics.fast.lookahead import after_event, ask_bin, before_event
from evapcool.physics.fast.predict import predict, predict_crossing, predict_real, set_key
from evapcool.physics.fast.tables import (
    KIND_EXIT,
    KIND_NONE,
    KIND_PAIR,
    KIND_WALL,
    RANK_CROSS,
    Tables,
)
from evapcool.physics.world import TRAPPED

INF = math.inf

# What advance() returns.
DONE = np.int64(0)  # every event up to t_end processed
LOG_FULL = np.int64(1)  # the log buffer needs emptying first
UPKEEP = np.int64(2)  # maintain() is due

#: The most log lines one event can write (a pair and two knives).
LOG_ROOM = 4


# -- the event loop -------------------------------------------------------------------
@part
def _event_kind(i, tb):
    p = tb.plan[i]
    return p.cross_axis if p.rank == RANK_CROSS else p.real_kind


@part
def _handle(i, kind, te, tb):
    """Process row i's event of this kind at te: (row to predict, whether fully, second row).

    A crossing leaves the real event standing: only the next crossing is predicted.
    """
    if kind == KIND_PAIR:
        first, second = pair_event(i, te, tb)
        return first, True, second
    if kind == KIND_WALL:
        return wall_event(i, te, tb), True, NO_ATOM
    if kind == KIND_EXIT:
        exit_event(i, te, tb)
        return i, True, NO_ATOM
    crossing_event(i, te, tb)  # KIND_CROSS_X or KIND_CROSS_Y
    return i, False, NO_ATOM


@hot
def _repredict(first, full, second, tb):
    """New predictions after an event, in one place: every inlined copy costs code.

    The first row's (full, or only its crossing), then the second row's (a pair's
    higher atom) after its knife test.
    """
    row = first
    while True:
        if row >= 0:
            if full:
                predict_real(row, tb)
            predict_crossing(row, tb)
            set_key(row, tb)
        if second < 0:
            return
        row = second
        second = NO_ATOM
        full = True
        if knife(row, tb.run[0].time, tb):
            row = NO_ATOM


@part
def advance(t_end, tb):
    """Process every event with time <= t_end in key order; DONE, LOG_FULL or UPKEEP."""
    run = tb.run[0]
    room = tb.log.shape[0] - LOG_ROOM if run.record != 0 else 1 << 62
    deep = run.deep != 0
    while True:
        if run.n_log > room:
            return LOG_FULL
        if run.since_maintain >= run.maintain_every:
            return UPKEEP
        run.since_maintain += 1
        if run.heap_size == 0:
            if not next_bin(tb):
                return DONE  # no atom has an event
            ask_bin(tb)
        i = tb.heap[0].row
        te = tb.heap[0].t
        kind = _event_kind(i, tb)
        if not te <= t_end or kind == KIND_NONE:  # (a key with no event cannot happen)
            return DONE
        nxt = before_event(i, kind, tb)
        first, full, second = _handle(i, kind, te, tb)
        after_event(nxt, tb)
        _repredict(first, full, second, tb)
        walk_ahead(deep, tb)


# -- setting up and upkeep ------------------------------------------------------------
@part
def _forget_events(i, tb):
    """Row i with no pending event and no cell (its status and World index kept)."""
    q = tb.queued[i]
    q.key_t = INF
    q.real_t = INF
    q.cross_t = INF
    q.arc_cross_t = -INF
    p = tb.plan[i]
    p.rank = 0
    p.tie_a = p.atom
    p.tie_b = 0
    p.real_rank = 0
    p.real_a = 0
    p.real_b = 0
    p.real_kind = 0
    p.partner = 0
    p.partner_count = 0
    p.cross_axis = 0
    p.cross_to = 0
    p.cell_prev = -1


@part
def setup(tb):
    """File trapped atoms in their cells (positions at the clock time), predict every atom."""
    run = tb.run[0]
    now = run.time
    tb.cells[:] = -1
    for i in range(tb.state.shape[0]):
        _forget_events(i, tb)
        if tb.plan[i].status == TRAPPED:
            s = tb.state[i]
            dt = now - s.t
            x = K.flight_x(s.x, s.vx, dt)
            y = K.flight_y(s.y, s.vy, 0.5 * run.gravity, dt)
            cx, cy = cell_at(x, y, run)
            link(i, cx, cy, tb)
    # Every finite key in the heap for now (bin width inf), the bins set after.
    refile_all(now, INF, tb)
    for i in range(tb.state.shape[0]):
        predict(i, tb)
    refile_all(now, bin_width(now, tb), tb)


@part
def _cell_order(sp, rows, tb):
    """new_row[row]: rows in cell order (row-major), the atoms off the grid last.

    Returns how many rows are in cells (they come first).
    """
    n = tb.state.shape[0]
    n_cells = tb.cells.shape[0] - n
    sp.new_row[:] = -1
    k = 0
    for c in range(n_cells):
        j = tb.cells[c]
        while j >= 0:
            sp.new_row[j] = k
            k += 1
            j = tb.cells[n_cells + j]
    linked = k
    for w in range(n):
        j = rows[w]
        if sp.new_row[j] < 0:
            sp.new_row[j] = k
            k += 1
    return linked


@part
def _move_rows(sp, rows, tb):
    """Every row j to row new_row[j], in all three tables; references relabelled."""
    n = tb.state.shape[0]
    for j in range(n):
        sp.state[j] = tb.state[j]
        sp.queued[j] = tb.queued[j]
        sp.plan[j] = tb.plan[j]
    for j in range(n):
        r = sp.new_row[j]
        tb.state[r] = sp.state[j]
        tb.queued[r] = sp.queued[j]
        tb.plan[r] = sp.plan[j]
    for i in range(n):
        tb.plan[i].partner = sp.new_row[tb.plan[i].partner]
    for w in range(n):
        rows[w] = sp.new_row[rows[w]]


@entry
def maintain(spares, rows, *tables):
    """Renumber the rows in cell order and refile the queue with a fresh bin width.

    Atoms of neighbouring cells then sit next to each other in memory, so the pair
    scans of big systems hit the cache. Cell lists are rebuilt in ascending row order.
    The events, their keys and the in-cell order's irrelevance (a scan keeps the least
    (t, rank, lo, hi) whatever order it meets the pairs in) leave the event sequence
    unchanged.
    """
    tb = Tables(*tables)
    now = tb.run[0].time
    linked = _cell_order(spares, rows, tb)
    _move_rows(spares, rows, tb)
    tb.cells[:] = -1
    for i in range(tb.state.shape[0]):
        tb.plan[i].cell_prev = -1
    for i in range(linked - 1, -1, -1):  # linking in descending order: lists ascend
        link(i, np.int64(tb.plan[i].cell_x), np.int64(tb.plan[i].cell_y), tb)
    refile_all(now, bin_width(now, tb), tb)
    tb.run[0].since_maintain = 0


@part
def knife_all(rows, tb):
    """The knife at the clock time, in ascending World index."""
    for w in range(rows.shape[0]):
        i = rows[w]
        if tb.plan[i].status == TRAPPED:
            knife(i, tb.run[0].time, tb)


# -- World <-> tables -----------------------------------------------------------------
@part
def _pull(world_scalars, world_arrays, tb):
    """The World's state -> tables (FastEngine._scalars and _arrays give the order; the
    arrays end with rows, the row of each World atom)."""
    time, energy_sum, x_rim, trap_height, won, n_trapped, pairs, walls = world_scalars
    pos, vel, t_atom, status, counter, rows = world_arrays
    run = tb.run[0]
    run.time = time
    run.energy_sum = energy_sum
    run.x_rim = x_rim
    run.trap_height = trap_height
    run.won = won
    run.n_trapped = n_trapped
    run.pairs = pairs
    run.walls = walls
    for w in range(rows.shape[0]):
        i = rows[w]
        s = tb.state[i]
        s.x = pos[w, 0]
        s.y = pos[w, 1]
        s.vx = vel[w, 0]
        s.vy = vel[w, 1]
        s.t = t_atom[w]
        s.count = counter[w]
        tb.plan[i].status = status[w]


@part
def _push(status_code, world_arrays, tb):
    """Tables -> the World's arrays; returns what goes back to Python (see FastEngine)."""
    pos, vel, t_atom, status, counter, rows = world_arrays
    for w in range(rows.shape[0]):
        i = rows[w]
        s = tb.state[i]
        pos[w, 0] = s.x
        pos[w, 1] = s.y
        vel[w, 0] = s.vx
        vel[w, 1] = s.vy
        t_atom[w] = s.t
        counter[w] = s.count
        status[w] = tb.plan[i].status
    run = tb.run[0]
    n_log = run.n_log
    run.n_log = 0
    return (
        status_code, n_log, run.time, run.energy_sum, run.won != 0, run.n_trapped,
        run.pairs, run.walls,
    )  # fmt: skip


# -- entry points from Python ---------------------------------------------------------
@entry
def start(world_scalars, world_arrays, *tables):
    """Take the World's state and set everything up from it."""
    tb = Tables(*tables)
    _pull(world_scalars, world_arrays, tb)
    setup(tb)


@entry
def run_until(t_end, world_scalars, world_arrays, *tables):
    """Take the World's state, process events up to t_end, give the state back.

    Returns (DONE, LOG_FULL or UPKEEP, log lines written, then the World's scalars);
    on DONE the clock is at t_end.
    """
    tb = Tables(*tables)
    _pull(world_scalars, world_arrays, tb)
    status = advance(t_end, tb)
    if status == DONE:
        tb.run[0].time = t_end
    return _push(status, world_arrays, tb)


@entry
def knife_now(world_scalars, world_arrays, *tables):
    """Take the World's state, apply the knife to every trapped atom, give the state back."""
    tb = Tables(*tables)
    _pull(world_scalars, world_arrays, tb)
    knife_all(world_arrays[5], tb)
    return _push(DONE, world_arrays, tb)


@entry
def grid_errors(now, *tables):
    """Trapped atoms filed more than one cell away from the cell of their centre now."""
    tb = Tables(*tables)
    run = tb.run[0]
    bad = 0
    for i in range(tb.state.shape[0]):
        p = tb.plan[i]
        if p.status != TRAPPED:
            continue
        s = tb.state[i]
        dt = now - s.t
        x = K.flight_x(s.x, s.vx, dt)
        y = K.flight_y(s.y, s.vy, 0.5 * run.gravity, dt)
        cx, cy = cell_at(x, y, run)
        if abs(cx - p.cell_x) > 1 or abs(cy - p.cell_y) > 1:
            bad += 1
    return bad
