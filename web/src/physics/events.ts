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
import {
  ATOM_IN,
  OUT,
  PAIR_IN,
  WALL_IN,
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
  PLAN,
  PLAN_WIDTH,
  QUEUED,
  QUEUED_WIDTH,
  STATE,
  STATE_WIDTH,
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
  const dt = t - S[s + STATE.t];
  S[s + STATE.x] = flightX(S[s + STATE.x], S[s + STATE.vx], dt);
  S[s + STATE.y] = flightY(S[s + STATE.y], S[s + STATE.vy], 0.5 * tb.gravity, dt);
  S[s + STATE.vy] = flightVy(S[s + STATE.vy], tb.gravity, dt);
  S[s + STATE.t] = t;
  tb.queued[QUEUED_WIDTH * r + QUEUED.arcCrossT] = -Infinity; // a new arc: no y crossing yet
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
  return tb.tc0 * Math.pow(nTrapped / tb.n, tb.tcExponent);
}

/** T < Tc(N) with the running energy sum (seed Eqs. 1 and 46), latched. */
function checkWin(tb: Tables): void {
  const n = tb.nTrapped;
  if (tb.won || n === 0 || !tb.winRule) return;
  if (tb.energySum / n < criticalTemperature(tb, n)) tb.won = true;
}

/** Row r leaves the trapped set (over the rim or by the knife). */
function remove(tb: Tables, r: number, status: number): void {
  tb.plan[PLAN_WIDTH * r + PLAN.status] = status;
  tb.nTrapped--;
  tb.energySum -= rowEnergy(tb, r);
  tb.state[STATE_WIDTH * r + STATE.count] += 1;
  unlink(tb, r);
  predict(tb, r);
  checkWin(tb);
}

/** Remove trapped row r now if its energy exceeds m g H; true if removed. */
export function knifeCut(tb: Tables, r: number): boolean {
  if (!tb.knife) return false;
  const m = tb.queued[QUEUED_WIDTH * r + QUEUED.mass];
  if (rowEnergy(tb, r) > m * tb.gravity * tb.trapHeight) {
    log(tb, EV_KNIFE, tb.plan[PLAN_WIDTH * r + PLAN.atom], -1);
    remove(tb, r, GONE);
    return true;
  }
  return false;
}

/** A pair event at time t: stale if the partner moved on, else the collision (seed Eqs. 10-12). */
export function pairEvent(tb: Tables, r: number, t: number): void {
  const S = tb.state;
  const j = tb.plan[PLAN_WIDTH * r + PLAN.partner];
  if (
    tb.won ||
    (S[STATE_WIDTH * j + STATE.count] | 0) !== tb.plan[PLAN_WIDTH * r + PLAN.partnerCount]
  ) {
    tb.stale++; // the partner moved on (or pairs are over)
    predict(tb, r);
    return;
  }
  // lo, hi: the rows of the lower and higher world index
  const swap = S[STATE_WIDTH * j + STATE.atom] < S[STATE_WIDTH * r + STATE.atom];
  const lo = swap ? j : r;
  const hi = swap ? r : j;
  clockTo(tb, t);
  move(tb, lo);
  move(tb, hi);
  const sl = STATE_WIDTH * lo;
  const sh = STATE_WIDTH * hi;
  const io = tb.io;
  io[PAIR_IN.rx] = S[sh + STATE.x] - S[sl + STATE.x];
  io[PAIR_IN.ry] = S[sh + STATE.y] - S[sl + STATE.y];
  io[PAIR_IN.vx1] = S[sl + STATE.vx];
  io[PAIR_IN.vy1] = S[sl + STATE.vy];
  io[PAIR_IN.vx2] = S[sh + STATE.vx];
  io[PAIR_IN.vy2] = S[sh + STATE.vy];
  io[PAIR_IN.m1] = tb.queued[QUEUED_WIDTH * lo + QUEUED.mass];
  io[PAIR_IN.m2] = tb.queued[QUEUED_WIDTH * hi + QUEUED.mass];
  collidePair(io);
  S[sl + STATE.vx] = io[OUT.vx1];
  S[sl + STATE.vy] = io[OUT.vy1];
  S[sh + STATE.vx] = io[OUT.vx2];
  S[sh + STATE.vy] = io[OUT.vy2];
  tb.pairs++;
  S[sl + STATE.count] += 1;
  S[sh + STATE.count] += 1;
  log(tb, EV_PAIR, tb.plan[PLAN_WIDTH * lo + PLAN.atom], tb.plan[PLAN_WIDTH * hi + PLAN.atom]);
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
  const cellX = P[p + PLAN.cellX];
  const cellY = P[p + PLAN.cellY];
  const to = P[p + PLAN.crossTo];
  unlink(tb, r);
  if (kind === KIND_CROSS_X) {
    link(tb, r, to, cellY);
    const c = 2 * to - cellX;
    if (c >= 0 && c < tb.nx)
      scan(tb, r, c, c, cellY > 0 ? cellY - 1 : 0, cellY < tb.ny - 1 ? cellY + 1 : tb.ny - 1);
  } else {
    link(tb, r, cellX, to);
    tb.queued[QUEUED_WIDTH * r + QUEUED.arcCrossT] = t;
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
  const x = S[s + STATE.x];
  if (Math.abs(x) > tb.xRim) {
    log(tb, EV_ESCAPE, tb.plan[PLAN_WIDTH * r + PLAN.atom], -1);
    remove(tb, r, ESCAPED);
    return;
  }
  const vx = S[s + STATE.vx];
  const vy = S[s + STATE.vy];
  const speed = Math.sqrt(vx * vx + vy * vy);
  const damped = tb.won && speed >= WIN_DAMPING_MIN_SPEED; // seed Eq. (34)
  const changes = damped || speed < WALL_MIN_NORMAL_SPEED;
  if (changes) tb.energySum -= rowEnergy(tb, r);
  const io = tb.io;
  io[ATOM_IN.x] = x;
  io[ATOM_IN.vx] = vx;
  io[ATOM_IN.vy] = vy;
  io[ATOM_IN.curvature] = tb.curvature;
  if (damped) {
    io[WALL_IN.keep] = 1.0 - WIN_DAMPING;
    io[WALL_IN.vMin] = WIN_NORMAL_SPEED_FLOOR;
    settleWall(io);
  } else {
    io[WALL_IN.vMin] = WALL_MIN_NORMAL_SPEED;
    bounceWall(io);
  }
  S[s + STATE.vx] = io[OUT.vx];
  S[s + STATE.vy] = io[OUT.vy];
  if (changes) tb.energySum += rowEnergy(tb, r);
  tb.walls++;
  S[s + STATE.count] += 1;
  log(tb, EV_WALL, tb.plan[PLAN_WIDTH * r + PLAN.atom], -1);
  predict(tb, r);
}

/** Escaped row r leaves the window at time t: gone. */
export function exitEvent(tb: Tables, r: number, t: number): void {
  clockTo(tb, t);
  move(tb, r);
  tb.plan[PLAN_WIDTH * r + PLAN.status] = GONE;
  tb.state[STATE_WIDTH * r + STATE.count] += 1;
  log(tb, EV_GONE, tb.plan[PLAN_WIDTH * r + PLAN.atom], -1);
  predict(tb, r);
}
