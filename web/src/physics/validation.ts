/**
 * The limits a state must keep, the twin of Python's `physics/validation.py` `check_world`:
 * every parameter within its range and the trapped atoms within reach and speed, from the
 * table both editions share (src/limits.ts), with Python's words (issue 25.1); the overlap
 * check is the core's (core/overlap.c: firstOverlap), as Python's where it is built.
 */
import {
  CURVATURE,
  GRAVITY,
  MASS,
  N_ATOMS,
  POSITION_MAX,
  RADIUS,
  TC_EXPONENT,
  TRAP_HEIGHT,
  VELOCITY_MAX,
  pyFloat,
  pyG,
  type Range,
} from "../limits";
import { instance, OUT_OF_MEMORY } from "./instance";

/** Per-atom positions and velocities as columns, trap coordinates. */
export interface Motion {
  x: Float64Array;
  y: Float64Array;
  vx: Float64Array;
  vy: Float64Array;
}

/** What `checkWorld` reads of a parsed state. */
export interface WorldLimitsInput extends Motion {
  time: number;
  curvature: number;
  gravity: number;
  trapHeight: number;
  tcExponent: number;
  t: Float64Array;
  radius: Float64Array;
  mass: Float64Array;
}

/** Every atom carried from its own time t to the clock in free flight, seed Eqs. (3) and (4),
 * as Python's World.state_at carries it. */
export function flownToNow(w: WorldLimitsInput): Motion {
  const n = w.x.length;
  const halfG = 0.5 * w.gravity;
  const now: Motion = {
    x: new Float64Array(n),
    y: new Float64Array(n),
    vx: new Float64Array(n),
    vy: new Float64Array(n),
  };
  for (let i = 0; i < n; i++) {
    const dt = w.time - w.t[i];
    now.x[i] = w.x[i] + w.vx[i] * dt;
    now.y[i] = w.y[i] + w.vy[i] * dt - halfG * dt * dt;
    now.vx[i] = w.vx[i];
    now.vy[i] = w.vy[i] - w.gravity * dt;
  }
  return now;
}

/** RangeError naming the first parameter or atom out of its range, in Python's order; `now`:
 * the atoms carried to the clock (flownToNow), of which the trapped ones are checked. */
export function checkWorld(
  w: WorldLimitsInput,
  now: Motion,
  trapped: (i: number) => boolean,
): void {
  N_ATOMS.check("n_atoms", w.radius.length);
  CURVATURE.check("curvature", w.curvature);
  GRAVITY.check("gravity", w.gravity);
  TRAP_HEIGHT.check("trap_height", w.trapHeight);
  TC_EXPONENT.check("tc_exponent", w.tcExponent);
  perAtomWithin("radius", w.radius, RADIUS);
  perAtomWithin("mass", w.mass, MASS);
  const ids = Array.from(w.radius.keys()).filter(trapped);
  const columns = [now.x, now.y, now.vx, now.vy];
  if (!ids.every((i) => columns.every((c) => Number.isFinite(c[i]))))
    throw new RangeError("positions and velocities must be finite");
  checkBounds(ids, now);
}

/** RangeError "<name> must be <allowed> (atom i has <value>)" for the first value out of range. */
export function perAtomWithin(name: string, values: ArrayLike<unknown>, range: Range): void {
  for (let i = 0; i < values.length; i++) {
    const v = values[i];
    if (typeof v !== "number" || !range.contains(v))
      throw new RangeError(
        `${name} must be ${range.allowed()} (atom ${i} has ${typeof v === "number" ? pyFloat(v) : String(v)})`,
      );
  }
}

/** Python's `check_bounds`: the first atom too far from the vertex, then the first too fast. */
function checkBounds(ids: number[], m: Motion): void {
  for (const i of ids) {
    if (Math.max(Math.abs(m.x[i]), Math.abs(m.y[i])) > POSITION_MAX)
      throw new RangeError(
        `positions must be within ${pyG(POSITION_MAX)} px of the cup's lowest point ` +
          `(atom ${i} is at (${pyG(m.x[i])}, ${pyG(m.y[i])}))`,
      );
  }
  for (const i of ids) {
    if (Math.hypot(m.vx[i], m.vy[i]) > VELOCITY_MAX)
      throw new RangeError(
        `velocities must be at most ${pyG(VELOCITY_MAX)} px/frame in speed ` +
          `(atom ${i} has (${pyG(m.vx[i])}, ${pyG(m.vy[i])}))`,
      );
  }
}

/**
 * Python's `check_start` for positions and velocities given to a new Simulation: within
 * reach and speed, centres inside the cup (y >= a x^2 exactly), no pair closer than r_i + r_j.
 */
export function checkStart(
  x: Float64Array,
  y: Float64Array,
  vx: Float64Array,
  vy: Float64Array,
  radius: Float64Array,
  curvature: number,
): void {
  checkBounds(Array.from(x.keys()), { x, y, vx, vy });
  for (let i = 0; i < x.length; i++) {
    const wall = curvature * x[i] * x[i];
    if (y[i] - wall < 0)
      throw new RangeError(
        "positions must be centres inside the cup or on its wall, y >= a x^2 " +
          `(atom ${i} at (${pyG(x[i])}, ${pyG(y[i])}) is below the wall y = ${pyG(wall)})`,
      );
  }
  const pair = firstOverlap(x, y, radius, () => true, 0);
  if (pair !== null) {
    const [a, b] = pair;
    const d = Math.hypot(x[a] - x[b], y[a] - y[b]);
    throw new RangeError(
      "positions must not overlap: every pair at least r_i + r_j apart " +
        `(atoms ${a} and ${b} are ${pyG(d)} px apart, r_${a} + r_${b} = ${pyG(radius[a] + radius[b])} px)`,
    );
  }
}

/** The first pair (i < j, least i, then least j) of included atoms closer than
 * (r_i + r_j)(1 - tol), or null (core/overlap.c: Python's validation.first_overlap). */
export function firstOverlap(
  x: Float64Array,
  y: Float64Array,
  radius: Float64Array,
  included: (i: number) => boolean,
  tol: number,
): [number, number] | null {
  const n = x.length;
  const c = instance(); // a fresh memory for the columns and the scratch, dropped after
  const at = c.core_buffer(c.core_new(), 6 * n + Math.ceil(n / 8) + 2);
  if (at === 0) throw new RangeError(OUT_OF_MEMORY(n));
  const columns = new Float64Array(c.memory.buffer, at, 3 * n);
  [x, y, radius].forEach((column, k) => columns.set(column.subarray(0, n), k * n));
  const include = at + 24 * n;
  const flags = new Int8Array(c.memory.buffer, include, n);
  for (let i = 0; i < n; i++) flags[i] = included(i) ? 1 : 0;
  const pair = include + 8 * Math.ceil(n / 8);
  const work = pair + 8;
  if (!c.core_first_overlap(at, at + 8 * n, at + 16 * n, include, n, tol, work, pair)) return null;
  const [i, j] = new Int32Array(c.memory.buffer, pair, 2);
  return [i, j];
}
