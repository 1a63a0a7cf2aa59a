"""The cell grid: trapped atoms filed in square cells, so pairs are looked for nearby only.

Cells are at least one contact distance wide (CELL_FACTOR of the largest diameter),
so an atom can only touch atoms of its own and the eight neighbouring cells.
Crossing a cell edge is an event of its own (predict.predict_crossing) that changes
no stored state.

The grid covers the region trapped atoms can reach: the cup below the rim (issue
13). Its size depends on the atom count, the diameter, the trap and the window,
never on the atoms' energies, and is at most MAX_CELLS_PER_ATOM cells per atom
(wider cells if the cup would need more), so memory stays bounded and hot atoms
cannot make the cells wide. Trapped atoms above the rim (flying high, about to
escape) are kept out of the grid proper, in the attic: its top row, whose cells
reach up to infinity. There they meet each other and the atoms just below, so their
events stay exact, while the bulk never scans them. The other edge cells reach to
infinity too (only round-off can use that).

Cell c of row cy and column cx is c = cy * nx + cx. tb.cells[c] is the first row
filed in cell c (-1 if none), tb.cells[n_cells + i] the next row in row i's cell. A
row's cell and its previous row in the cell are in its PLAN record.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from evapcool.physics.fast.jit import hot
from evapcool.physics.world import World

#: Cell edge in contact distances; > 1 leaves room for round-off in crossing times.
CELL_FACTOR = 1.1
#: The grid reaches this many cells above the rim (atoms just over it stay in it).
ROWS_ABOVE_RIM = 2
#: At most this many cells per atom, and at least MIN_CELLS may be used.
MAX_CELLS_PER_ATOM = 16
MIN_CELLS = 4096
#: When the rim rises above the grid, the new grid covers this many times the old
#: reach (so that raising the trap step by step does not rebuild it every frame).
GROWTH = 2.0


class Grid(NamedTuple):
    """Where the cells are: column 0 starts at x0, row 0 at y0; nx by ny cells of edge cell."""

    x0: float
    y0: float
    cell: float
    nx: int
    ny: int
    reach: float  # the highest rim this grid was built for

    @property
    def top(self) -> float:
        """The attic's floor: trapped centres above it fly in the attic (the top row)."""
        return self.y0 + (self.ny - 1) * self.cell


def reach(world: World, height: float) -> float:
    """How high the grid must reach for rim height `height` (px): the rim, or the
    cup's height at the window's sides if that is lower (an infinite rim)."""
    x_edge = max(-world.x_left, world.x_right)
    return min(height, world.curvature * x_edge * x_edge)


def geometry(world: World, height: float) -> Grid:
    """The grid for this World's atoms and a rim at `height`."""
    n = len(world.radius)
    a = float(world.curvature)
    top = reach(world, height)
    cell = CELL_FACTOR * 2.0 * float(np.max(world.radius))
    budget = max(MAX_CELLS_PER_ATOM * n, MIN_CELLS)
    while True:
        y_top = top + ROWS_ABOVE_RIM * cell
        half_w = math.sqrt(max(y_top, 0.0) / a) + cell
        nx = max(1, math.ceil(2.0 * half_w / cell))
        ny = max(1, math.ceil((y_top + 0.5 * cell) / cell)) + 1  # + the attic
        if nx * ny <= budget:
            return Grid(-0.5 * nx * cell, -0.5 * cell, cell, nx, ny, top)
        cell *= 1.01 * math.sqrt(nx * ny / budget)  # too many: wider cells


def regrid_for(world: World, grid: Grid, height: float) -> Grid | None:
    """A new grid if the rim at `height` rose above this one or left it far too big."""
    new = reach(world, height)
    if new > grid.reach:
        return geometry(world, max(new, min(GROWTH * grid.reach, reach(world, math.inf))))
    if new < grid.reach / GROWTH**2:  # cheap test first: this runs at every height change
        fine = CELL_FACTOR * 2.0 * float(np.max(world.radius))
        if grid.cell > 1.01 * fine:
            return geometry(world, GROWTH * new)  # the cells were widened for a big cup
    return None


# -- compiled ---------------------------------------------------------------------------
@hot
def cell_of(u, u0, cs, n):
    """Cell coordinate of u among n; the edge cells reach to infinity."""
    c = math.floor((u - u0) / cs)
    if c < 0.0:
        return 0
    if c > n - 1:
        return n - 1
    return int(c)


@hot
def cell_at(x, y, run):
    """(column, row) of the cell of a trapped centre at (x, y)."""
    return cell_of(x, run.grid_x0, run.cell, run.nx), cell_of(y, run.grid_y0, run.cell, run.ny)


@hot
def cell_index(cx, cy, run):
    """Index of cell (cx, cy) in tb.cells."""
    return cy * run.nx + cx


@hot
def neighbours(cx, cy, run):
    """The block of cells around cell (cx, cy): (x0, x1, y0, y1), clipped to the grid."""
    x0 = cx - 1 if cx > 0 else 0
    x1 = cx + 1 if cx < run.nx - 1 else run.nx - 1
    y0 = cy - 1 if cy > 0 else 0
    y1 = cy + 1 if cy < run.ny - 1 else run.ny - 1
    return x0, x1, y0, y1


@hot
def unlink(i, tb):
    """Take row i out of its cell's list."""
    n_cells = tb.cells.shape[0] - tb.plan.shape[0]
    p = tb.plan[i]
    before = p.cell_prev
    after = tb.cells[n_cells + i]
    if before >= 0:
        tb.cells[n_cells + before] = after
    else:
        tb.cells[cell_index(np.int64(p.cell_x), np.int64(p.cell_y), tb.run[0])] = after
    if after >= 0:
        tb.plan[after].cell_prev = before
    tb.cells[n_cells + i] = -1
    p.cell_prev = -1


@hot
def link(i, cx, cy, tb):
    """File row i first in cell (cx, cy)."""
    n_cells = tb.cells.shape[0] - tb.plan.shape[0]
    p = tb.plan[i]
    p.cell_x = cx
    p.cell_y = cy
    c = cell_index(cx, cy, tb.run[0])
    first = tb.cells[c]
    tb.cells[n_cells + i] = first
    p.cell_prev = -1
    if first >= 0:
        tb.plan[first].cell_prev = i
    tb.cells[c] = i
