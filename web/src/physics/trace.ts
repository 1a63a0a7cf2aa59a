/**
 * Event traces: the web twin of src/evapcool/physics/trace.py (docs/state.md).
 *
 * A trace is a starting state, a schedule of steps [dt, trap height, repeat], the events
 * processed over them and the state after the last step. `traceText` writes the layout of
 * Python's trace_text, floats as 17 significant digits (C's %.17g), so the text of a run
 * of this engine can be diffed against the Python engines' text of the same run.
 */
import { Simulation } from "./simulation";
import type { SimulationState, StateInput } from "./state";

export const TRACE_FORMAT = "evapcool-trace";
export const TRACE_VERSION = 1;
/** A schedule never runs longer than this many frames (a state with no events left). */
export const MAX_FRAMES = 100_000;

/** [dt frames, trap height px, how many times]. */
export type PackedStep = [number, number, number];
export type TraceEvent = [string, number, number, number];

export interface Trace {
  format: typeof TRACE_FORMAT;
  version: typeof TRACE_VERSION;
  case: string;
  description: string;
  events_requested: number;
  start: SimulationState | StateInput;
  steps: PackedStep[];
  events: TraceEvent[];
  end: SimulationState;
  summary: ReturnType<typeof summaryOf>;
}

// -- text ----------------------------------------------------------------------------------
/** x = m 2^e exactly as BigInts (x finite, nonzero). */
function binary(x: number): [bigint, number] {
  const view = new DataView(new ArrayBuffer(8));
  view.setFloat64(0, Math.abs(x));
  const bits = view.getBigUint64(0);
  const expBits = Number((bits >> 52n) & 0x7ffn);
  const frac = bits & 0xfffffffffffffn;
  if (expBits === 0) return [frac, -1074];
  return [frac | (1n << 52n), expBits - 1075];
}

/** True if |x| equals the decimal digits d (an integer) times 10^q exactly. */
function exactly(x: number, d: bigint, q: number): boolean {
  const [m, e] = binary(x);
  let lhs = m;
  let rhs = d;
  if (e >= 0) lhs <<= BigInt(e);
  else rhs <<= BigInt(-e);
  if (q >= 0) rhs *= 10n ** BigInt(q);
  else lhs *= 10n ** BigInt(-q);
  return lhs === rhs;
}

/**
 * C's "%.17g" (which Python's traces use): 17 significant digits, trailing zeros dropped,
 * exponent form below 1e-4 and from 1e17. Exact halfway cases round to even as C does
 * (toExponential would round them up).
 */
export function numberText(x: number): string {
  if (!Number.isFinite(x))
    throw new RangeError(`number must be finite to be written as JSON (got ${x})`);
  if (x === 0) return Object.is(x, -0) ? "-0" : "0";
  let s = Math.abs(x).toExponential(16);
  const s18 = Math.abs(x).toExponential(17);
  const m18 = s18.slice(0, s18.indexOf("e")).replace(".", "");
  const e18 = Number(s18.slice(s18.indexOf("e") + 1));
  if (m18.endsWith("5") && exactly(x, BigInt(m18), e18 - 17)) {
    const kept = m18.slice(0, 17);
    if (Number(kept[16]) % 2 === 0) s = `${kept[0]}.${kept.slice(1)}e${e18 >= 0 ? "+" : ""}${e18}`;
  }
  const cut = s.indexOf("e");
  const digits = s.slice(0, cut).replace(".", "");
  const exp = Number(s.slice(cut + 1));
  const sign = x < 0 ? "-" : "";
  if (exp < -4 || exp >= 17) {
    const mant = (digits[0] + "." + digits.slice(1)).replace(/\.?0+$/, "");
    const e = String(Math.abs(exp)).padStart(2, "0");
    return `${sign}${mant}e${exp < 0 ? "-" : "+"}${e}`;
  }
  let whole: string;
  let frac: string;
  if (exp >= 0) {
    whole = digits.slice(0, exp + 1);
    frac = digits.slice(exp + 1);
  } else {
    whole = "0";
    frac = "0".repeat(-exp - 1) + digits;
  }
  frac = frac.replace(/0+$/, "");
  return sign + whole + (frac ? "." + frac : "");
}

function isScalar(v: unknown): boolean {
  return typeof v !== "object" || v === null;
}

/** Canonical JSON: arrays of scalars on one line, objects and nested arrays one item a line. */
export function jsonText(value: unknown, indent = 0): string {
  const pad = " ".repeat(indent + 2);
  if (typeof value === "boolean") return value ? "true" : "false";
  if (value === null) return "null";
  if (typeof value === "number") return numberText(value);
  if (typeof value === "string") return JSON.stringify(value);
  if (Array.isArray(value) || ArrayBuffer.isView(value)) {
    const seq = Array.from(value as ArrayLike<unknown>);
    if (seq.every(isScalar)) return "[" + seq.map((e) => jsonText(e)).join(", ") + "]";
    return (
      "[\n" +
      seq.map((e) => pad + jsonText(e, indent + 2)).join(",\n") +
      "\n" +
      " ".repeat(indent) +
      "]"
    );
  }
  if (typeof value === "object") {
    const entries = Object.entries(value as Record<string, unknown>);
    if (entries.length === 0) return "{}";
    const items = entries.map(([k, v]) => `${pad}${JSON.stringify(k)}: ${jsonText(v, indent + 2)}`);
    return "{\n" + items.join(",\n") + "\n" + " ".repeat(indent) + "}";
  }
  throw new TypeError(`cannot write ${typeof value} as JSON`);
}

