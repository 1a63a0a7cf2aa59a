/**
 * The engine: the one physics core (core/*.c at the top of the repository, the same C the
 * Python package builds natively), compiled by clang for wasm32 and inlined by the build
 * packed (deflate, base 85: scripts/wasm-plugin.mjs). It processes the events of Python's ReferenceEngine in
 * the same order with the same arithmetic, so the golden traces replay bit for bit.
 *
 * One WebAssembly instance per engine (instance.ts), holding one `Core` (core_new): its memory
 * holds that engine's tables, allocated once. Its exports' types (core-exports.ts) are generated from the
 * core's header, core/evapcool_core.h, as Python's binding is. Validation stays in front of it (Simulation, state.ts):
 * the core is handed sound states.
 */
import { instance, OUT_OF_MEMORY } from "./instance";
import { escapeBox, type Room } from "./room";
import type { Core, CoreExports } from "./core-exports";
import type { EscapeRule } from "./constants";
import {
  CORE_DONE,
  CORE_FRAME_END,
  CORE_LOG_FULL,
  CORE_LOG_LINE_BYTES,
  CORE_MOVES_FULL,
} from "./model";

/** Everything an engine needs besides the atoms: a checked config's rules (config.ts's
 * SimulationConfig, whose checks call the core: named here, not imported), or a state's. */
export type EngineRules = { readonly room: Room; readonly escape: EscapeRule } & Readonly<
  Record<"curvature" | "gravity" | "tcExponent" | "trapHeight", number> &
    Record<"win" | "recordEvents", boolean>
>;

/** Atoms and the clock; for a fresh start t = 0, status trapped and the sums are computed. */
export interface EngineAtoms {
  x: ArrayLike<number>;
  y: ArrayLike<number>;
  vx: ArrayLike<number>;
  vy: ArrayLike<number>;
  t: ArrayLike<number>;
  radius: ArrayLike<number>;
  mass: ArrayLike<number>;
  status: ArrayLike<number>;
  time: number;
  /** Running sum of trapped energies; computed in index order if absent. */
  energySum?: number;
  /** T at the start (Tc0 = 0.75 of it); the current temperature if absent. */
  initialTemperature?: number;
  won: boolean;
  pairCount: number;
  wallCount: number;
}

/** What storedOf(i, k) returns for each k: the core's State fields in order, then the mass. */
export const STORED = { x: 0, y: 1, vx: 2, vy: 3, t: 4, radius: 5, mass: 6 } as const;

/** Entry points called with a Core alone that answer a number: its scalars (core/tables.c) among them. */
type Reader = {
  [K in keyof CoreExports]: CoreExports[K] extends (core: Core) => number ? K : never;
}[keyof CoreExports];

/** Log lines the core buffers between two copies (at least the atom count + 8). */
const LOG_BUFFER = 4096;

/** The atoms' columns where core_allocate placed the inputs: 7 columns of doubles, then status. */
function writeInputs(buffer: ArrayBuffer, at: number, atoms: EngineAtoms): void {
  const n = atoms.x.length;
  const f64 = new Float64Array(buffer, at, 7 * n);
  const columns = [atoms.x, atoms.y, atoms.vx, atoms.vy, atoms.t, atoms.radius, atoms.mass];
  columns.forEach((column, k) => {
    for (let i = 0; i < n; i++) f64[k * n + i] = column[i];
  });
  const status = new Int32Array(buffer, at + 8 * 7 * n, n);
  for (let i = 0; i < n; i++) status[i] = atoms.status[i];
}

/** One engine: a Core in an instance of its own, loaded with the atoms and started. */
export class WasmEngine {
  /** Atoms at the start (N0), gone ones included. */
  readonly nAtoms: number;
  /** T at the start (Tc0 = 0.75 of it). */
  readonly initialTemperature: number;
  readonly tc0: number;
  /** The instance's entry points. */
  private readonly c: CoreExports;
  /** This engine's Core in the instance's memory: every entry point's first argument. */
  private readonly core: Core;
  /** Where core_snapshot writes (taken at the first snapshot, 0 before), and its view (a new
   * one only if the memory grew). */
  private snapAt = 0;
  private snapView = new Float64Array(0);
  /** The event log, copied out of the core's buffer: [kind, i, j, time], world indices. */
  private readonly log: Array<[number, number, number, number]> = [];
  /** The moves taken from the core's buffer when it was full. */
  private readonly taken: Array<[number, number]> = [];

  /** The rules it runs, kept apart from whatever else the caller's object holds. */
  readonly rules: EngineRules;

