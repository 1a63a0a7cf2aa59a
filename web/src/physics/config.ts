/**
 * SimulationConfig (issue 26.2), twin of src/evapcool/physics/config.py: every parameter of a
 * new Simulation checked once, at the boundary: `new Simulation(options)` builds one from its
 * options, and nothing below checks it again. Ranges come from limits.py's table
 * (limits.json); errors are RangeErrors naming the parameter.
 */
import {
  ATOM_RADIUS,
  CURVATURE,
  ESCAPE_RULES,
  GRAVITY,
  N_ATOMS,
  TC_EXPONENT_SEED,
  TRAP_HEIGHT,
  type EscapeRule,
} from "./constants";
import { CLASSIC_ROOM, checkRoom, type Room } from "./room";
import { bad, num } from "./state";
import { checkStart, perAtomWithin, type Motion } from "./validation";
import {
  CURVATURE as CURVATURE_RANGE,
  GRAVITY as GRAVITY_RANGE,
  MASS as MASS_RANGE,
  N_ATOMS as N_ATOMS_RANGE,
  RADIUS as RADIUS_RANGE,
  SEED as SEED_RANGE,
  TC_EXPONENT as TC_EXPONENT_RANGE,
  TRAP_HEIGHT as TRAP_HEIGHT_RANGE,
  type Range,
} from "../limits";

/** Points as interleaved numbers [x0, y0, x1, y1, ...] or as pairs [[x0, y0], ...]. */
export type Points = ArrayLike<number> | ReadonlyArray<readonly [number, number]>;

export interface SimulationOptions {
  /** Atoms at the start (default 49; the number of positions if those are given). */
  nAtoms?: number;
  /** Radius, px: one for all, or one per atom (then positions must be given). Default 12. */
  radius?: number | ArrayLike<number>;
  /** Mass: one for all or one per atom. Default 1. */
  mass?: number | ArrayLike<number>;
  /** a of the cup y = a x^2, per px. Default 0.01. */
  curvature?: number;
  /** g, px / frame^2. Default 10/30. */
  gravity?: number;
  /** Rim height H, px above the lowest centre position (Infinity allowed). Default 400. */
  trapHeight?: number;
  /** The room around the cup: where escaped atoms are gone, how high the start fills. Default the original's. */
  room?: Room;
  /** Seed of the start's generator (a whole number >= 0); a random one if absent. */
  seed?: number;
  /** p in Tc(N) = Tc0 (N / N0)^p. Default 2/3 (seed Eq. 46); 2/5 is the cup's Bose gas. */
  tcExponent?: number;
  /** "rim" (atoms fly over the rim, default) or "knife" (energy above m g H cut at once). */
  escape?: EscapeRule;
  /** The win rule: false keeps the gas a gas below Tc. Default true. */
  win?: boolean;
  /** Keep every event in `eventLog` (tests, traces). Default false. */
  recordEvents?: boolean;
  /** Starting centres (trap coordinates), instead of the game's rows of cells. */
  positions?: Points;
  /** Starting velocities, px / frame, with positions. */
  velocities?: Points;
}

const OPTION_KEYS = new Set([
  "nAtoms",
  "radius",
  "mass",
  "curvature",
  "gravity",
  "trapHeight",
  "room",
  "seed",
  "tcExponent",
  "escape",
  "win",
  "recordEvents",
  "positions",
  "velocities",
]);

/** A checked set of Simulation parameters (build it with checkedConfig). */
export interface SimulationConfig {
  readonly nAtoms: number;
  /** One per atom. */
  readonly radius: Float64Array;
  readonly mass: Float64Array;
  readonly curvature: number;
  readonly gravity: number;
  readonly trapHeight: number;
  readonly tcExponent: number;
  readonly room: Room;
  /** The start generator's seed; null: one is drawn. */
  readonly seed: number | null;
  readonly escape: EscapeRule;
  readonly win: boolean;
  readonly recordEvents: boolean;
  /** Given starting centres and velocities (trap coordinates), or null for the cup's loading. */
  readonly start: Motion | null;
}

