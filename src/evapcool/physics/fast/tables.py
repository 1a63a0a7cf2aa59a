"""The fast engine's tables: what it knows about every atom, and its running scalars.

Three record arrays hold one 64-byte record per atom each, aligned so that a record
is one cache line: the engine touches an atom's lines, not scattered columns.
Row i of every table belongs to the same atom, but not to atom i of the World: the
rows are renumbered in cell order now and then (see driver.maintain), and `atom`
holds the World index. Everything that orders events or is seen outside (tie
breaks, the log, the knife's ascending order) uses that index, never the row.

NumPy only: importing this module never imports Numba.
"""

from __future__ import annotations

from collections import namedtuple
from typing import Any

import numpy as np

LINE = 64  # bytes in a cache line


def _record(fields: list[tuple[str, str]], itemsize: int | None = None) -> np.dtype[np.void]:
    names = [name for name, _ in fields]
    formats = [fmt for _, fmt in fields]
    if itemsize is None:
        return np.dtype({"names": names, "formats": formats}, align=True)
    return np.dtype({"names": names, "formats": formats, "itemsize": itemsize}, align=True)


#: What the pair scan reads of every neighbour, in one line: the stored state and the
#: two integers the scan needs when a pair wins (the partner check and the tie break).
STATE = _record(
    [
        ("x", "f8"),  # stored position (trap coordinates, px) ...
        ("y", "f8"),
        ("vx", "f8"),  # ... and velocity (px/frame) ...
        ("vy", "f8"),
        ("t", "f8"),  # ... at this time (frames): the atom's own clock
        ("radius", "f8"),
        ("count", "i8"),  # events so far: a partner's pair event is stale once it moved on
        ("atom", "i8"),  # World index
    ],
    LINE,
)

#: What the event queue reads: the key time and the queue links, with the times the key
#: is chosen from and the mass in the rest of the line.
QUEUED = _record(
    [
        ("key_t", "f8"),  # time the atom is filed under: min(real_t, cross_t)
        ("real_t", "f8"),  # time of its real event (pair, wall or exit), inf if none
        ("cross_t", "f8"),  # time of its next cell crossing, inf if none
        ("arc_cross_t", "f8"),  # last y crossing taken on the current arc (-inf: none)
        ("mass", "f8"),
        ("heap_pos", "i4"),  # place in the heap, -1 if in a list
        ("bin", "i4"),  # list it is filed in (calendar.py), -1 if in the heap
        ("next", "i4"),  # neighbours in that list, -1 at the ends
        ("prev", "i4"),
    ],
    LINE,
)

#: The atom's pending events (key parts, kinds, partner) and where it is.
PLAN = _record(
    [
        ("rank", "i4"),  # key: (key_t, rank, tie_a, tie_b), see RANK_* below
        ("tie_a", "i4"),
        ("tie_b", "i4"),
        ("real_rank", "i4"),  # the real event's key parts
        ("real_a", "i4"),
        ("real_b", "i4"),
        ("real_kind", "i4"),  # KIND_PAIR, KIND_WALL, KIND_EXIT or KIND_NONE
        ("partner", "i4"),  # row of the partner of a pair event
        ("partner_count", "i4"),  # the partner's count then (low 32 bits)
        ("cross_axis", "i4"),  # KIND_CROSS_X, KIND_CROSS_Y or KIND_NONE
        ("cross_to", "i4"),  # cell column (x) or row (y) the crossing enters
        ("status", "i4"),  # TRAPPED, ESCAPED or GONE (world.py)
        ("cell_x", "i4"),  # the cell it is filed in (trapped atoms only)
        ("cell_y", "i4"),
        ("cell_prev", "i4"),  # previous atom in that cell, -1 if first
        ("atom", "i4"),  # World index
    ],
    LINE,
)

#: Event kinds inside the engine (the log uses world.EV_*).
KIND_NONE = 0
KIND_PAIR = 1
KIND_WALL = 2
KIND_EXIT = 3
KIND_CROSS_X = 4  # into the next column of cells
KIND_CROSS_Y = 5  # into the next row of cells