  constructor(given: EngineRules, atoms: EngineAtoms) {
    const { room, curvature, gravity, tcExponent, escape, win, trapHeight, recordEvents } = given;
    this.rules = { room, curvature, gravity, tcExponent, escape, win, trapHeight, recordEvents };
    const n = atoms.x.length;
    this.nAtoms = n;
    const c = instance();
    this.c = c;
    const core = c.core_new();
    if (core === 0) throw new RangeError(OUT_OF_MEMORY(n));
    this.core = core;
    const logCapacity = recordEvents ? Math.max(LOG_BUFFER, n + 8) : 0;
    const inputs = c.core_allocate(core, n, logCapacity);
    if (inputs === 0) throw new RangeError(OUT_OF_MEMORY(n));
    writeInputs(c.memory.buffer, inputs, atoms);
    // Escaped atoms are gone beyond the room's edges; the trap origin lies the first atom's
    // radius above the wall's lowest point.
    const [xLeft, xRight, yBottom] = escapeBox(room, atoms.radius[0]);
    c.core_load(
      core,
      inputs,
      gravity,
      curvature,
      xLeft,
      xRight,
      yBottom,
      escape === "knife" ? 1 : 0,
      win ? 1 : 0,
      recordEvents ? 1 : 0,
      atoms.time,
      atoms.won ? 1 : 0,
      atoms.pairCount,
      atoms.wallCount,
    );
    const energySum = atoms.energySum ?? c.core_sequential_energy_sum(core);
    const nTrapped = c.core_n_trapped(core);
    this.initialTemperature = atoms.initialTemperature ?? (nTrapped > 0 ? energySum / nTrapped : 0);
    // seed Eq. (46): Tc0 is 3/4 of the starting temperature; the core reads Tc(N) from a table.
    this.tc0 = 0.75 * this.initialTemperature;
    c.core_fill_tc_table(core, this.tc0, tcExponent);
    if (!c.core_start(core, energySum, trapHeight)) throw new RangeError(OUT_OF_MEMORY(n));
  }

  /** What entry point `name` answers now: a scalar such as the clock, the trap, a count, the
   * grid's shape or errors, a sum of energies. */
  read(name: Reader): number {
    return this.c[name](this.core);
  }

  /** Process every event with time <= tEnd in time order, then set the clock. */
  advanceTo(tEnd: number): void {
    while (this.c.core_advance_to(this.core, tEnd) === CORE_LOG_FULL) this.drainLog();
    this.drainLog();
  }

  /** New rim height, at once; with the knife rule, atoms above m g H go now, in index order. */
  setTrapHeight(height: number): void {
    this.drainLog(); // the knife may log every atom: the buffer holds n + 8 lines
    this.c.core_set_trap_height(this.core, height);
    this.drainLog();
  }

  /** Declare the gas condensed now (demonstrations and tests). */
  forceWin(): void {
    this.c.core_force_win(this.core);
  }

  /** Play to `end` frames (core/play.c); onFrame(height held) after each recorded frame. */
  playTo(end: number, onFrame: ((height: number) => void) | null): void {
    for (;;) {
      const code = this.c.core_play_to(this.core, end, onFrame ? 1 : 0);
      this.drainLog();
      if (code === CORE_DONE) return;
      if (code === CORE_MOVES_FULL) this.takeMoves();
      else if (code === CORE_FRAME_END) onFrame?.(this.read("core_trap_height"));
    }
  }

  /** A rim height from the next whole frame (at once if `now` or on one), or refused. */
  askHeight(height: number, now: boolean): boolean {
    const asked = this.c.core_ask_height(this.core, height, now ? 1 : 0) === 1;
    this.drainLog();
    return asked;
  }

  /** Hold these [height, frames] runs' heights, counted from the start (none: stop). */
  hold(runs: ReadonlyArray<readonly [number, number]>): void {
    if (!this.c.core_hold(this.core, runs.length)) throw new RangeError(OUT_OF_MEMORY(this.nAtoms));
    for (const [height, frames] of runs) this.c.core_hold_run(this.core, height, frames);
    this.drainLog();
  }

  /** The [height, frames] runs held so far, up to the win. */
  moves(): Array<[number, number]> {
    return [...this.taken, ...this.keptMoves()];
  }

  /** The core's buffer of moves was full: keep them here, empty it. */
  private takeMoves(): void {
    this.taken.push(...this.keptMoves());
    this.c.core_moves_taken(this.core);
  }

  private keptMoves(): Array<[number, number]> {
    const kept: Array<[number, number]> = [];
    for (let k = 0; k < this.c.core_n_moves(this.core); k++)
      kept.push([this.c.core_move_height(this.core, k), this.c.core_move_frames(this.core, k)]);
    return kept;
  }

