/**
 * The engine: the one physics core (core/*.c at the top of the repository, the same C the
 * Python package builds natively), compiled by clang for wasm32 and inlined by the build as
 * base64 (scripts/wasm-plugin.mjs). It processes the events of Python's ReferenceEngine in
 * the same order with the same arithmetic, so the golden traces replay bit for bit.
 *
 * One WebAssembly instance per engine, holding one `Core` (core_new): its memory holds that
 * engine's tables, allocated once. Validation stays in front of it (Simulation, state.ts):
 * the core is handed sound states.
 */
import packedCore from "virtual:evapcool-wasm";
import { power } from "./portable";

/** Everything an engine needs besides the atoms. */
export interface EngineSetup {
  curvature: number;
  gravity: number;
  trapHeight: number;
  /** Window edges in trap coordinates (an escaped atom is gone beyond them). */
  xLeft: number;
  xRight: number;
  yBottom: number;
  tcExponent: number;
  knife: boolean;
  winRule: boolean;
  recordEvents: boolean;
}

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

/** What Simulation uses of an engine. */
export interface EngineCore {
  // fixed for the engine's life
  /** Atoms at the start (N0), gone ones included. */
  readonly nAtoms: number;
  readonly gravity: number;
  readonly curvature: number;
  readonly knife: boolean;
  readonly winRule: boolean;
  readonly tcExponent: number;
  readonly initialTemperature: number;
  /** The cell grid's columns, rows and cell edge. */
  readonly gridColumns: number;
  readonly gridRows: number;
  readonly cellSize: number;
  // the running state
  readonly time: number;
  readonly trapHeight: number;
  readonly xRim: number;
  readonly won: boolean;
  readonly nTrapped: number;
  readonly pairCount: number;
  readonly wallCount: number;
  readonly energySum: number;
  readonly nLog: number;
  readonly crossingCount: number;
  readonly staleCount: number;
  /** Process every event with time <= tEnd in time order, then set the clock. */
  advanceTo(tEnd: number): void;
  /** New rim height, at once; with the knife rule, atoms above m g H go now, in index order. */
  setTrapHeight(height: number): void;
  /** Declare the gas condensed now (demonstrations and tests). */
  forceWin(): void;
  /** Tc(N) = Tc0 (N / N0)^p, seed Eq. (46) with exponent p. */
  criticalTemperatureOf(nTrapped: number): number;
  /** Sum of trapped energies added in world index order (the engines continue it). */
  sequentialEnergySum(): number;
  statusOf(i: number): number;
  /** Stored value k (STORED) of world atom i. */
  storedOf(i: number, k: number): number;
  /** World atom i's energy 1/2 m v^2 + m g y from its stored state (conserved in flight). */
  atomEnergy(i: number): number;
  /** Position and velocity of world atom i carried to time t into out = [x, y, vx, vy]. */
  stateAt(i: number, t: number, out: Float64Array): void;
  /** Trapped atoms filed more than one cell away from their cell now (0 if sound). */
  gridErrors(): number;
  /** Event k of the log: [kind, i, j, time] with world indices. */
  logEntry(k: number): [number, number, number, number];
}

/** A Core's address in the instance's memory (core/tables.h). */
type Core = number;

/** The C entry points (core/driver.c, tables.c, grid.c, memory.c): a Core first. */
interface CoreExports {
  memory: WebAssembly.Memory;
  core_new(): Core;
  core_allocate(core: Core, n: number, logCapacity: number): number;
  core_load(
    core: Core,
    inputs: number,
    gravity: number,
    curvature: number,
    xLeft: number,
    xRight: number,
    yBottom: number,
    knife: number,
    winRule: number,
    record: number,
    time: number,
    won: number,
    pairs: number,
    walls: number,
  ): void;
  core_start(core: Core, energySum: number, trapHeight: number): number;
  core_advance_to(core: Core, tEnd: number): number;
  core_set_trap_height(core: Core, height: number): void;
  core_force_win(core: Core): void;
  core_status_of(core: Core, i: number): number;
  core_stored_of(core: Core, i: number, k: number): number;
  core_atom_energy(core: Core, i: number): number;
  core_state_at(core: Core, i: number, t: number): number;
  core_sequential_energy_sum(core: Core): number;
  core_grid_errors(core: Core): number;
  core_tc_table_address(core: Core): number;
  core_log_address(core: Core): number;
  core_log_clear(core: Core): void;
  core_time(core: Core): number;
  core_energy_sum(core: Core): number;
  core_x_rim(core: Core): number;
  core_trap_height(core: Core): number;
  core_won(core: Core): number;
  core_n_trapped(core: Core): number;
  core_pairs(core: Core): number;
  core_walls(core: Core): number;
  core_crossings(core: Core): number;
  core_stale(core: Core): number;
  core_renumbered(core: Core): number;
  core_n_log(core: Core): number;
  core_nx(core: Core): number;
  core_ny(core: Core): number;
  core_cell(core: Core): number;
}