# Ranks order events of equal time: a cell crossing changes no state and may reveal
# a partner, so it goes first; then solo events (the reference engine prefers them to
# pairs on a tie); then pairs by (lower, higher) World index.
RANK_CROSS = -1
RANK_SOLO = 0
RANK_PAIR = 1

#: The engine's scalars: fixed parameters, the running state it shares with the World,
#: counters, and the event calendar's state. One record, `run[0]`.
RUN = _record(
    [
        # fixed for the engine's life
        ("gravity", "f8"),
        ("curvature", "f8"),
        ("grid_x0", "f8"),  # left edge of cell column 0
        ("grid_y0", "f8"),  # bottom edge of cell row 0
        ("cell", "f8"),  # cell edge (px)
        ("x_left", "f8"),  # window edges (exit bounds before the radius)
        ("x_right", "f8"),
        ("y_bottom", "f8"),
        ("nx", "i8"),  # cell columns
        ("ny", "i8"),  # cell rows
        ("knife", "i8"),  # 1: the knife escape rule
        ("record", "i8"),  # 1: write the event log
        ("maintain_every", "i8"),  # events between two calls of driver.maintain
        ("deep", "i8"),  # 1: look two events ahead for memory (lookahead.py)
        # shared with the World (copied in and out around every call)
        ("time", "f8"),
        ("energy_sum", "f8"),  # running sum over trapped atoms
        ("x_rim", "f8"),
        ("trap_height", "f8"),
        ("won", "i8"),
        ("n_trapped", "i8"),
        ("pairs", "i8"),
        ("walls", "i8"),
        # engine-only counts
        ("crossings", "i8"),  # cell crossings processed
        ("stale", "i8"),  # pair events found stale and re-predicted
        ("since_maintain", "i8"),  # events since the last maintenance
        ("n_log", "i8"),  # lines in the log buffer
        # the event calendar (calendar.py)
        ("bin_base", "f8"),  # time where bin 0 starts
        ("bin_width", "f8"),
        ("heap_size", "i8"),
        ("bin", "i8"),  # the current bin: its atoms are in the heap
        ("scan_bin", "i8"),  # bin at the last refiling of the overflow list
        ("n_bins", "i8"),  # lists in the ring
        ("n_ring", "i8"),  # atoms in the ring's lists
        ("n_over", "i8"),  # atoms in the overflow list
        ("cursor1", "i8"),  # cursors walking the next two bins' lists ahead of time
        ("cursor2", "i8"),
    ]
)

#: An entry of the calendar's heap: a row filed under key time t.
HEAP_ENTRY = np.dtype([("t", "f8"), ("row", "i8")])

#: One line of the event log: (world.EV_* kind, atom, other atom or -1, time).
LOG_LINE = np.dtype([("kind", "i8"), ("a", "i8"), ("b", "i8"), ("t", "f8")])

#: Everything the compiled code works on, passed as one argument.
Tables = namedtuple(
    "Tables",
    [
        "state",  # STATE per row
        "queued",  # QUEUED per row
        "plan",  # PLAN per row
        "heap",  # HEAP_ENTRY: the event calendar's heap
        "bins",  # first row of each list: n_bins ring lists, overflow, no event
        "cells",  # first row of each cell (row-major: grid.py), then the next
        # row in the same cell for every row (the pair scan walks this array only)
        "run",  # RUN, one record
        "tc_table",  # critical temperature for every atom count, seed Eq. (46)
        "log",  # LOG_LINE buffer
    ],
)

#: Scratch tables for driver.maintain (renumbering the rows), passed to it alone: every
#: array in Tables is one more argument in every call the compiler has to process.
Spares = namedtuple("Spares", ["state", "queued", "plan", "new_row"])


def aligned(n: int, dtype: np.dtype[Any]) -> np.ndarray:
    """A zeroed table of n records starting on a cache-line boundary.

    NumPy aligns to 16 bytes only: a 64-byte record would then straddle two lines,
    and every visit to an atom would cost two cache misses instead of one.
    """
    nbytes = n * dtype.itemsize
    buf = np.zeros(nbytes + LINE, dtype=np.uint8)
    start = -buf.ctypes.data % LINE
    return buf[start : start + nbytes].view(dtype)
