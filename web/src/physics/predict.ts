/**
 * Predictions (src/evapcool/physics/fast/predict.py): an atom's real event (wall or pair if
 * trapped, exit if escaped), its next cell crossing, and the key it is filed under in the
 * calendar, the earlier of the two. Each atom keeps only its earliest event; a pair event
 * remembers the partner's event count and is re-predicted if the partner has changed
 * since (lazy invalidation).
 */
import { ESCAPED, TRAPPED } from "./constants";
import {
  ATOM_IN_CURVATURE,
  ATOM_IN_GRAVITY,
  ATOM_IN_T0,
  ATOM_IN_VX,
  ATOM_IN_VY,
  ATOM_IN_X,
  ATOM_IN_Y,
  EXIT_IN_X_LEFT,
  EXIT_IN_X_RIGHT,
  EXIT_IN_Y_BOTTOM,
  OUT_TIME,
  exitTime,
  pairContactTime,
  wallContactTime,
} from "./kernels";
import {
  KIND_CROSS_X,
  KIND_CROSS_Y,
  KIND_EXIT,
  KIND_NONE,
  KIND_PAIR,
  KIND_WALL,
  PLAN_ATOM,
  PLAN_CELL_X,
  PLAN_CELL_Y,
  PLAN_CROSS_AXIS,
  PLAN_CROSS_TO,
  PLAN_PARTNER,
  PLAN_PARTNER_COUNT,
  PLAN_REAL_A,
  PLAN_REAL_B,
  PLAN_REAL_KIND,
  PLAN_REAL_RANK,
  PLAN_STATUS,
  PLAN_WIDTH,
  QUEUED_ARC_CROSS_T,
  QUEUED_CROSS_T,
  QUEUED_REAL_T,
  QUEUED_WIDTH,
  RANK_CROSS,
  RANK_PAIR,
  RANK_SOLO,
  STATE_ATOM,
  STATE_COUNT,
  STATE_RADIUS,
  STATE_T,
  STATE_VX,
  STATE_VY,
  STATE_WIDTH,
  STATE_X,
  STATE_Y,
} from "./tables";
import type { Tables } from "./tables";

/**
 * Pairs of trapped row r with the rows of cells [x0, x1] x [y0, y1] (seed Eqs. 15-19).
 * An earlier pair replaces r's real event; on a tie the solo event stays and pairs go in
 * (lower, higher) world index order, as in the reference engine.
 */
export function scan(tb: Tables, r: number, x0: number, x1: number, y0: number, y1: number) {
  const S = tb.state;
  const P = tb.plan;
  const cells = tb.cells;
  const nCells = tb.nCells;
  const nx = tb.nx;
  const g = tb.gravity;
  const s = STATE_WIDTH * r;
  const x = S[s + STATE_X];
  const y = S[s + STATE_Y];
  const vx = S[s + STATE_VX];
  const vy = S[s + STATE_VY];
  const t0 = S[s + STATE_T];
  const radius = S[s + STATE_RADIUS];
  const atom = S[s + STATE_ATOM];
  const p = PLAN_WIDTH * r;
  let bestT = tb.queued[QUEUED_WIDTH * r + QUEUED_REAL_T];
  let pair = P[p + PLAN_REAL_RANK] === RANK_PAIR;
  let bestA = P[p + PLAN_REAL_A];
  let bestB = P[p + PLAN_REAL_B];
  let best = -1;
  // Integer arithmetic in asm.js style (shifts, | 0): no overflow checks in the hot loop.
  for (let cy = y0; cy <= y1; cy++) {
    const rowStart = (cy * nx) | 0;
    for (let cx = x0; cx <= x1; cx++) {
      for (let j = cells[(rowStart + cx) | 0]; j >= 0; j = cells[(nCells + j) | 0]) {
        if (j === r) continue;
        const sj = j << 3; // STATE_WIDTH = 8: sj | k is sj + k
        const t = pairContactTime(
          x,
          y,
          vx,
          vy,
          t0,
          S[sj],
          S[sj | STATE_Y],
          S[sj | STATE_VX],
          S[sj | STATE_VY],
          S[sj | STATE_T],
          radius + S[sj | STATE_RADIUS],
          g,
        );
        if (t <= bestT) {
          const other = S[sj | STATE_ATOM]; // rare: only now the partner's world index
          const lo = atom < other ? atom : other;
          const hi = atom < other ? other : atom;
          if (t < bestT || (pair && (lo < bestA || (lo === bestA && hi < bestB)))) {
            bestT = t;
            pair = true;
            bestA = lo;
            bestB = hi;
            best = j;
          }
        }
      }
    }
  }
  if (best >= 0) takePair(tb, r, best, bestT, bestA, bestB);
}

