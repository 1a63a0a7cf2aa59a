/**
 * What the game and the view read from the physics: the camelCase shape of Python's
 * `Simulation` (SPEC section 3). `engine.ts` adapts the engine in `../physics` to it, so
 * nothing else imports the physics directly.
 */

/** Per-atom snapshot in trap coordinates (x right, y up, px; velocities px / frame). */
export interface AtomArrays {
  x: Float64Array;
  y: Float64Array;
  vx: Float64Array;
  vy: Float64Array;
  radius: Float64Array;
  mass: Float64Array;
  /** How many entries are valid (arrays may be longer and reused). */
  count: number;
}

export interface SimLike {
  /** Simulation time in frames (1/30 s). */
  readonly time: number;
  readonly nAtoms: number;
  readonly nTrapped: number;
  readonly nEscaped: number;
  /** Rim height H, px above the lowest centre position. */
  trapHeight: number;
  readonly rimHalfWidth: number;
  readonly curvature: number;
  readonly gravity: number;
  readonly temperature: number;
  readonly initialTemperature: number;
  readonly criticalTemperature: number;
  readonly tcExponent: number;
  readonly won: boolean;
  readonly collisionCount: number;
  /** Screen position (px, y down) of the trap origin in the 640 x 672 window. */
  readonly screenOrigin: readonly [number, number];
  advance(dt: number): void;
  /** Fill `out` with the trapped atoms now (reusing its arrays when long enough). */
  trapped(out: AtomArrays): AtomArrays;
  /** Fill `out` with the escaped atoms still falling inside the window. */
  escaped(out: AtomArrays): AtomArrays;
}

export function emptyAtoms(): AtomArrays {
  const z = () => new Float64Array(0);
  return { x: z(), y: z(), vx: z(), vy: z(), radius: z(), mass: z(), count: 0 };
}

/** Grow the arrays of `out` to hold n atoms (kept when already long enough). */
export function ensureAtoms(out: AtomArrays, n: number): AtomArrays {
  if (out.x.length < n) {
    const cap = Math.max(n, Math.ceil(out.x.length * 1.5));
    out.x = new Float64Array(cap);
    out.y = new Float64Array(cap);
    out.vx = new Float64Array(cap);
    out.vy = new Float64Array(cap);
    out.radius = new Float64Array(cap);
    out.mass = new Float64Array(cap);
  }
  out.count = n;
  return out;
}
