"""Asking for memory ahead of the event loop: no effect on results, only on speed.

At 10^4 to 10^5 atoms the tables outgrow the caches the core has to itself, and an
event would start by waiting for its atom's records, its partner's, and the heads
of the cells it scans. The loop therefore asks (jit.prefetch) for the records the
next event will read while the current one is processed: the next event is most
likely the root's earliest child in the heap. From DEEP_MIN_ATOMS atoms on (run.deep)
it also asks, two events ahead, for the cell heads and first atoms of the scans.
"""

from __future__ import annotations

import math

import numpy as np

from evapcool.physics.fast.grid import cell_index, neighbours
from evapcool.physics.fast.jit import hot, part, prefetch
from evapcool.physics.fast.tables import KIND_CROSS_X, KIND_CROSS_Y, KIND_PAIR, RANK_CROSS
from evapcool.physics.world import TRAPPED

INF = math.inf

#: From this many atoms the tables are far beyond the caches the core has to itself,
#: and the loop asks two events ahead for the rows the scans will read (with fewer
#: atoms they are found in cache anyway, and the asking only costs time).
DEEP_MIN_ATOMS = 20_000


@hot
def ask_atom(j, tb):
    """Start loading all three records of row j."""
    prefetch(tb.state, j)
    prefetch(tb.queued, j)
    prefetch(tb.plan, j)


@part
def ask_bin(tb):
    """A new bin's atoms are the next few events: start loading their records."""
    for p in range(tb.run[0].heap_size):
        prefetch(tb.plan, tb.heap[p].row)
        prefetch(tb.state, tb.heap[p].row)


@hot
def _coming_cells(j, tb):
    """The block of cells row j's next event will scan: (x0, x1, y0, y1), empty if y0 > y1.

    A crossing scans the row or column beyond its new cell; other events the 3 x 3
    block around it (a pair's partner scans around its own cell, not included).
    Nothing for atoms off the grid.
    """
    run = tb.run[0]
    p = tb.plan[j]
    x0, x1, y0, y1 = neighbours(np.int64(p.cell_x), np.int64(p.cell_y), run)
    if p.rank == RANK_CROSS:
        if p.cross_axis == KIND_CROSS_X:
            x0 = 2 * p.cross_to - p.cell_x
            x1 = x0
            if not 0 <= x0 < run.nx:
                y1 = y0 - 1
        else:
            y0 = 2 * p.cross_to - p.cell_y
            y1 = y0 if 0 <= y0 < run.ny else y0 - 1
    if p.status != TRAPPED:
        y1 = y0 - 1
    return x0, x1, y0, y1


@part
def _ask_heads(j, tb):
    """Ask for the lines of cell heads row j's next event will read."""
    run = tb.run[0]
    x0, _, y0, y1 = _coming_cells(j, tb)
    for cy in range(y0, y1 + 1):
        prefetch(tb.cells, cell_index(x0, cy, run))


@part
def _ask_firsts(j, tb):
    """Read those heads (asked for an event earlier) and ask for their atoms' records.

    Most cells hold one atom or none, so the first is most of a scan's misses. No
    branch on empty cells: row 0 is asked for instead, harmlessly.
    """
    run = tb.run[0]
    x0, x1, y0, y1 = _coming_cells(j, tb)
    for cy in range(y0, y1 + 1):
        for c in range(cell_index(x0, cy, run), cell_index(x1, cy, run) + 1):
            prefetch(tb.state, max(tb.cells[c], 0))


@part
def _after_next(c, n, tb):
    """Heap place of the event after the next (the next is at place c), or -1.

    The earliest of the root's other children and the next one's children.
    """
    best = -1
    t = INF
    for d in range(1, min(5, n)):
        if d != c and tb.heap[d].t < t:
            best = d
            t = tb.heap[d].t
    for d in range(4 * c + 1, min(4 * c + 5, n)):
        if tb.heap[d].t < t:
            best = d
            t = tb.heap[d].t
    return best


@hot
def _ask_heads_of(i, tb):
    """Ask for the heads of the 3 x 3 block around trapped row i (one line per cell row)."""
    run = tb.run[0]
    p = tb.plan[i]
    if p.status == TRAPPED:
        x0, _, y0, y1 = neighbours(np.int64(p.cell_x), np.int64(p.cell_y), run)
        for cy in range(y0, y1 + 1):
            prefetch(tb.cells, cell_index(x0, cy, run))


@hot
def before_event(i, kind, tb):
    """Ask for what this event and the next will read; returns the likely next row (or -1)."""
    run = tb.run[0]
    n = run.heap_size
    nxt = -1
    if n > 1:
        c = np.int64(1)
        for d in range(2, min(5, n)):
            if tb.heap[d].t < tb.heap[c].t:
                c = d
        nxt = tb.heap[c].row
        ask_atom(nxt, tb)
        if run.deep != 0 and n > 2:
            after = _after_next(c, n, tb)
            if after >= 0:
                _ask_heads(tb.heap[after].row, tb)
    if kind == KIND_PAIR:  # the partner's records, while the counts are compared
        ask_atom(np.int64(tb.plan[i].partner), tb)
    _ask_heads_of(i, tb)
    return nxt


@hot
def after_event(nxt, tb):
    """The next row's records have come: ask for its partner's and its cells' heads.

    Done before the predictions, the slow part: they arrive meanwhile.
    """
    if nxt < 0:
        return
    run = tb.run[0]
    p = tb.plan[nxt]
    if p.rank != RANK_CROSS and p.real_kind == KIND_PAIR:
        ask_atom(np.int64(p.partner), tb)
    if run.deep != 0:  # its heads were asked for an event ago: now its neighbours' rows
        _ask_firsts(nxt, tb)
    elif p.status == TRAPPED:
        if p.rank == RANK_CROSS and p.cross_axis == KIND_CROSS_Y:
            # Into the next row of cells: the row beyond it is the one scanned.
            cy = 2 * p.cross_to - p.cell_y
            if 0 <= cy < run.ny:
                prefetch(tb.cells, cy * run.nx + max(p.cell_x - 1, 0))
        else:
            _ask_heads_of(nxt, tb)
