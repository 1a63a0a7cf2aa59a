/**
 * The limits a state must keep, the twin of Python's `physics/validation.py` `check_world`:
 * every parameter within its range and the trapped atoms within reach and speed, from the
 * table both editions share (src/limits.ts), with Python's words (issue 25.1).
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
import { firstOverlap } from "./state";

/** What `checkWorld` reads of a parsed state. */
export interface WorldLimitsInput {
  time: number;
  curvature: number;
  gravity: number;
  trapHeight: number;
  tcExponent: number;
  x: Float64Array;
  y: Float64Array;
  vx: Float64Array;
  vy: Float64Array;
  t: Float64Array;
  radius: Float64Array;
  mass: Float64Array;
  trapped: (i: number) => boolean;
}

/** RangeError naming the first parameter or atom out of its range, in Python's order. */
export function checkWorld(w: WorldLimitsInput): void {
  N_ATOMS.check("n_atoms", w.radius.length);
  CURVATURE.check("curvature", w.curvature);
  GRAVITY.check("gravity", w.gravity);
  TRAP_HEIGHT.check("trap_height", w.trapHeight);
  TC_EXPONENT.check("tc_exponent", w.tcExponent);
  perAtom("radius", w.radius, RADIUS);
  perAtom("mass", w.mass, MASS);
  const n = w.radius.length;
  const halfG = 0.5 * w.gravity;
  const ids: number[] = [];
  const pos: number[] = [];
  const vel: number[] = [];
  for (let i = 0; i < n; i++) {
    if (!w.trapped(i)) continue;
    const dt = w.time - w.t[i];
    ids.push(i);
    // free flight to now, seed Eqs. (3) and (4), as Python's World.state_at carries them
    pos.push(w.x[i] + w.vx[i] * dt, w.y[i] + w.vy[i] * dt - halfG * dt * dt);
    vel.push(w.vx[i], w.vy[i] - w.gravity * dt);
  }
  if (!pos.every(Number.isFinite) || !vel.every(Number.isFinite))
    throw new RangeError("positions and velocities must be finite");
  checkBounds(ids, pos, vel);
}

function perAtom(name: string, values: Float64Array, range: Range): void {
  for (let i = 0; i < values.length; i++)
    if (!(values[i] >= range.low && values[i] <= range.high))
      throw new RangeError(
        `${name} must be ${range.allowed()} (atom ${i} has ${pyFloat(values[i])})`,
      );
}

/** Python's `check_bounds`: the first atom too far from the vertex, then the first too fast. */
export function checkBounds(ids: number[], pos: number[], vel: number[]): void {
  for (let k = 0; k < ids.length; k++) {
    if (Math.max(Math.abs(pos[2 * k]), Math.abs(pos[2 * k + 1])) > POSITION_MAX)
      throw new RangeError(
        `positions must be within ${pyG(POSITION_MAX)} px of the cup's lowest point ` +
          `(atom ${ids[k]} is at (${pyG(pos[2 * k])}, ${pyG(pos[2 * k + 1])}))`,
      );
  }
  for (let k = 0; k < ids.length; k++) {
    if (Math.hypot(vel[2 * k], vel[2 * k + 1]) > VELOCITY_MAX)
      throw new RangeError(
        `velocities must be at most ${pyG(VELOCITY_MAX)} px/frame in speed ` +
          `(atom ${ids[k]} has (${pyG(vel[2 * k])}, ${pyG(vel[2 * k + 1])}))`,
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
  const n = x.length;
  const ids = Array.from({ length: n }, (_, i) => i);
  const interleave = (a: Float64Array, b: Float64Array): number[] =>
    Array.from({ length: 2 * n }, (_, k) => (k % 2 === 0 ? a[k >> 1] : b[k >> 1]));
  checkBounds(ids, interleave(x, y), interleave(vx, vy));
  for (let i = 0; i < n; i++) {
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
