/**
 * The state JSON shared by both editions (docs/state.md; Python: evapcool.physics.state).
 *
 * A state is everything the physics needs to go on exactly: each atom's stored state at
 * its own last-event time (positions move lazily), radius, mass and lifecycle, the clock,
 * the trap, the rules, and what the win needs (the starting temperature; N0 is the number
 * of atoms listed, gone ones included, so indices stay those of the run).
 * Python's twin: `src/evapcool/physics/state.py` (docs/twins.md).
 */
import { CONTACT_TOLERANCE, pyFloat } from "../limits";
import {
  CURVATURE,
  ESCAPE_RULES,
  GRAVITY,
  STATUS_NAMES,
  TC_EXPONENT_SEED,
  TRAP_HEIGHT,
  TRAPPED,
  type EscapeRule,
  type StatusName,
} from "./constants";
import type { Room } from "./room";
import { checkWorld, firstOverlap, flownToNow, type WorldLimitsInput } from "./validation";

export const STATE_FORMAT = "evapcool-state";
export const STATE_VERSION = 1;

/** A state as written: every field present, floats exact (JSON numbers round-trip). */
export interface SimulationState {
  format: typeof STATE_FORMAT;
  version: typeof STATE_VERSION;
  /** The clock, frames. */
  time: number;
  /** Rim height H, px; "inf" for a rim out of reach. */
  trap_height: number | "inf";
  curvature: number;
  gravity: number;
  /** Window (width, height), px: the screen mapping and the edges where escaped atoms are gone. */
  window: [number, number];
  escape: EscapeRule;
  tc_exponent: number;
  /** The win rule (false: the gas stays a gas below Tc). */
  win: boolean;
  won: boolean;
  /** T at the start: Tc0 = 0.75 of it (seed Eq. 46). */
  initial_temperature: number;
  /** Running sum of the trapped atoms' energies, as the engines keep it (the win uses it). */
  energy_sum: number;
  pair_collisions: number;
  wall_collisions: number;
  atoms: {
    /** Stored state of each atom at its own time t (t <= time). */
    x: number[];
    y: number[];
    vx: number[];
    vy: number[];
    t: number[];
    radius: number[];
    mass: number[];
    status: StatusName[];
  };
}

/** A state as read: a SimulationState's fields, all optional but the atoms' x, y, vx, vy
 * (defaults in docs/state.md); one radius or mass stands for every atom. */
export type StateInput = Partial<Omit<SimulationState, "atoms">> & {
  atoms: Pick<SimulationState["atoms"], "x" | "y" | "vx" | "vy"> &
    Partial<Pick<SimulationState["atoms"], "t" | "status">> &
    Partial<Record<"radius" | "mass", number | number[]>>;
};

/** A validated state, every default filled in, per-atom columns as typed arrays. */
export interface ParsedState extends WorldLimitsInput {
  /** The room the state's window field names. */
  room: Room;
  escape: EscapeRule;
  win: boolean;
  won: boolean;
  initialTemperature: number | undefined;
  energySum: number | undefined;
  pairCount: number;
  wallCount: number;
  /** 0 trapped, 1 escaped, 2 gone. */
  status: Int8Array;
}

const STATE_KEYS = new Set([
  "format",
  "version",
  "time",
  "trap_height",
  "curvature",
  "gravity",
  "window",
  "escape",
  "tc_exponent",
  "win",
  "won",
  "initial_temperature",
  "energy_sum",
  "pair_collisions",
  "wall_collisions",
  "atoms",
]);
const ATOM_KEYS = new Set(["x", "y", "vx", "vy", "t", "radius", "mass", "status"]);

/** A RangeError "<name> must be <allowed> (got <value>)", like Python's ValueError. */
export function bad(name: string, allowed: string, value: unknown): RangeError {
  return new RangeError(`${name} must be ${allowed} (got ${show(value)})`);
}

/** A short, readable rendering of a bad value for error messages. */
export function show(value: unknown): string {
  if (typeof value === "number") return String(value);
  if (typeof value === "string") return JSON.stringify(value);
  if (value === undefined) return "undefined";
  if (ArrayBuffer.isView(value))
    return `${value.constructor.name} of length ${(value as Float64Array).length}`;
  try {
    const s = JSON.stringify(value);
    return s.length > 60 ? s.slice(0, 57) + "..." : s;
  } catch {
    return String(value);
  }
}

function isObject(v: unknown): v is Record<string, unknown> {
  return typeof v === "object" && v !== null && !Array.isArray(v);
}

/** A field's value, or the fallback when absent; RangeError "<name> must be <allowed>" unless
 * ok(value). */
