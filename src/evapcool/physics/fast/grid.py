"""The cell grid: trapped atoms filed in square cells, so pairs are looked for nearby only.

Cells are at least one contact distance wide, so an atom can only touch atoms of
its own and the eight neighbouring cells. Crossing a cell edge is an event of its
own (predict.predict_crossing) that changes no stored state. The edge cells are
clamped, i.e. they reach to infinity, so a trapped atom flying out of the box is
still in a cell and still meets its neighbours.

tb.cells[c] is the first row filed in cell c = cell_y * nx + cell_x (-1 if none);
tb.cells[n_cells + i] the next row in row i's cell. A row's cell and its previous
row in the cell are in its PLAN record.
"""

from __future__ import annotations

import math

import numpy as np

from evapcool.physics.fast.jit import hot
from evapcool.physics.world import TRAPPED, World

#: Cell edge in contact distances; > 1 leaves room for round-off in crossing times.
CELL_FACTOR = 1.1
#: The box reaches the height this percentile of trapped atoms can reach.
BOX_PERCENTILE = 99.5
#: At most this many cells per atom (bounds memory for tiny, sparse atoms).
MAX_CELLS_PER_ATOM = 8


def geometry(world: World) -> tuple[float, float, float, int, int]:
    """(x0, y0, cell edge, columns, rows) of the grid for this World."""
    n = len(world.radius)
    g = float(world.gravity)
    a = float(world.curvature)
    cs = CELL_FACTOR * 2.0 * float(np.max(world.radius))
    trapped = world.status == TRAPPED
    heights = world.energies()[trapped] / (world.mass[trapped] * g)
    top = float(np.percentile(heights, BOX_PERCENTILE)) if len(heights) else 1.0
    y_top = max(top, 1.0) + cs
    half_w = math.sqrt(y_top / a) + cs
    max_cells = MAX_CELLS_PER_ATOM * n + 64
    if (2.0 * half_w / cs) * (y_top / cs) > max_cells:
        cs = math.sqrt(2.0 * half_w * y_top / max_cells)
    nx = max(1, math.ceil(2.0 * half_w / cs))
    ny = max(1, math.ceil((y_top + 0.5 * cs) / cs))
    return -0.5 * nx * cs, -0.5 * cs, cs, nx, ny


@hot
def cell_of(u, u0, cs, n):
    """Cell coordinate of u; the edge cells reach to infinity."""
    c = math.floor((u - u0) / cs)
    if c < 0.0:
        return 0
    if c > n - 1:
        return n - 1
    return int(c)


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
        tb.cells[p.cell_y * tb.run[0].nx + p.cell_x] = after
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
    c = cy * tb.run[0].nx + cx
    first = tb.cells[c]
    tb.cells[n_cells + i] = first
    p.cell_prev = -1
    if first >= 0:
        tb.plan[first].cell_prev = i
    tb.cells[c] = i
