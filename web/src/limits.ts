/**
 * The allowed range of every parameter, read from `limits.json`, which
 * `scripts/web_limits.py` writes from Python's `src/evapcool/limits.py`: one table for both
 * editions, so both refuse the same values with the same words (issue 25.1). Messages are
 * built as Python's `Range.allowed()` and `bad_value()` build them, numbers printed as
 * Python prints them (`repr` and `:g`).
 */
import table from "./limits.json";

type Bound = number | "inf";
interface RangeRow {
  low: Bound;
  high: Bound;
  unit: string;
  integer: boolean;
  low_open: boolean;
  inf_ok: boolean;
}

const num = (b: Bound): number => (b === "inf" ? Infinity : b);

/** Python's `repr(float)`: shortest round-trip digits, exponent below 1e-4 and from 1e16. */
export function pyFloat(x: number): string {
  if (Number.isNaN(x)) return "nan";
  if (!Number.isFinite(x)) return x > 0 ? "inf" : "-inf";
  if (x === 0) return Object.is(x, -0) ? "-0.0" : "0.0";
  const [mantissa, expText] = x.toExponential().split("e");
  const exp = Number(expText);
  if (exp < -4 || exp >= 16) return `${mantissa}e${exp < 0 ? "-" : "+"}${pad2(Math.abs(exp))}`;
  const s = String(x);
  return /[.e]/.test(s) ? s : `${s}.0`;
}

/** Python's `format(x, "g")`: 6 significant digits, trailing zeros dropped. */
export function pyG(x: number): string {
  if (Number.isNaN(x)) return "nan";
  if (!Number.isFinite(x)) return x > 0 ? "inf" : "-inf";
  if (x === 0) return Object.is(x, -0) ? "-0" : "0";
  const [mantissa, expText] = x.toExponential(5).split("e");
  const exp = Number(expText);
  if (exp < -4 || exp >= 6)
    return `${trimZeros(mantissa)}e${exp < 0 ? "-" : "+"}${pad2(Math.abs(exp))}`;
  return trimZeros(x.toFixed(Math.max(0, 5 - exp)));
}

/** Python's `repr` of a value in an error message, shortened like `limits.shown`. */
export function shown(value: unknown): string {
  if (typeof value === "number") return pyFloat(value);
  if (typeof value === "string") {
    const cut = value.length > 40 ? `${value.slice(0, 18)}...${value.slice(-19)}` : value;
    return `'${cut}'`;
  }
  if (typeof value === "boolean") return value ? "True" : "False";
  if (value === null || value === undefined) return "None";
  if (Array.isArray(value)) {
    const items = value.slice(0, 4).map(shown);
    return `[${items.join(", ")}${value.length > 4 ? ", ..." : ""}]`;
  }
  return String(value);
}

function pad2(n: number): string {
  return n < 10 ? `0${n}` : String(n);
}

function trimZeros(s: string): string {
  return s.includes(".") ? s.replace(/\.?0+$/, "") : s;
}

/**
 * A bad value of one parameter with its name as data, the twin of Python's
 * `limits.ParameterError` (issue 26.2): `message` is the API's line ("nAtoms: ..."); a page
 * renders it with its own option names from a table (`render`), never by rewriting text.
 */
export class ParameterError extends RangeError {
  constructor(
    readonly parameter: string,
    readonly detail: string,
    readonly sep: string = " ",
  ) {
    super(`${parameter}${sep}${detail}`);
    this.name = "RangeError";
  }

  /** The line with the parameter under its name in names (e.g. nAtoms -> atoms). */
  render(names: Readonly<Record<string, string>>): string {
    return `${names[this.parameter] ?? this.parameter}${this.sep}${this.detail}`;
  }
}

/** A closed interval [low, high] (open at low if lowOpen), whole numbers if integer. */
export class Range {
  readonly low: number;
  readonly high: number;
  readonly unit: string;
  readonly integer: boolean;
  readonly lowOpen: boolean;
  readonly infOk: boolean;

  constructor(row: RangeRow) {
    this.low = num(row.low);
    this.high = num(row.high);
    this.unit = row.unit;
    this.integer = row.integer;
    this.lowOpen = row.low_open;
    this.infOk = row.inf_ok;
  }