function field<T>(allowed: string, ok: (v: unknown) => boolean) {
  return (name: string, v: unknown, fallback: T): T => {
    if (v === undefined) return fallback;
    if (!ok(v)) throw bad(name, allowed, v);
    return v as T;
  };
}
/** A finite number (the type guard of every numeric field). */
export const num = (v: unknown): v is number => typeof v === "number" && Number.isFinite(v);
const finite = field<number>("a finite number", num);
const positive = field<number>("a positive finite number", (v) => num(v) && v > 0);
const count = field<number>(
  "a whole number >= 0",
  (v) => Number.isSafeInteger(v) && num(v) && v >= 0,
);
const flag = field<boolean>("true or false", (v) => typeof v === "boolean");

function column(name: string, v: unknown, n: number): Float64Array {
  if (!Array.isArray(v) || (n >= 0 && v.length !== n))
    throw bad(name, n >= 0 ? `an array of ${n} finite numbers` : "an array of finite numbers", v);
  const out = new Float64Array(v.length);
  for (let i = 0; i < v.length; i++) {
    const e: unknown = v[i];
    if (!num(e)) throw bad(`${name}[${i}]`, "a finite number", e);
    out[i] = e;
  }
  return out;
}

function perAtom(name: string, v: unknown, n: number, fallback: number): Float64Array {
  if (v === undefined || typeof v === "number")
    return new Float64Array(n).fill(positive(name, v, fallback));
  const out = column(name, v, n);
  for (let i = 0; i < n; i++)
    if (!(out[i] > 0)) throw bad(`${name}[${i}]`, "a positive finite number", out[i]);
  return out;
}

/**
 * The `window` field (docs/state.md) names the room as the window of the original's layout that
 * shows it: the cup's lowest point in the middle of a play area inside borders of 48 px (left)
 * and 96 px (right), and 128 px above the window's bottom (physics/state.py's room_of_window).
 */
const WINDOW: readonly [number, number] = [640, 672];
const LEFT_BORDER = 48;
const RIGHT_BORDER = 96;
const VERTEX_ABOVE_BOTTOM = 128;

/** The room that a state's window field names (view/screen.ts places it so too). */
export function roomOfWindow(window: readonly [number, number]): Room {
  const [w, h] = window;
  const x = LEFT_BORDER + (w - LEFT_BORDER - RIGHT_BORDER) / 2;
  const y = h - VERTEX_ABOVE_BOTTOM;
  return { left: x, right: w - x, below: h - y, above: y };
}

/** The window field for a room; RangeError if no window of the layout gives it. */
export function windowOfRoom(room: Room): [number, number] {
  const size: [number, number] = [
    Math.round(room.left + room.right),
    Math.round(room.below + room.above),
  ];
  const back = roomOfWindow(size);
  if ((["left", "right", "below", "above"] as const).some((side) => back[side] !== room[side]))
    throw new RangeError(
      `room must be one a window gives (view/screen.ts) to be written as a state (got ${JSON.stringify(room)})`,
    );
  return size;
}

/** Validate a window (width, height) of whole pixels, at least 160 x 160. */
export function checkWindow(name: string, v: unknown): [number, number] {
  if (
    !Array.isArray(v) ||
    v.length !== 2 ||
    !v.every((s) => typeof s === "number" && Number.isSafeInteger(s) && s >= 160)
  )
    throw bad(name, "two whole numbers (width, height) of at least 160 x 160 px", v);
  return [v[0] as number, v[1] as number];
}