/** Row r's real event becomes the pair with row j at time t, key (t, RANK_PAIR, a, b). */
function takePair(tb: Tables, r: number, j: number, t: number, a: number, b: number): void {
  const P = tb.plan;
  const p = PLAN_WIDTH * r;
  tb.queued[QUEUED_WIDTH * r + QUEUED_REAL_T] = t;
  P[p + PLAN_REAL_RANK] = RANK_PAIR;
  P[p + PLAN_REAL_A] = a;
  P[p + PLAN_REAL_B] = b;
  P[p + PLAN_REAL_KIND] = KIND_PAIR;
  P[p + PLAN_PARTNER] = j;
  P[p + PLAN_PARTNER_COUNT] = tb.state[STATE_WIDTH * j + STATE_COUNT] | 0;
}

/** Row r's solo event time: the wall (SPEC 2.1) if trapped, the exit if escaped. */
function soloTime(tb: Tables, r: number, trapped: boolean): number {
  const S = tb.state;
  const s = STATE_WIDTH * r;
  const io = tb.io;
  io[ATOM_IN_X] = S[s + STATE_X];
  io[ATOM_IN_Y] = S[s + STATE_Y];
  io[ATOM_IN_VX] = S[s + STATE_VX];
  io[ATOM_IN_VY] = S[s + STATE_VY];
  io[ATOM_IN_T0] = S[s + STATE_T];
  io[ATOM_IN_GRAVITY] = tb.gravity;
  if (trapped) {
    io[ATOM_IN_CURVATURE] = tb.curvature;
    wallContactTime(io);
  } else {
    const radius = S[s + STATE_RADIUS];
    io[EXIT_IN_X_LEFT] = tb.xLeft - radius;
    io[EXIT_IN_X_RIGHT] = tb.xRight + radius;
    io[EXIT_IN_Y_BOTTOM] = tb.yBottom - radius;
    exitTime(io);
  }
  return io[OUT_TIME];
}

/** Row r's real event: wall or pair if trapped, exit if escaped, none if gone. */
export function predictReal(tb: Tables, r: number): void {
  const P = tb.plan;
  const p = PLAN_WIDTH * r;
  const status = P[p + PLAN_STATUS];
  let t = Infinity;
  let kind = KIND_NONE;
  if (status === TRAPPED || status === ESCAPED) {
    t = soloTime(tb, r, status === TRAPPED);
    kind = status === TRAPPED ? KIND_WALL : KIND_EXIT;
  }
  tb.queued[QUEUED_WIDTH * r + QUEUED_REAL_T] = t;
  P[p + PLAN_REAL_RANK] = RANK_SOLO;
  P[p + PLAN_REAL_A] = P[p + PLAN_ATOM];
  P[p + PLAN_REAL_B] = 0;
  P[p + PLAN_REAL_KIND] = kind;
  if (status === TRAPPED && !tb.won) {
    const cellX = P[p + PLAN_CELL_X];
    const cellY = P[p + PLAN_CELL_Y];
    scan(
      tb,
      r,
      cellX > 0 ? cellX - 1 : 0,
      cellX < tb.nx - 1 ? cellX + 1 : tb.nx - 1,
      cellY > 0 ? cellY - 1 : 0,
      cellY < tb.ny - 1 ? cellY + 1 : tb.ny - 1,
    );
  }
}

/**
 * Row r's next cell crossing (none unless trapped and the game is on): the earlier of
 * crossX and crossY, written to crossT, crossAxis and crossTo.
 */
export function predictCross(tb: Tables, r: number): void {
  const P = tb.plan;
  const p = PLAN_WIDTH * r;
  const q = QUEUED_WIDTH * r;
  let t = Infinity;
  let axis = KIND_NONE;
  let to = 0;
  if (P[p + PLAN_STATUS] === TRAPPED && !tb.won) {
    const cellX = P[p + PLAN_CELL_X];
    const cellY = P[p + PLAN_CELL_Y];
    t = crossX(tb, r, cellX);
    if (t < Infinity) {
      axis = KIND_CROSS_X;
      to = tb.state[STATE_WIDTH * r + STATE_VX] > 0.0 ? cellX + 1 : cellX - 1;
    }
    const ty = crossY(tb, r, cellY);
    if (ty < t) {
      t = ty;
      axis = KIND_CROSS_Y;
      to = tb.crossYTo;
    }
  }
  tb.queued[q + QUEUED_CROSS_T] = t;
  P[p + PLAN_CROSS_AXIS] = axis;
  P[p + PLAN_CROSS_TO] = to;
}