/** core_advance_to's answer (CORE_LOG_FULL) when the log must be emptied before it goes on. */
const LOG_FULL = 1;
/** A log line in C: kind, a, b, padding (int32 each), then the time (double). */
const LOG_LINE_BYTES = 24;
/** Log lines the core buffers between two copies (at least the atom count + 8). */
const LOG_BUFFER = 4096;

/** The WebAssembly memory (at most 4 GB) could not hold the engine's tables. */
const OUT_OF_MEMORY = (n: number) =>
  `nAtoms must fit the engine core's memory (${n} atoms did not: not enough memory)`;

let compiled: WebAssembly.Module | null = null;
/** The core's bytes handed over by the page (the worker's bundle carries none of its own). */
let given: Uint8Array<ArrayBuffer> | null = null;

/** The core's bytes: the page's own, or those handed over (empty if neither). */
export function coreBytes(): Uint8Array<ArrayBuffer> {
  return given ?? packedCore;
}

/** Whether this page or worker has the WebAssembly core (the page cannot start without). */
export function haveCore(): boolean {
  return coreBytes().length > 0;
}

/** The physics worker gets the core from the page: one copy in the page's file, not two. */
export function provideCore(bytes: Uint8Array<ArrayBuffer>): void {
  given = bytes;
}

/** The core's compiled module (compiled once, synchronously, on first use). */
function coreModule(): WebAssembly.Module {
  if (compiled === null) {
    const bytes = coreBytes();
    if (bytes.length === 0) throw new Error("the engine core was not handed to this worker");
    compiled = new WebAssembly.Module(bytes);
  }
  return compiled;
}

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

export class WasmEngine implements EngineCore {
  readonly nAtoms: number;
  readonly gravity: number;
  readonly curvature: number;
  readonly knife: boolean;
  readonly winRule: boolean;
  readonly tcExponent: number;
  readonly recordEvents: boolean;
  readonly initialTemperature: number;
  readonly tc0: number;
  readonly gridColumns: number;
  readonly gridRows: number;
  readonly cellSize: number;
  /** The instance's entry points. */
  private readonly c: CoreExports;
  /** This engine's Core in the instance's memory: every entry point's first argument. */
  private readonly core: Core;
  /** The core's memory as doubles (a new view if the memory grew). */
  private mem: Float64Array;
  // The event log, copied out of the core's buffer (world indices).
  private logKind = new Uint8Array(0);
  private logI = new Int32Array(0);
  private logJ = new Int32Array(0);
  private logT = new Float64Array(0);
  nLog = 0;

