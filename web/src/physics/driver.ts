/**
 * The event loop (src/evapcool/physics/fast/driver.py): the calendar hands out the least
 * key, keyed (time, rank, a, b) so ties fall as in the reference engine (tables.ts's
 * ranks), and the event's handler (events.ts) carries it out. Every few events per atom
 * the rows are renumbered in cell order (maintain), so the atoms of neighbouring cells sit
 * next to each other in memory and the pair scans stay in the caches.
 */
import { TRAPPED } from "./constants";
import { fileAll, link } from "./grid";
import { crossEvent, exitEvent, knifeCut, pairEvent, wallEvent } from "./events";
import { loadKey, predictCross, predictReal } from "./predict";
import {
  KIND_CROSS_X,
  KIND_CROSS_Y,
  KIND_EXIT,
  KIND_PAIR,
  KIND_WALL,
  PLAN_ATOM,
  PLAN_CELL_X,
  PLAN_CELL_Y,
  PLAN_CROSS_AXIS,
  PLAN_PARTNER,
  PLAN_REAL_KIND,
  PLAN_STATUS,
  PLAN_WIDTH,
  QUEUED_WIDTH,
  RANK_CROSS,
  STATE_WIDTH,
} from "./tables";
import type { Tables } from "./tables";

/** Rows are put in cell order, and the calendar's bins fitted, every this many events per atom. */
const RENUMBER_EVENTS_PER_ATOM = 8;

/** Put trapped atoms in their cells (positions now), predict every atom, file the keys. */
export function start(tb: Tables): void {
  fileAll(tb);
  for (let r = 0; r < tb.n; r++) {
    predictReal(tb, r);
    predictCross(tb, r);
    loadKey(tb, r);
  }
  tb.calendar.rebuild(tb.time);
  tb.sinceMaintain = 0;
}

/** Process every event with time <= tEnd in time order, then set the clock. */
export function advanceTo(tb: Tables, tEnd: number): void {
  const calendar = tb.calendar;
  const every = RENUMBER_EVENTS_PER_ATOM * tb.n;
  for (;;) {
    if (++tb.sinceMaintain > every) maintain(tb);
    const r = calendar.top();
    if (r < 0) break;
    const t = calendar.keyT[r];
    if (!(t <= tEnd)) break;
    const p = PLAN_WIDTH * r;
    const kind =
      calendar.rankOf(r) === RANK_CROSS
        ? tb.plan[p + PLAN_CROSS_AXIS]
        : tb.plan[p + PLAN_REAL_KIND];
    if (kind === KIND_PAIR) pairEvent(tb, r, t);
    else if (kind === KIND_CROSS_X || kind === KIND_CROSS_Y) crossEvent(tb, r, kind, t);
    else if (kind === KIND_WALL) wallEvent(tb, r, t);
    else if (kind === KIND_EXIT) exitEvent(tb, r, t);
    else break;
  }
  tb.time = tEnd;
}

/** Renumber the rows (or, once the gas has condensed, only refit the calendar's bins). */
function maintain(tb: Tables): void {
  tb.sinceMaintain = 0;
  if (tb.won) tb.calendar.rebuild(tb.time);
  else renumber(tb);
}

/**
 * Renumber the rows in cell order (row-major), the atoms off the grid last. Moves every
 * table row, relabels partners, rebuilds the cell lists and re-files the calendar. Events,
 * their keys (world indices) and so the event order are unchanged.
 */
function renumber(tb: Tables): void {
  const n = tb.n;
  const nCells = tb.nCells;
  const cells = tb.cells;
  const order = tb.order; // order[new row] = old row
  const fresh = tb.row; // world index -> new row
  const P = tb.plan;
  let k = 0;
  for (let c = 0; c < nCells; c++)
    for (let j = cells[c]; j >= 0; j = cells[nCells + j]) order[k++] = j;
  const linked = k;
  for (let r = 0; r < n; r++) fresh[P[PLAN_WIDTH * r + PLAN_ATOM]] = -1;
  for (let q = 0; q < linked; q++) fresh[P[PLAN_WIDTH * order[q] + PLAN_ATOM]] = q;
  for (let r = 0; r < n; r++) if (fresh[P[PLAN_WIDTH * r + PLAN_ATOM]] < 0) order[k++] = r;
  for (let q = linked; q < n; q++) fresh[P[PLAN_WIDTH * order[q] + PLAN_ATOM]] = q;
  moveRows(tb);
  // Partners are rows: relabel them (the old row's world index, then its new row).
  const moved = tb.plan;
  for (let q = 0; q < n; q++) {
    const p = PLAN_WIDTH * q;
    if (moved[p + PLAN_REAL_KIND] === KIND_PAIR)
      moved[p + PLAN_PARTNER] = fresh[P[PLAN_WIDTH * moved[p + PLAN_PARTNER] + PLAN_ATOM]];
  }
  // Cell lists: linking in descending row order leaves each list ascending.
  cells.fill(-1);
  for (let q = linked - 1; q >= 0; q--)
    link(tb, q, moved[PLAN_WIDTH * q + PLAN_CELL_X], moved[PLAN_WIDTH * q + PLAN_CELL_Y]);
  for (let q = 0; q < n; q++) loadKey(tb, q);
  tb.calendar.rebuild(tb.time);
  tb.renumbers++;
}

/** Copy the rows into the spare tables in tb.order, then swap the spares in. */
function moveRows(tb: Tables): void {
  const { state, plan, queued, spareState, sparePlan, spareQueued, order } = tb;
  for (let q = 0; q < tb.n; q++) {
    const o = order[q];
    for (let k = 0; k < STATE_WIDTH; k++)
      spareState[STATE_WIDTH * q + k] = state[STATE_WIDTH * o + k];
    for (let k = 0; k < PLAN_WIDTH; k++) sparePlan[PLAN_WIDTH * q + k] = plan[PLAN_WIDTH * o + k];
    for (let k = 0; k < QUEUED_WIDTH; k++)
      spareQueued[QUEUED_WIDTH * q + k] = queued[QUEUED_WIDTH * o + k];
  }
  tb.state = spareState;
  tb.plan = sparePlan;
  tb.queued = spareQueued;
  tb.spareState = state;
  tb.sparePlan = plan;
  tb.spareQueued = queued;
}

/** New rim height, at once; with the knife rule, atoms above m g H go now, in index order. */
export function setTrapHeight(tb: Tables, height: number): void {
  tb.trapHeight = height;
  tb.xRim = Math.sqrt(height / tb.curvature);
  if (!tb.knife) return;
  for (let i = 0; i < tb.n; i++) {
    const r = tb.row[i];
    if (tb.plan[PLAN_WIDTH * r + PLAN_STATUS] === TRAPPED) knifeCut(tb, r);
  }
}
