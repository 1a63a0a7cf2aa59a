/**
 * The events (src/evapcool/physics/fast/events.py): one handler per kind, each moving the
 * atoms it touches to the clock, applying the rule, logging, and re-predicting. Stored
 * states move only at an atom's real events (lazy positions); escaped atoms leave the grid
 * and have only their exit event.
 */
import {
  ESCAPED,
  EV_ESCAPE,
  EV_GONE,
  EV_KNIFE,
  EV_PAIR,
  EV_WALL,
  GONE,
  WALL_MIN_NORMAL_SPEED,
  WIN_DAMPING,
  WIN_DAMPING_MIN_SPEED,
  WIN_NORMAL_SPEED_FLOOR,
} from "./constants";
import { link, unlink } from "./grid";
import { power } from "./portable";
import {
  ATOM_IN_CURVATURE,
  ATOM_IN_VX,
  ATOM_IN_VY,
  ATOM_IN_X,
  OUT_VX,
  OUT_VX1,
  OUT_VX2,
  OUT_VY,
  OUT_VY1,
  OUT_VY2,
  PAIR_IN_M1,
  PAIR_IN_M2,
  PAIR_IN_RX,
  PAIR_IN_RY,
  PAIR_IN_VX1,
  PAIR_IN_VX2,
  PAIR_IN_VY1,
  PAIR_IN_VY2,
  WALL_IN_KEEP,
  WALL_IN_V_MIN,
  bounceWall,
  collidePair,
  flightVy,
  flightX,
  flightY,
  settleWall,
} from "./kernels";
import { predict, predictCross, scan, setKey } from "./predict";
import {
  KIND_CROSS_X,
  PLAN_ATOM,
  PLAN_CELL_X,
  PLAN_CELL_Y,
  PLAN_CROSS_TO,
  PLAN_PARTNER,
  PLAN_PARTNER_COUNT,
  PLAN_STATUS,
  PLAN_WIDTH,
  QUEUED_ARC_CROSS_T,
  QUEUED_MASS,
  QUEUED_WIDTH,
  STATE_ATOM,
  STATE_COUNT,
  STATE_T,
  STATE_VX,
  STATE_VY,
  STATE_WIDTH,
  STATE_X,
  STATE_Y,
  rowEnergy,
} from "./tables";
import type { Tables } from "./tables";

/** The clock to an event's time (never backwards: keys may lie a round-off behind). */
function clockTo(tb: Tables, t: number): void {
  if (t >= tb.time) tb.time = t;
}

/** Carry row r's stored state to the clock (exact free flight, seed Eqs. 3-4). */
export function move(tb: Tables, r: number): void {
  const t = tb.time;
  const S = tb.state;
  const s = STATE_WIDTH * r;
  const dt = t - S[s + STATE_T];
  S[s + STATE_X] = flightX(S[s + STATE_X], S[s + STATE_VX], dt);
  S[s + STATE_Y] = flightY(S[s + STATE_Y], S[s + STATE_VY], 0.5 * tb.gravity, dt);
  S[s + STATE_VY] = flightVy(S[s + STATE_VY], tb.gravity, dt);
  S[s + STATE_T] = t;
  tb.queued[QUEUED_WIDTH * r + QUEUED_ARC_CROSS_T] = -Infinity; // a new arc: no y crossing yet
}

/** Log an event at the clock's time (world indices; b = -1 for solo events). */
export function log(tb: Tables, kind: number, a: number, b: number): void {
  if (!tb.recordEvents) return;
  const k = tb.nLog;
  if (k === tb.logT.length) {
    const cap = Math.max(1024, 2 * k);
    const grow = <A extends Uint8Array | Int32Array | Float64Array>(old: A, fresh: A): A => {
      fresh.set(old);
      return fresh;
    };
    tb.logKind = grow(tb.logKind, new Uint8Array(cap));
    tb.logA = grow(tb.logA, new Int32Array(cap));
    tb.logB = grow(tb.logB, new Int32Array(cap));
    tb.logT = grow(tb.logT, new Float64Array(cap));
  }
  tb.logKind[k] = kind;
  tb.logA[k] = a;
  tb.logB[k] = b;
  tb.logT[k] = tb.time;
  tb.nLog = k + 1;
}