export function traceText(trace: Trace): string {
  return jsonText(trace) + "\n";
}

/** The state as JSON text, exactly as Python's state_text writes it. */
export function stateText(sim: Simulation): string {
  return jsonText(sim.toState()) + "\n";
}

// -- running -------------------------------------------------------------------------------
/** Load state with event recording, then set each step's height and advance its dt. */
export function runSteps(
  state: StateInput | SimulationState,
  steps: readonly PackedStep[],
): Simulation {
  const sim = Simulation.fromState(state, { recordEvents: true });
  for (const [dt, height, count] of steps) {
    for (let k = 0; k < count; k++) {
      sim.trapHeight = height;
      sim.advance(dt);
    }
  }
  return sim;
}

function pack(steps: Array<[number, number]>): PackedStep[] {
  const out: PackedStep[] = [];
  for (const [dt, h] of steps) {
    const last = out[out.length - 1];
    if (last && last[0] === dt && last[1] === h) last[2]++;
    else out.push([dt, h, 1]);
  }
  return out;
}

/** The smallest double above x (x finite, >= 0). */
function nextUp(x: number): number {
  if (x === 0) return Number.MIN_VALUE;
  const view = new DataView(new ArrayBuffer(8));
  view.setFloat64(0, x);
  view.setBigUint64(0, view.getBigUint64(0) + 1n);
  return view.getFloat64(0);
}

/** Whole frames, then a last step that ends at the time of the n-th event (as Python plans). */
export function planSteps(
  state: StateInput | SimulationState,
  nEvents: number,
  heightOfFrame?: (k: number) => number,
): PackedStep[] {
  const sim = Simulation.fromState(state, { recordEvents: true });
  const steps: Array<[number, number]> = [];
  for (let k = 0; k < MAX_FRAMES; k++) {
    const height = heightOfFrame ? heightOfFrame(k) : sim.trapHeight;
    sim.trapHeight = height;
    const before = sim.time;
    if (sim.eventCount >= nEvents) {
      steps.push([0, height]);
      break;
    }
    sim.advance(1);
    if (sim.eventCount < nEvents) {
      steps.push([1, height]);
      continue;
    }
    const tN = sim.eventAt(nEvents - 1).time;
    let dt = tN - before;
    while (before + dt < tN) dt = nextUp(dt);
    steps.push([dt, height]);
    break;
  }
  return pack(steps);
}

/** The run's figures at its end, as Python's trace summary names them. */
export function summaryOf(sim: Simulation) {
  return {
    n_trapped: sim.nTrapped,
    n_escaped: sim.nEscaped,
    temperature: sim.temperature,
    total_energy: sim.totalEnergy(),
    critical_temperature: sim.criticalTemperature,
    won: sim.won,
    pair_collisions: sim.pairCollisionCount,
    wall_collisions: sim.wallCollisionCount,
  };
}

/** What a run of this engine gave: its events, its state at the end, its summary. */
function outcome(sim: Simulation): Pick<Trace, "events" | "end" | "summary"> {
  const events = sim.eventLog.map((e): TraceEvent => [e.kind, e.i, e.j, e.time]);
  return { events, end: sim.toState(), summary: summaryOf(sim) };
}

/** The trace of this engine from state over the schedule that reaches nEvents. */
export function makeTrace(
  name: string,
  description: string,
  state: StateInput | SimulationState,
  nEvents: number,
  heightOfFrame?: (k: number) => number,
): Trace {
  const steps = planSteps(state, nEvents, heightOfFrame);
  return {
    format: TRACE_FORMAT,
    version: TRACE_VERSION,
    case: name,
    description,
    events_requested: nEvents,
    start: state,
    steps,
    ...outcome(runSteps(state, steps)),
  };
}

/** The trace this engine produces from trace's start and steps (the same, if it agrees). */
export function replayTrace(trace: Trace): Trace {
  return { ...trace, ...outcome(runSteps(trace.start, trace.steps)) };
}

/** Parse a trace's text; numbers read back to the same bits (JSON.parse keeps -0). */
export function readTrace(text: string): Trace {
  const t = JSON.parse(text) as Trace;
  if (typeof t !== "object" || t === null || t.format !== TRACE_FORMAT)
    throw new RangeError(`trace must be a JSON object with format "${TRACE_FORMAT}"`);
  return t;
}