/** Time row r reaches the next column edge along vx (Infinity at an edge column). */
function crossX(tb: Tables, r: number, cellX: number): number {
  const S = tb.state;
  const s = STATE_WIDTH * r;
  const vx = S[s + STATE_VX];
  if (vx > 0.0 && cellX < tb.nx - 1)
    return S[s + STATE_T] + (tb.gridX0 + (cellX + 1) * tb.cellSize - S[s + STATE_X]) / vx;
  if (vx < 0.0 && cellX > 0)
    return S[s + STATE_T] + (tb.gridX0 + cellX * tb.cellSize - S[s + STATE_X]) / vx;
  return Infinity;
}

/**
 * Time row r crosses a row edge: up through the top edge (first root, if the arc passes
 * it), else down through the bottom edge; roots at or before the arc's last y crossing
 * (arcCrossT) are ones already taken. The row entered goes to tb.crossYTo.
 */
function crossY(tb: Tables, r: number, cellY: number): number {
  const S = tb.state;
  const s = STATE_WIDTH * r;
  const g = tb.gravity;
  const y = S[s + STATE_Y];
  const vy = S[s + STATE_VY];
  const t0 = S[s + STATE_T];
  const taken = tb.queued[QUEUED_WIDTH * r + QUEUED_ARC_CROSS_T];
  if (vy > 0.0 && cellY < tb.ny - 1) {
    const d = tb.gridY0 + (cellY + 1) * tb.cellSize - y;
    const disc = vy * vy - 2.0 * g * d;
    if (disc > 0.0) {
      const root = Math.sqrt(disc);
      const t1 = t0 + (2.0 * d) / (vy + root);
      const t2 = t0 + (vy + root) / g;
      if (t2 > t1 && t1 > taken) {
        tb.crossYTo = cellY + 1;
        return t1;
      }
    }
  }
  if (cellY > 0) {
    const h = y - (tb.gridY0 + cellY * tb.cellSize);
    let disc = vy * vy + 2.0 * g * h;
    if (disc < 0.0) disc = 0.0;
    const root = Math.sqrt(disc);
    let t2: number;
    if (vy > 0.0) t2 = t0 + (vy + root) / g;
    else if (root - vy > 0.0) t2 = t0 + (2.0 * h) / (root - vy);
    else t2 = t0;
    if (t2 > taken) {
      tb.crossYTo = cellY - 1;
      return t2;
    }
  }
  return Infinity;
}

/** Everything about row r from its stored state, re-filed. */
export function predict(tb: Tables, r: number): void {
  predictReal(tb, r);
  predictCross(tb, r);
  setKey(tb, r);
}

/** Row r's key is the earlier of its crossing and its real event; re-file it. */
export function setKey(tb: Tables, r: number): void {
  const P = tb.plan;
  const p = PLAN_WIDTH * r;
  const q = QUEUED_WIDTH * r;
  const crossT = tb.queued[q + QUEUED_CROSS_T];
  const realT = tb.queued[q + QUEUED_REAL_T];
  const calendar = tb.calendar;
  if (crossT <= realT) {
    calendar.keyT[r] = crossT;
    calendar.file(r, RANK_CROSS, P[p + PLAN_ATOM], P[p + PLAN_CROSS_AXIS]);
  } else {
    calendar.keyT[r] = realT;
    calendar.file(r, P[p + PLAN_REAL_RANK], P[p + PLAN_REAL_A], P[p + PLAN_REAL_B]);
  }
}

/** As setKey, but only loading the key (the calendar is rebuilt afterwards). */
export function loadKey(tb: Tables, r: number): void {
  const P = tb.plan;
  const p = PLAN_WIDTH * r;
  const q = QUEUED_WIDTH * r;
  const crossT = tb.queued[q + QUEUED_CROSS_T];
  const realT = tb.queued[q + QUEUED_REAL_T];
  const calendar = tb.calendar;
  if (crossT <= realT) {
    calendar.keyT[r] = crossT;
    calendar.load(r, RANK_CROSS, P[p + PLAN_ATOM], P[p + PLAN_CROSS_AXIS]);
  } else {
    calendar.keyT[r] = realT;
    calendar.load(r, P[p + PLAN_REAL_RANK], P[p + PLAN_REAL_A], P[p + PLAN_REAL_B]);
  }
}