  /** '0.01 to 1000 px', '> 0 px', '1 to 1000000' (Python's `Range.span`). */
  span(): string {
    const unit = this.unit ? ` ${this.unit}` : "";
    let text: string;
    if (this.lowOpen && !Number.isFinite(this.high)) text = `> ${pyG(this.low)}${unit}`;
    else if (this.lowOpen) text = `> ${pyG(this.low)} and <= ${pyG(this.high)}${unit}`;
    else if (this.integer) text = `${BigInt(this.low)} to ${BigInt(this.high)}${unit}`;
    else text = `${pyG(this.low)} to ${pyG(this.high)}${unit}`;
    return text + (this.infOk && Number.isFinite(this.high) ? " or inf" : "");
  }

  /** 'a whole number from 1 to 1000000', 'a number > 0 px or inf' (Python's `allowed`). */
  allowed(): string {
    const kind = this.integer ? "a whole number" : "a number";
    return this.lowOpen ? `${kind} ${this.span()}` : `${kind} from ${this.span()}`;
  }

  contains(value: number): boolean {
    if (Number.isNaN(value)) return false;
    if (value === Infinity && this.infOk) return true;
    const above = this.lowOpen ? value > this.low : value >= this.low;
    return above && value <= this.high && Number.isFinite(value);
  }

  /** value if within the range, else RangeError "name must be <allowed> (got <value>)". */
  check(name: string, value: unknown): number {
    const ok =
      typeof value === "number" &&
      (this.integer
        ? Number.isInteger(value) && value >= this.low && value <= this.high
        : this.contains(value));
    // A whole number shows as Python shows an int: 0, not 0.0.
    const whole = this.integer && typeof value === "number" && Number.isInteger(value);
    if (!ok)
      throw whole ? wholeError(name, this.allowed(), value) : badValue(name, this.allowed(), value);
    return value as number;
  }
}

function wholeError(name: string, allowed: string, value: number): RangeError {
  return new RangeError(`${name} must be ${allowed} (got ${BigInt(value)})`);
}

/** "name must be allowed (got value)", Python's `limits.bad_value`. */
export function badValue(name: string, allowed: string, value: unknown): RangeError {
  return new RangeError(`${name} must be ${allowed} (got ${shown(value)})`);
}

const ranges = table.ranges as Record<string, RangeRow>;
const row = (name: string): Range => {
  const r = ranges[name];
  if (r === undefined) throw new Error(`limits.json has no range ${name}`);
  return new Range(r);
};
const bound = (name: string): number => num((table.bounds as Record<string, Bound>)[name]);

export const N_ATOMS = row("N_ATOMS");
export const RADIUS = row("RADIUS");
export const MASS = row("MASS");
export const GRAVITY = row("GRAVITY");
export const CURVATURE = row("CURVATURE");
export const TRAP_HEIGHT = row("TRAP_HEIGHT");
export const TC_EXPONENT = row("TC_EXPONENT");
export const WINDOW_SIDE = row("WINDOW_SIDE");
export const SEED = row("SEED");
export const DT = row("DT");
export const APPLET_RADIUS = row("APPLET_RADIUS");
export const APPLET_ATOMS = row("APPLET_ATOMS");
export const APPLET_SPEED = row("APPLET_SPEED");
export const APPLET_HEIGHT = row("APPLET_HEIGHT");
/** A recorded game's atoms and radius (replay codes, class challenges). */
export const REPLAY_ATOMS = row("REPLAY_ATOMS");
export const REPLAY_RADIUS = row("REPLAY_RADIUS");
/** The longest recorded game, frames. */
export const REPLAY_FRAMES_MAX = bound("REPLAY_FRAMES_MAX");
/** Speed of any atom of a state or start, px/frame. */
export const VELOCITY_MAX = bound("VELOCITY_MAX");
/** |x| and y of any centre, px. */
export const POSITION_MAX = bound("POSITION_MAX");
/** The longest time a stored high-score row may claim, s. */
export const SCORE_SECONDS_MAX = bound("SCORE_SECONDS_MAX");
/** A state saved mid-run may touch or sit on the wall up to this relative round-off. */
export const CONTACT_TOLERANCE = bound("CONTACT_TOLERANCE");