/** Parse and validate a state (object or JSON text); RangeError naming the field if bad. */
export function parseState(input: unknown): ParsedState {
  let s: unknown = input;
  if (typeof input === "string") {
    try {
      s = JSON.parse(input);
    } catch (e) {
      throw new RangeError(`state must be JSON text (${(e as Error).message})`);
    }
  }
  if (!isObject(s)) throw bad("state", "an object with an atoms table", s);
  for (const k of Object.keys(s))
    if (!STATE_KEYS.has(k)) throw bad("state", `free of unknown fields`, k);
  if (s.format !== undefined && s.format !== STATE_FORMAT)
    throw bad("state.format", JSON.stringify(STATE_FORMAT), s.format);
  if (s.version !== undefined && s.version !== STATE_VERSION)
    throw bad("state.version", String(STATE_VERSION), s.version);
  const atoms = s.atoms;
  if (!isObject(atoms)) throw bad("state.atoms", "an object of per-atom arrays", atoms);
  for (const k of Object.keys(atoms))
    if (!ATOM_KEYS.has(k)) throw bad("state.atoms", "free of unknown fields", k);
  const x = column("state.atoms.x", atoms.x, -1);
  const n = x.length;
  if (n < 1) throw bad("state.atoms.x", "an array of at least 1 atom", atoms.x);
  const y = column("state.atoms.y", atoms.y, n);
  const vx = column("state.atoms.vx", atoms.vx, n);
  const vy = column("state.atoms.vy", atoms.vy, n);
  const time = finite("state.time", s.time, 0);
  const t =
    atoms.t === undefined ? new Float64Array(n).fill(time) : column("state.atoms.t", atoms.t, n);
  for (let i = 0; i < n; i++)
    if (t[i] > time) throw bad(`state.atoms.t[${i}]`, `at most the clock ${time}`, t[i]);
  const radius = perAtom("state.atoms.radius", atoms.radius, n, 12);
  const mass = perAtom("state.atoms.mass", atoms.mass, n, 1);
  const status = new Int8Array(n);
  if (atoms.status !== undefined) {
    if (!Array.isArray(atoms.status) || atoms.status.length !== n)
      throw bad(
        "state.atoms.status",
        `an array of ${n} of "trapped", "escaped", "gone"`,
        atoms.status,
      );
    for (let i = 0; i < n; i++) {
      const k = STATUS_NAMES.indexOf(atoms.status[i] as StatusName);
      if (k < 0)
        throw bad(`state.atoms.status[${i}]`, `"trapped", "escaped" or "gone"`, atoms.status[i]);
      status[i] = k;
    }
  }
  const trapHeight =
    s.trap_height === "inf" ? Infinity : positive("state.trap_height", s.trap_height, TRAP_HEIGHT);
  const escape = s.escape === undefined ? "rim" : s.escape;
  if (!ESCAPE_RULES.includes(escape as EscapeRule))
    throw bad("state.escape", `one of ${ESCAPE_RULES.join(", ")}`, escape);
  return {
    time,
    trapHeight,
    curvature: positive("state.curvature", s.curvature, CURVATURE),
    gravity: positive("state.gravity", s.gravity, GRAVITY),
    room: roomOfWindow(s.window === undefined ? WINDOW : checkWindow("state.window", s.window)),
    escape: escape as EscapeRule,
    tcExponent: positive("state.tc_exponent", s.tc_exponent, TC_EXPONENT_SEED),
    win: flag("state.win", s.win, true),
    won: flag("state.won", s.won, false),
    initialTemperature:
      s.initial_temperature === undefined
        ? undefined
        : finite("state.initial_temperature", s.initial_temperature, 0),
    energySum: s.energy_sum === undefined ? undefined : finite("state.energy_sum", s.energy_sum, 0),
    pairCount: count("state.pair_collisions", s.pair_collisions, 0),
    wallCount: count("state.wall_collisions", s.wall_collisions, 0),
    x,
    y,
    vx,
    vy,
    t,
    radius,
    mass,
    status,
  };
}

/**
 * A parsed state's trapped atoms where they are now (Python's world_from_state): centres inside
 * the cup (y >= a x^2) and pairs at least r_i + r_j apart up to round-off (CONTACT_TOLERANCE,
 * relative: a mid-run state's atoms touch after collisions; the condensate's no longer collide,
 * so after the win they may overlap), within the limits. RangeError naming the first offending
 * atoms (least index, then least partner) or field.
 */
export function checkState(p: ParsedState): void {
  const now = flownToNow(p);
  const { x, y } = now;
  const trapped = (i: number) => p.status[i] === TRAPPED;
  const tol = CONTACT_TOLERANCE;
  for (let i = 0; i < x.length; i++) {
    if (!trapped(i)) continue;
    const wall = p.curvature * x[i] * x[i];
    if (y[i] < wall - tol * (1 + Math.abs(wall))) {
      throw new RangeError(
        `state.atoms: atom ${i} at (${pyFloat(x[i])}, ${pyFloat(y[i])}) is outside the cup; centres must ` +
          `be inside it or on its wall, y >= a x^2 (a = ${pyFloat(p.curvature)})`,
      );
    }
  }
  const pair = p.won ? null : firstOverlap(x, y, p.radius, trapped, tol);
  if (pair !== null) {
    const [bi, bj] = pair;
    const d = Math.hypot(x[bj] - x[bi], y[bj] - y[bi]);
    throw new RangeError(
      `state.atoms: atoms ${bi} and ${bj} overlap (centres ${pyFloat(d)} apart, less than ` +
        `r${bi} + r${bj} = ${pyFloat(p.radius[bi] + p.radius[bj])}); atoms must be at least r_i + r_j apart`,
    );
  }
  checkWorld(p, now, trapped);
}