/** Tc(N) = Tc0 (N / N0)^p, seed Eq. (46) with exponent p. */
export function criticalTemperature(tb: Tables, nTrapped: number): number {
  return tb.tc0 * power(nTrapped / tb.n, tb.tcExponent);
}

/** T < Tc(N) with the running energy sum (seed Eqs. 1 and 46), latched. */
function checkWin(tb: Tables): void {
  const n = tb.nTrapped;
  if (tb.won || n === 0 || !tb.winRule) return;
  if (tb.energySum / n < criticalTemperature(tb, n)) tb.won = true;
}

/** Row r leaves the trapped set (over the rim or by the knife). */
function remove(tb: Tables, r: number, status: number): void {
  tb.plan[PLAN_WIDTH * r + PLAN_STATUS] = status;
  tb.nTrapped--;
  tb.energySum -= rowEnergy(tb, r);
  tb.state[STATE_WIDTH * r + STATE_COUNT] += 1;
  unlink(tb, r);
  predict(tb, r);
  checkWin(tb);
}

/** Remove trapped row r now if its energy exceeds m g H; true if removed. */
export function knifeCut(tb: Tables, r: number): boolean {
  if (!tb.knife) return false;
  const m = tb.queued[QUEUED_WIDTH * r + QUEUED_MASS];
  if (rowEnergy(tb, r) > m * tb.gravity * tb.trapHeight) {
    log(tb, EV_KNIFE, tb.plan[PLAN_WIDTH * r + PLAN_ATOM], -1);
    remove(tb, r, GONE);
    return true;
  }
  return false;
}

/** A pair event at time t: stale if the partner moved on, else the collision (seed Eqs. 10-12). */
export function pairEvent(tb: Tables, r: number, t: number): void {
  const S = tb.state;
  const j = tb.plan[PLAN_WIDTH * r + PLAN_PARTNER];
  if (
    tb.won ||
    (S[STATE_WIDTH * j + STATE_COUNT] | 0) !== tb.plan[PLAN_WIDTH * r + PLAN_PARTNER_COUNT]
  ) {
    tb.stale++; // the partner moved on (or pairs are over)
    predict(tb, r);
    return;
  }
  // lo, hi: the rows of the lower and higher world index
  const swap = S[STATE_WIDTH * j + STATE_ATOM] < S[STATE_WIDTH * r + STATE_ATOM];
  const lo = swap ? j : r;
  const hi = swap ? r : j;
  clockTo(tb, t);
  move(tb, lo);
  move(tb, hi);
  const sl = STATE_WIDTH * lo;
  const sh = STATE_WIDTH * hi;
  const io = tb.io;
  io[PAIR_IN_RX] = S[sh + STATE_X] - S[sl + STATE_X];
  io[PAIR_IN_RY] = S[sh + STATE_Y] - S[sl + STATE_Y];
  io[PAIR_IN_VX1] = S[sl + STATE_VX];
  io[PAIR_IN_VY1] = S[sl + STATE_VY];
  io[PAIR_IN_VX2] = S[sh + STATE_VX];
  io[PAIR_IN_VY2] = S[sh + STATE_VY];
  io[PAIR_IN_M1] = tb.queued[QUEUED_WIDTH * lo + QUEUED_MASS];
  io[PAIR_IN_M2] = tb.queued[QUEUED_WIDTH * hi + QUEUED_MASS];
  collidePair(io);
  S[sl + STATE_VX] = io[OUT_VX1];
  S[sl + STATE_VY] = io[OUT_VY1];
  S[sh + STATE_VX] = io[OUT_VX2];
  S[sh + STATE_VY] = io[OUT_VY2];
  tb.pairs++;
  S[sl + STATE_COUNT] += 1;
  S[sh + STATE_COUNT] += 1;
  log(tb, EV_PAIR, tb.plan[PLAN_WIDTH * lo + PLAN_ATOM], tb.plan[PLAN_WIDTH * hi + PLAN_ATOM]);
  if (!knifeCut(tb, lo)) predict(tb, lo);
  if (!knifeCut(tb, hi)) predict(tb, hi);
}