  /** [height, frames] runs from a whole frame, up to the win or `limit` frames: the frames
   * played (no event log is kept). */
  replay(runs: ReadonlyArray<readonly [number, number]>, limit: number): number {
    const at = this.c.core_buffer(this.core, 2 * runs.length);
    if (at === 0 && runs.length > 0) throw new RangeError(OUT_OF_MEMORY(this.nAtoms));
    const buffer = new Float64Array(this.c.memory.buffer, at, 2 * runs.length);
    runs.forEach(([height, frames], k) => buffer.set([height, frames], 2 * k));
    return this.c.core_replay(this.core, at, runs.length, limit);
  }

  /** A recording's path in the (N, T) plane (core_path, Python's game/path.py sampling): the
   * runs played as `replay` plays them; rows [k, N, T, h] kept at frame 0 (height h0), every
   * stride-th whole frame, the last and the win's, T unrounded. */
  path(
    runs: ReadonlyArray<readonly [number, number]>,
    limit: number,
    stride: number,
    h0: number,
  ): { frames: number; rows: Array<[number, number, number, number]> } {
    const most = Math.floor(limit / stride) + 2;
    const at = this.c.core_buffer(this.core, 2 * runs.length + 4 * most + 1);
    if (at === 0) throw new RangeError(OUT_OF_MEMORY(this.nAtoms));
    const input = new Float64Array(this.c.memory.buffer, at, 2 * runs.length);
    runs.forEach(([height, frames], k) => input.set([height, frames], 2 * k));
    const points = at + 16 * runs.length;
    const count = points + 32 * most;
    const frames = this.c.core_path(this.core, at, runs.length, limit, stride, h0, points, count);
    const kept = new Int32Array(this.c.memory.buffer, count, 1)[0]; // views after: memory may grow
    const flat = new Float64Array(this.c.memory.buffer, points, 4 * kept);
    const rows: Array<[number, number, number, number]> = [];
    for (let r = 0; r < kept; r++)
      rows.push([flat[4 * r], flat[4 * r + 1], flat[4 * r + 2], flat[4 * r + 3]]);
    return { frames, rows };
  }

  /** Why the gas can no longer condense (core_out_of_reach: REACH_*), or REACH_WITHIN. */
  outOfReach(lowest: number, height: number): number {
    return this.c.core_out_of_reach(this.core, lowest, height);
  }

  /** Tc(N) = Tc0 (N / N0)^p, seed Eq. (46) with exponent p. */
  criticalTemperatureOf(nTrapped: number): number {
    return this.tc0 * this.c.core_power(nTrapped / this.nAtoms, this.rules.tcExponent);
  }

  statusOf(i: number): number {
    return this.c.core_status_of(this.core, i);
  }

  /** Stored value k (STORED) of world atom i. */
  storedOf(i: number, k: number): number {
    return this.c.core_stored_of(this.core, i, k);
  }

  /** World atom i's energy 1/2 m v^2 + m g y from its stored state (conserved in flight). */
  atomEnergy(i: number): number {
    return this.c.core_atom_energy(this.core, i);
  }

  /** The atoms of this status at time t (core_snapshot): their count and eight columns of
   * nAtoms doubles (index, x, y, vx, vy, radius, mass, energy), valid until the next call. */
  columns(status: number, t: number): [number, Float64Array] {
    if (this.snapAt === 0) this.snapAt = this.c.core_buffer(this.core, 8 * this.nAtoms);
    if (this.snapAt === 0) throw new RangeError(OUT_OF_MEMORY(this.nAtoms));
    const count = this.c.core_snapshot(this.core, status, t, this.snapAt);
    if (this.snapView.buffer !== this.c.memory.buffer)
      this.snapView = new Float64Array(this.c.memory.buffer, this.snapAt, 8 * this.nAtoms);
    return [count, this.snapView];
  }

  /** Event k of the log: [kind, i, j, time] with world indices. */
  logEntry(k: number): [number, number, number, number] {
    return this.log[k];
  }

  /** Events recorded so far. */
  get nLog(): number {
    return this.log.length;
  }

  /** Copy the core's log lines into the log here and empty its buffer. */
  private drainLog(): void {
    const lines = this.c.core_n_log(this.core);
    if (lines === 0) return;
    const buffer = this.c.memory.buffer;
    const base = this.c.core_log_address(this.core);
    // A log line: kind, a, b, padding (int32 each), then the time (double).
    const ints = new Int32Array(buffer, base, (lines * CORE_LOG_LINE_BYTES) >> 2);
    const times = new Float64Array(buffer, base, (lines * CORE_LOG_LINE_BYTES) >> 3);
    for (let k = 0; k < lines; k++)
      this.log.push([ints[6 * k], ints[6 * k + 1], ints[6 * k + 2], times[3 * k + 2]]);
    this.c.core_log_clear(this.core);
  }
}
