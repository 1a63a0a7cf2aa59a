/**
 * The cell grid (src/evapcool/physics/fast/grid.py): trapped atoms live in a uniform grid
 * of cells 1.1 contact distances wide, its edge cells reaching to infinity; each cell is a
 * doubly linked list of rows (tb.cells holds the heads, then every row's next; PLAN's
 * cellPrev the way back). Pairs are looked for in the 3 x 3 block around an atom.
 */
import { TRAPPED } from "./constants";
import { flightX, flightY } from "./kernels";
import {
  PLAN_CELL_PREV,
  PLAN_CELL_X,
  PLAN_CELL_Y,
  PLAN_STATUS,
  PLAN_WIDTH,
  QUEUED_MASS,
  QUEUED_WIDTH,
  STATE_RADIUS,
  STATE_T,
  STATE_VX,
  STATE_VY,
  STATE_WIDTH,
  STATE_X,
  STATE_Y,
  rowEnergy,
} from "./tables";
import type { Tables } from "./tables";

/** Cell edge in contact distances; > 1 leaves room for round-off in crossing times. */
const CELL_FACTOR = 1.1;
/** At most this many cells per atom (bounds memory for tiny, sparse atoms). */
const MAX_CELLS_PER_ATOM = 8;

/**
 * Cells: 1.1 of the largest contact distance, over the region the trapped atoms can reach
 * (below the height of the most energetic one, y <= E / (m g)), as long as that takes at
 * most 8 cells per atom; beyond it atoms sit in the edge cells, which reach to infinity.
 * Cells are never widened for a few hot atoms (that would make every scan long).
 */
export function gridShape(tb: Tables): { cellSize: number; nx: number; ny: number } {
  let rMax = 0;
  let top = 1;
  for (let r = 0; r < tb.n; r++) {
    if (tb.plan[PLAN_WIDTH * r + PLAN_STATUS] !== TRAPPED) continue;
    const radius = tb.state[STATE_WIDTH * r + STATE_RADIUS];
    if (radius > rMax) rMax = radius;
    const h = rowEnergy(tb, r) / (tb.queued[QUEUED_WIDTH * r + QUEUED_MASS] * tb.gravity);
    if (h > top) top = h;
  }
  const cellSize = rMax > 0 ? CELL_FACTOR * 2 * rMax : 1;
  const maxCells = MAX_CELLS_PER_ATOM * tb.n + 64;
  // Box: |x| <= sqrt(yTop / a) + cellSize, 0 <= y <= yTop; shrink yTop until it fits.
  let yTop = top + cellSize;
  for (;;) {
    const halfW = Math.sqrt(yTop / tb.curvature) + cellSize;
    const nx = Math.max(1, Math.ceil((2 * halfW) / cellSize));
    const ny = Math.max(1, Math.ceil((yTop + 0.5 * cellSize) / cellSize));
    if (nx * ny <= maxCells || yTop <= cellSize) return { cellSize, nx, ny };
    yTop *= 0.8;
  }
}

/** Lay out the grid of gridShape, every cell empty. */
export function placeGrid(tb: Tables): void {
  const { cellSize, nx, ny } = gridShape(tb);
  tb.cellSize = cellSize;
  tb.nx = nx;
  tb.ny = ny;
  tb.gridX0 = -0.5 * nx * cellSize;
  tb.gridY0 = -0.5 * cellSize;
  tb.nCells = nx * ny;
  tb.cells = new Int32Array(tb.nCells + tb.n).fill(-1);
}

/** The cell index along one axis of coordinate u (edge cells reach to infinity). */
export function clampCell(tb: Tables, u: number, u0: number, n: number): number {
  const c = Math.floor((u - u0) / tb.cellSize);
  if (c < 0) return 0;
  if (c > n - 1) return n - 1;
  return c;
}

/** File row r first in cell (cellX, cellY). */
export function link(tb: Tables, r: number, cellX: number, cellY: number): void {
  const P = tb.plan;
  const cells = tb.cells;
  P[PLAN_WIDTH * r + PLAN_CELL_X] = cellX;
  P[PLAN_WIDTH * r + PLAN_CELL_Y] = cellY;
  const c = cellY * tb.nx + cellX;
  const q = cells[c];
  cells[tb.nCells + r] = q;
  P[PLAN_WIDTH * r + PLAN_CELL_PREV] = -1;
  if (q >= 0) P[PLAN_WIDTH * q + PLAN_CELL_PREV] = r;
  cells[c] = r;
}

/** Take row r out of its cell's list. */
export function unlink(tb: Tables, r: number): void {
  const P = tb.plan;
  const cells = tb.cells;
  const p = P[PLAN_WIDTH * r + PLAN_CELL_PREV];
  const q = cells[tb.nCells + r];
  const c = P[PLAN_WIDTH * r + PLAN_CELL_Y] * tb.nx + P[PLAN_WIDTH * r + PLAN_CELL_X];
  if (p >= 0) cells[tb.nCells + p] = q;
  else if (cells[c] === r) cells[c] = q;
  if (q >= 0) P[PLAN_WIDTH * q + PLAN_CELL_PREV] = p;
  cells[tb.nCells + r] = -1;
  P[PLAN_WIDTH * r + PLAN_CELL_PREV] = -1;
}

/** Put every trapped row in its cell at the clock's time. */
export function fileAll(tb: Tables): void {
  const S = tb.state;
  const halfG = 0.5 * tb.gravity;
  for (let r = 0; r < tb.n; r++) {
    if (tb.plan[PLAN_WIDTH * r + PLAN_STATUS] !== TRAPPED) continue;
    const s = STATE_WIDTH * r;
    const dt = tb.time - S[s + STATE_T];
    const x = flightX(S[s + STATE_X], S[s + STATE_VX], dt);
    const y = flightY(S[s + STATE_Y], S[s + STATE_VY], halfG, dt);
    link(tb, r, clampCell(tb, x, tb.gridX0, tb.nx), clampCell(tb, y, tb.gridY0, tb.ny));
  }
}

/** Trapped atoms filed more than one cell away from their cell now (0 if sound). */
export function gridErrors(tb: Tables): number {
  if (tb.won) return 0;
  const S = tb.state;
  const P = tb.plan;
  const halfG = 0.5 * tb.gravity;
  let bad = 0;
  for (let r = 0; r < tb.n; r++) {
    const p = PLAN_WIDTH * r;
    if (P[p + PLAN_STATUS] !== TRAPPED) continue;
    const s = STATE_WIDTH * r;
    const dt = tb.time - S[s + STATE_T];
    const x = flightX(S[s + STATE_X], S[s + STATE_VX], dt);
    const y = flightY(S[s + STATE_Y], S[s + STATE_VY], halfG, dt);
    const cellX = clampCell(tb, x, tb.gridX0, tb.nx);
    const cellY = clampCell(tb, y, tb.gridY0, tb.ny);
    if (Math.abs(cellX - P[p + PLAN_CELL_X]) > 1 || Math.abs(cellY - P[p + PLAN_CELL_Y]) > 1) bad++;
  }
  return bad;
}