/**
 * Row r enters the next cell (kind KIND_CROSS_X or KIND_CROSS_Y) at time t. Only the row
 * or column of cells that came within reach needs a scan: pairs with the other neighbours
 * are held already. Once the gas has condensed the grid is no longer kept.
 */
export function crossEvent(tb: Tables, r: number, kind: number, t: number): void {
  tb.crossings++;
  if (tb.won) {
    predict(tb, r);
    return;
  }
  const P = tb.plan;
  const p = PLAN_WIDTH * r;
  const cellX = P[p + PLAN_CELL_X];
  const cellY = P[p + PLAN_CELL_Y];
  const to = P[p + PLAN_CROSS_TO];
  unlink(tb, r);
  if (kind === KIND_CROSS_X) {
    link(tb, r, to, cellY);
    const c = 2 * to - cellX;
    if (c >= 0 && c < tb.nx)
      scan(tb, r, c, c, cellY > 0 ? cellY - 1 : 0, cellY < tb.ny - 1 ? cellY + 1 : tb.ny - 1);
  } else {
    link(tb, r, cellX, to);
    tb.queued[QUEUED_WIDTH * r + QUEUED_ARC_CROSS_T] = t;
    const c = 2 * to - cellY;
    if (c >= 0 && c < tb.ny)
      scan(tb, r, cellX > 0 ? cellX - 1 : 0, cellX < tb.nx - 1 ? cellX + 1 : tb.nx - 1, c, c);
  }
  predictCross(tb, r); // its real event stands, or the scan found an earlier pair
  setKey(tb, r);
}

/** Row r meets the wall at time t: over the rim it escapes (SPEC 2.3), else it bounces. */
export function wallEvent(tb: Tables, r: number, t: number): void {
  clockTo(tb, t);
  move(tb, r);
  const S = tb.state;
  const s = STATE_WIDTH * r;
  const x = S[s + STATE_X];
  if (Math.abs(x) > tb.xRim) {
    log(tb, EV_ESCAPE, tb.plan[PLAN_WIDTH * r + PLAN_ATOM], -1);
    remove(tb, r, ESCAPED);
    return;
  }
  const vx = S[s + STATE_VX];
  const vy = S[s + STATE_VY];
  const speed = Math.sqrt(vx * vx + vy * vy);
  const damped = tb.won && speed >= WIN_DAMPING_MIN_SPEED; // seed Eq. (34)
  const changes = damped || speed < WALL_MIN_NORMAL_SPEED;
  if (changes) tb.energySum -= rowEnergy(tb, r);
  const io = tb.io;
  io[ATOM_IN_X] = x;
  io[ATOM_IN_VX] = vx;
  io[ATOM_IN_VY] = vy;
  io[ATOM_IN_CURVATURE] = tb.curvature;
  if (damped) {
    io[WALL_IN_KEEP] = 1.0 - WIN_DAMPING;
    io[WALL_IN_V_MIN] = WIN_NORMAL_SPEED_FLOOR;
    settleWall(io);
  } else {
    io[WALL_IN_V_MIN] = WALL_MIN_NORMAL_SPEED;
    bounceWall(io);
  }
  S[s + STATE_VX] = io[OUT_VX];
  S[s + STATE_VY] = io[OUT_VY];
  if (changes) tb.energySum += rowEnergy(tb, r);
  tb.walls++;
  S[s + STATE_COUNT] += 1;
  log(tb, EV_WALL, tb.plan[PLAN_WIDTH * r + PLAN_ATOM], -1);
  predict(tb, r);
}

/** Escaped row r leaves the window at time t: gone. */
export function exitEvent(tb: Tables, r: number, t: number): void {
  clockTo(tb, t);
  move(tb, r);
  tb.plan[PLAN_WIDTH * r + PLAN_STATUS] = GONE;
  tb.state[STATE_WIDTH * r + STATE_COUNT] += 1;
  log(tb, EV_GONE, tb.plan[PLAN_WIDTH * r + PLAN_ATOM], -1);
  predict(tb, r);
}