/** Each option checked once, before anything is allocated per atom; RangeError naming it. */
export function checkedConfig(options: SimulationOptions = {}): SimulationConfig {
  if (typeof options !== "object" || options === null) throw bad("options", "an object", options);
  for (const k of Object.keys(options))
    if (!OPTION_KEYS.has(k))
      throw bad("options", `free of unknown names (known: ${[...OPTION_KEYS].join(", ")})`, k);
  const o = options;
  const given = o.positions !== undefined || o.velocities !== undefined;
  if (given && (o.positions === undefined || o.velocities === undefined))
    throw bad("velocities", "given together with positions", given);
  let n = o.nAtoms;
  if (n === undefined) n = o.positions !== undefined ? pointCount(o.positions) : N_ATOMS;
  N_ATOMS_RANGE.check("nAtoms", n);
  const radius = perAtom(RADIUS_RANGE, "radius", o.radius, n, ATOM_RADIUS);
  const curvature = inRange(CURVATURE_RANGE, "curvature", o.curvature, CURVATURE);
  const win = o.win ?? true;
  if (typeof win !== "boolean") throw bad("win", "true or false", win);
  const recordEvents = o.recordEvents ?? false;
  if (typeof recordEvents !== "boolean") throw bad("recordEvents", "true or false", recordEvents);
  const escape = o.escape ?? "rim";
  if (!ESCAPE_RULES.includes(escape))
    throw bad("escape", `one of ${ESCAPE_RULES.join(", ")}`, escape);
  let start: SimulationConfig["start"] = null;
  if (given) {
    const [x, y] = points("positions", o.positions, n);
    const [vx, vy] = points("velocities", o.velocities, n);
    checkStart(x, y, vx, vy, radius, curvature);
    start = { x, y, vx, vy };
  } else {
    for (let i = 1; i < n; i++)
      if (radius[i] !== radius[0])
        throw bad("radius", "one number unless positions are given", "per-atom radii");
  }
  return {
    nAtoms: n,
    radius,
    mass: perAtom(MASS_RANGE, "mass", o.mass, n, 1),
    curvature,
    gravity: inRange(GRAVITY_RANGE, "gravity", o.gravity, GRAVITY),
    trapHeight: inRange(TRAP_HEIGHT_RANGE, "trapHeight", o.trapHeight, TRAP_HEIGHT),
    tcExponent: inRange(TC_EXPONENT_RANGE, "tcExponent", o.tcExponent, TC_EXPONENT_SEED),
    room: o.room === undefined ? CLASSIC_ROOM : checkRoom("room", o.room),
    seed: o.seed === undefined ? null : SEED_RANGE.check("seed", o.seed),
    escape,
    win,
    recordEvents,
    start,
  };
}

/** v within range (limits.py's table, issue 25.1), or fallback when not given. */
function inRange(range: Range, name: string, v: unknown, fallback: number): number {
  return v === undefined ? fallback : range.check(name, v);
}

function perAtom(
  range: Range,
  name: string,
  v: unknown,
  n: number,
  fallback: number,
): Float64Array {
  if (v === undefined || typeof v === "number")
    return new Float64Array(n).fill(inRange(range, name, v, fallback));
  const arr = v as ArrayLike<number>;
  if (typeof arr !== "object" || arr === null || arr.length !== n)
    throw bad(name, `${range.allowed()}, or ${n} such numbers`, v);
  perAtomWithin(name, arr, range);
  return Float64Array.from(arr);
}

function pointCount(v: Points): number {
  const first = (v as ArrayLike<unknown>)[0];
  return typeof first === "object" && first !== null ? v.length : Math.floor(v.length / 2);
}

/** Points as two columns; RangeError unless exactly n finite points. */
export function points(name: string, v: unknown, n: number): [Float64Array, Float64Array] {
  const xs = new Float64Array(n);
  const ys = new Float64Array(n);
  const arr = v as ArrayLike<unknown>;
  const allowed = `${n} finite points ([x, y] pairs or ${2 * n} interleaved numbers)`;
  if (typeof arr !== "object" || arr === null) throw bad(name, allowed, v);
  const pairs = arr.length > 0 && typeof arr[0] === "object" && arr[0] !== null;
  if (arr.length !== (pairs ? n : 2 * n)) throw bad(name, allowed, v);
  for (let i = 0; i < n; i++) {
    let x: unknown;
    let y: unknown;
    if (pairs) {
      const p = arr[i] as ArrayLike<unknown>;
      if (typeof p !== "object" || p === null || p.length !== 2)
        throw bad(`${name}[${i}]`, "an [x, y] pair", p);
      x = p[0];
      y = p[1];
    } else {
      x = arr[2 * i];
      y = arr[2 * i + 1];
    }
    if (!num(x) || !num(y))
      throw bad(`${name}[${i}]`, "a point of finite numbers", pairs ? arr[i] : [x, y]);
    xs[i] = x;
    ys[i] = y;
  }
  return [xs, ys];
}
