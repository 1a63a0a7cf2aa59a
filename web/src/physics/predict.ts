/**
 * Predictions (src/evapcool/physics/fast/predict.py): an atom's real event (wall or pair if
 * trapped, exit if escaped), its next cell crossing, and the key it is filed under in the
 * calendar, the earlier of the two. Each atom keeps only its earliest event; a pair event
 * remembers the partner's event count and is re-predicted if the partner has changed
 * since (lazy invalidation).
 */
import { ESCAPED, TRAPPED } from "./constants";
import { ATOM_IN, EXIT_IN, OUT, exitTime, pairContactTime, wallContactTime } from "./kernels";
import {
  KIND_CROSS_X,
  KIND_CROSS_Y,
  KIND_EXIT,
  KIND_NONE,
  KIND_PAIR,
  KIND_WALL,
  PLAN,
  PLAN_WIDTH,
  QUEUED,
  QUEUED_WIDTH,
  RANK_CROSS,
  RANK_PAIR,
  RANK_SOLO,
  STATE,
  STATE_WIDTH,
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
  const x = S[s + STATE.x];
  const y = S[s + STATE.y];
  const vx = S[s + STATE.vx];
  const vy = S[s + STATE.vy];
  const t0 = S[s + STATE.t];
  const radius = S[s + STATE.radius];
  const atom = S[s + STATE.atom];
  const p = PLAN_WIDTH * r;
  let bestT = tb.queued[QUEUED_WIDTH * r + QUEUED.realT];
  let pair = P[p + PLAN.realRank] === RANK_PAIR;
  let bestA = P[p + PLAN.realA];
  let bestB = P[p + PLAN.realB];
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
          S[sj | STATE.y],
          S[sj | STATE.vx],
          S[sj | STATE.vy],
          S[sj | STATE.t],
          radius + S[sj | STATE.radius],
          g,
        );
        if (t <= bestT) {
          const other = S[sj | STATE.atom]; // rare: only now the partner's world index
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
  tb.queued[QUEUED_WIDTH * r + QUEUED.realT] = t;
  P[p + PLAN.realRank] = RANK_PAIR;
  P[p + PLAN.realA] = a;
  P[p + PLAN.realB] = b;
  P[p + PLAN.realKind] = KIND_PAIR;
  P[p + PLAN.partner] = j;
  P[p + PLAN.partnerCount] = tb.state[STATE_WIDTH * j + STATE.count] | 0;
}

/** Row r's solo event time: the wall (SPEC 2.1) if trapped, the exit if escaped. */
function soloTime(tb: Tables, r: number, trapped: boolean): number {
  const S = tb.state;
  const s = STATE_WIDTH * r;
  const io = tb.io;
  io[ATOM_IN.x] = S[s + STATE.x];
  io[ATOM_IN.y] = S[s + STATE.y];
  io[ATOM_IN.vx] = S[s + STATE.vx];
  io[ATOM_IN.vy] = S[s + STATE.vy];
  io[ATOM_IN.t0] = S[s + STATE.t];
  io[ATOM_IN.gravity] = tb.gravity;
  if (trapped) {
    io[ATOM_IN.curvature] = tb.curvature;
    wallContactTime(io);
  } else {
    const radius = S[s + STATE.radius];
    io[EXIT_IN.xLeft] = tb.xLeft - radius;
    io[EXIT_IN.xRight] = tb.xRight + radius;
    io[EXIT_IN.yBottom] = tb.yBottom - radius;
    exitTime(io);
  }
  return io[OUT.time];
}

/** Row r's real event: wall or pair if trapped, exit if escaped, none if gone. */
export function predictReal(tb: Tables, r: number): void {
  const P = tb.plan;
  const p = PLAN_WIDTH * r;
  const status = P[p + PLAN.status];
  let t = Infinity;
  let kind = KIND_NONE;
  if (status === TRAPPED || status === ESCAPED) {
    t = soloTime(tb, r, status === TRAPPED);
    kind = status === TRAPPED ? KIND_WALL : KIND_EXIT;
  }
  tb.queued[QUEUED_WIDTH * r + QUEUED.realT] = t;
  P[p + PLAN.realRank] = RANK_SOLO;
  P[p + PLAN.realA] = P[p + PLAN.atom];
  P[p + PLAN.realB] = 0;
  P[p + PLAN.realKind] = kind;
  if (status === TRAPPED && !tb.won) {
    const cellX = P[p + PLAN.cellX];
    const cellY = P[p + PLAN.cellY];
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
  if (P[p + PLAN.status] === TRAPPED && !tb.won) {
    const cellX = P[p + PLAN.cellX];
    const cellY = P[p + PLAN.cellY];
    t = crossX(tb, r, cellX);
    if (t < Infinity) {
      axis = KIND_CROSS_X;
      to = tb.state[STATE_WIDTH * r + STATE.vx] > 0.0 ? cellX + 1 : cellX - 1;
    }
    const ty = crossY(tb, r, cellY);
    if (ty < t) {
      t = ty;
      axis = KIND_CROSS_Y;
      to = tb.crossYTo;
    }
  }
  tb.queued[q + QUEUED.crossT] = t;
  P[p + PLAN.crossAxis] = axis;
  P[p + PLAN.crossTo] = to;
}

/** Time row r reaches the next column edge along vx (Infinity at an edge column). */
function crossX(tb: Tables, r: number, cellX: number): number {
  const S = tb.state;
  const s = STATE_WIDTH * r;
  const vx = S[s + STATE.vx];
  if (vx > 0.0 && cellX < tb.nx - 1)
    return S[s + STATE.t] + (tb.gridX0 + (cellX + 1) * tb.cellSize - S[s + STATE.x]) / vx;
  if (vx < 0.0 && cellX > 0)
    return S[s + STATE.t] + (tb.gridX0 + cellX * tb.cellSize - S[s + STATE.x]) / vx;
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
  const y = S[s + STATE.y];
  const vy = S[s + STATE.vy];
  const t0 = S[s + STATE.t];
  const taken = tb.queued[QUEUED_WIDTH * r + QUEUED.arcCrossT];
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
  const crossT = tb.queued[q + QUEUED.crossT];
  const realT = tb.queued[q + QUEUED.realT];
  const calendar = tb.calendar;
  if (crossT <= realT) {
    calendar.keyT[r] = crossT;
    calendar.file(r, RANK_CROSS, P[p + PLAN.atom], P[p + PLAN.crossAxis]);
  } else {
    calendar.keyT[r] = realT;
    calendar.file(r, P[p + PLAN.realRank], P[p + PLAN.realA], P[p + PLAN.realB]);
  }
}

/** As setKey, but only loading the key (the calendar is rebuilt afterwards). */
export function loadKey(tb: Tables, r: number): void {
  const P = tb.plan;
  const p = PLAN_WIDTH * r;
  const q = QUEUED_WIDTH * r;
  const crossT = tb.queued[q + QUEUED.crossT];
  const realT = tb.queued[q + QUEUED.realT];
  const calendar = tb.calendar;
  if (crossT <= realT) {
    calendar.keyT[r] = crossT;
    calendar.load(r, RANK_CROSS, P[p + PLAN.atom], P[p + PLAN.crossAxis]);
  } else {
    calendar.keyT[r] = realT;
    calendar.load(r, P[p + PLAN.realRank], P[p + PLAN.realA], P[p + PLAN.realB]);
  }
}