  constructor(setup: EngineSetup, atoms: EngineAtoms) {
    const n = atoms.x.length;
    this.nAtoms = n;
    this.gravity = setup.gravity;
    this.curvature = setup.curvature;
    this.knife = setup.knife;
    this.winRule = setup.winRule;
    this.tcExponent = setup.tcExponent;
    this.recordEvents = setup.recordEvents;
    const instance = new WebAssembly.Instance(coreModule(), {});
    const c = instance.exports as unknown as CoreExports;
    this.c = c;
    const core = c.core_new();
    if (core === 0) throw new RangeError(OUT_OF_MEMORY(n));
    this.core = core;
    const logCapacity = setup.recordEvents ? Math.max(LOG_BUFFER, n + 8) : 0;
    const inputs = c.core_allocate(core, n, logCapacity);
    if (inputs === 0) throw new RangeError(OUT_OF_MEMORY(n));
    writeInputs(c.memory.buffer, inputs, atoms);
    c.core_load(
      core,
      inputs,
      setup.gravity,
      setup.curvature,
      setup.xLeft,
      setup.xRight,
      setup.yBottom,
      setup.knife ? 1 : 0,
      setup.winRule ? 1 : 0,
      setup.recordEvents ? 1 : 0,
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
    const table = new Float64Array(c.memory.buffer, c.core_tc_table_address(core), n + 1);
    for (let k = 0; k <= n; k++) table[k] = this.criticalTemperatureOf(k);
    if (!c.core_start(core, energySum, setup.trapHeight)) throw new RangeError(OUT_OF_MEMORY(n));
    this.gridColumns = c.core_nx(core);
    this.gridRows = c.core_ny(core);
    this.cellSize = c.core_cell(core);
    this.mem = new Float64Array(c.memory.buffer);
  }

  get time(): number {
    return this.c.core_time(this.core);
  }
  get trapHeight(): number {
    return this.c.core_trap_height(this.core);
  }
  get xRim(): number {
    return this.c.core_x_rim(this.core);
  }
  get won(): boolean {
    return this.c.core_won(this.core) !== 0;
  }
  get nTrapped(): number {
    return this.c.core_n_trapped(this.core);
  }
  get pairCount(): number {
    return this.c.core_pairs(this.core);
  }
  get wallCount(): number {
    return this.c.core_walls(this.core);
  }
  get energySum(): number {
    return this.c.core_energy_sum(this.core);
  }
  get crossingCount(): number {
    return this.c.core_crossings(this.core);
  }
  get staleCount(): number {
    return this.c.core_stale(this.core);
  }
  get renumberCount(): number {
    return this.c.core_renumbered(this.core);
  }

  advanceTo(tEnd: number): void {
    while (this.c.core_advance_to(this.core, tEnd) === LOG_FULL) this.drainLog();
    this.drainLog();
  }

  setTrapHeight(height: number): void {
    this.drainLog(); // the knife may log every atom: the buffer holds n + 8 lines
    this.c.core_set_trap_height(this.core, height);
    this.drainLog();
  }

  forceWin(): void {
    this.c.core_force_win(this.core);
  }

  criticalTemperatureOf(nTrapped: number): number {
    return this.tc0 * power(nTrapped / this.nAtoms, this.tcExponent);
  }

  sequentialEnergySum(): number {
    return this.c.core_sequential_energy_sum(this.core);
  }

  statusOf(i: number): number {
    return this.c.core_status_of(this.core, i);
  }

  storedOf(i: number, k: number): number {
    return this.c.core_stored_of(this.core, i, k);
  }

  atomEnergy(i: number): number {
    return this.c.core_atom_energy(this.core, i);
  }

  stateAt(i: number, t: number, out: Float64Array): void {
    const at = this.c.core_state_at(this.core, i, t) >> 3;
    let mem = this.mem;
    if (mem.buffer !== this.c.memory.buffer)
      mem = this.mem = new Float64Array(this.c.memory.buffer);
    out[0] = mem[at];
    out[1] = mem[at + 1];
    out[2] = mem[at + 2];
    out[3] = mem[at + 3];
  }

  gridErrors(): number {
    return this.c.core_grid_errors(this.core);
  }

  logEntry(k: number): [number, number, number, number] {
    return [this.logKind[k], this.logI[k], this.logJ[k], this.logT[k]];
  }

  /** Copy the core's log lines into the log here and empty its buffer. */
  private drainLog(): void {
    const lines = this.c.core_n_log(this.core);
    if (lines === 0) return;
    const need = this.nLog + lines;
    if (need > this.logT.length) {
      const cap = Math.max(1024, 2 * need);
      const grow = <A extends Uint8Array | Int32Array | Float64Array>(old: A, fresh: A): A => {
        fresh.set(old);
        return fresh;
      };
      this.logKind = grow(this.logKind, new Uint8Array(cap));
      this.logI = grow(this.logI, new Int32Array(cap));
      this.logJ = grow(this.logJ, new Int32Array(cap));
      this.logT = grow(this.logT, new Float64Array(cap));
    }
    const buffer = this.c.memory.buffer;
    const base = this.c.core_log_address(this.core);
    const ints = new Int32Array(buffer, base, (lines * LOG_LINE_BYTES) >> 2);
    const times = new Float64Array(buffer, base, (lines * LOG_LINE_BYTES) >> 3);
    for (let k = 0; k < lines; k++) {
      const q = this.nLog + k;
      this.logKind[q] = ints[6 * k];
      this.logI[q] = ints[6 * k + 1];
      this.logJ[q] = ints[6 * k + 2];
      this.logT[q] = times[3 * k + 2];
    }
    this.nLog = need;
    this.c.core_log_clear(this.core);
  }
}
