/**
 * The WebAssembly engine core (web/wasm/*.c, compiled by clang for wasm32 and inlined by the
 * build as base64): the same events as engine.ts's Engine, bit for bit, behind the same
 * interface, so `Simulation` runs on either (`setEngineCore`).
 *
 * One WebAssembly instance per engine: its memory holds that engine's tables, allocated once.
 * Validation stays in front of it (Simulation, state.ts): the core is handed sound states.
 */
import packedCore from "virtual:evapcool-wasm";
import type { Engine, EngineAtoms, EngineSetup } from "./engine";
import { power } from "./portable";

/** What Simulation uses of an engine (engine.ts's Engine or WasmEngine). */
export type EngineCore = Pick<
  Engine,
  | "nAtoms"
  | "gravity"
  | "curvature"
  | "knife"
  | "winRule"
  | "tcExponent"
  | "time"
  | "trapHeight"
  | "xRim"
  | "won"
  | "nTrapped"
  | "pairCount"
  | "wallCount"
  | "energySum"
  | "initialTemperature"
  | "nLog"
  | "crossingCount"
  | "staleCount"
  | "gridColumns"
  | "gridRows"
  | "cellSize"
  | "sequentialEnergySum"
  | "logEntry"
  | "criticalTemperatureOf"
  | "advanceTo"
  | "setTrapHeight"
  | "forceWin"
  | "statusOf"
  | "storedOf"
  | "atomEnergy"
  | "stateAt"
  | "gridErrors"
>;

/** The C entry points (driver.c, tables.c, grid.c). */
interface CoreExports {
  memory: WebAssembly.Memory;
  allocate(n: number, logCapacity: number): number;
  load(
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
  start(energySum: number, trapHeight: number): number;
  advance_to(tEnd: number): number;
  set_trap_height(height: number): void;
  force_win(): void;
  status_of(i: number): number;
  stored_of(i: number, k: number): number;
  atom_energy(i: number): number;
  state_at(i: number, t: number): number;
  sequential_energy_sum(): number;
  grid_errors(): number;
  tc_table_address(): number;
  log_address(): number;
  log_clear(): void;
  time(): number;
  energy_sum(): number;
  x_rim(): number;
  trap_height(): number;
  won(): number;
  n_trapped(): number;
  pairs(): number;
  walls(): number;
  crossings(): number;
  stale(): number;
  renumbered(): number;
  n_log(): number;
  nx(): number;
  ny(): number;
  cell(): number;
}

/** advance_to's answer when the log buffer must be emptied before it goes on. */
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

/** Whether this page or worker has the WebAssembly core (else engine.ts's Engine plays). */
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

/** The atoms' columns where allocate() placed the inputs: 7 columns of doubles, then status. */
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
  private readonly core: CoreExports;
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
    const core = instance.exports as unknown as CoreExports;
    this.core = core;
    const logCapacity = setup.recordEvents ? Math.max(LOG_BUFFER, n + 8) : 0;
    const inputs = core.allocate(n, logCapacity);
    if (inputs === 0) throw new RangeError(OUT_OF_MEMORY(n));
    writeInputs(core.memory.buffer, inputs, atoms);
    core.load(
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
    const energySum = atoms.energySum ?? core.sequential_energy_sum();
    const nTrapped = core.n_trapped();
    this.initialTemperature = atoms.initialTemperature ?? (nTrapped > 0 ? energySum / nTrapped : 0);
    // seed Eq. (46): Tc0 is 3/4 of the starting temperature; the core reads Tc(N) from a table.
    this.tc0 = 0.75 * this.initialTemperature;
    const table = new Float64Array(core.memory.buffer, core.tc_table_address(), n + 1);
    for (let k = 0; k <= n; k++) table[k] = this.criticalTemperatureOf(k);
    if (!core.start(energySum, setup.trapHeight)) throw new RangeError(OUT_OF_MEMORY(n));
    this.gridColumns = core.nx();
    this.gridRows = core.ny();
    this.cellSize = core.cell();
    this.mem = new Float64Array(core.memory.buffer);
  }

  get time(): number {
    return this.core.time();
  }
  get trapHeight(): number {
    return this.core.trap_height();
  }
  get xRim(): number {
    return this.core.x_rim();
  }
  get won(): boolean {
    return this.core.won() !== 0;
  }
  get nTrapped(): number {
    return this.core.n_trapped();
  }
  get pairCount(): number {
    return this.core.pairs();
  }
  get wallCount(): number {
    return this.core.walls();
  }
  get energySum(): number {
    return this.core.energy_sum();
  }
  get crossingCount(): number {
    return this.core.crossings();
  }
  get staleCount(): number {
    return this.core.stale();
  }
  get renumberCount(): number {
    return this.core.renumbered();
  }

  /** Process every event with time <= tEnd in time order, then set the clock. */
  advanceTo(tEnd: number): void {
    while (this.core.advance_to(tEnd) === LOG_FULL) this.drainLog();
    this.drainLog();
  }

  /** New rim height; with the knife rule, atoms above m g H go at once, in index order. */
  setTrapHeight(height: number): void {
    this.drainLog(); // the knife may log every atom: the buffer holds n + 8 lines
    this.core.set_trap_height(height);
    this.drainLog();
  }

  forceWin(): void {
    this.core.force_win();
  }

  /** Tc(N) = Tc0 (N / N0)^p, seed Eq. (46) with exponent p. */
  criticalTemperatureOf(nTrapped: number): number {
    return this.tc0 * power(nTrapped / this.nAtoms, this.tcExponent);
  }

  sequentialEnergySum(): number {
    return this.core.sequential_energy_sum();
  }

  statusOf(i: number): number {
    return this.core.status_of(i);
  }

  /** Stored value k of world atom i: 0 x, 1 y, 2 vx, 3 vy, 4 t, 5 radius, 6 mass. */
  storedOf(i: number, k: number): number {
    return this.core.stored_of(i, k);
  }

  atomEnergy(i: number): number {
    return this.core.atom_energy(i);
  }

  /** Position and velocity of world atom i carried to time t into out = [x, y, vx, vy]. */
  stateAt(i: number, t: number, out: Float64Array): void {
    const at = this.core.state_at(i, t) >> 3;
    let mem = this.mem;
    if (mem.buffer !== this.core.memory.buffer)
      mem = this.mem = new Float64Array(this.core.memory.buffer);
    out[0] = mem[at];
    out[1] = mem[at + 1];
    out[2] = mem[at + 2];
    out[3] = mem[at + 3];
  }

  gridErrors(): number {
    return this.core.grid_errors();
  }

  /** Event k of the log: [kind, i, j, time] with world indices. */
  logEntry(k: number): [number, number, number, number] {
    return [this.logKind[k], this.logI[k], this.logJ[k], this.logT[k]];
  }

  /** Copy the core's log lines into the log here and empty its buffer. */
  private drainLog(): void {
    const lines = this.core.n_log();
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
    const buffer = this.core.memory.buffer;
    const base = this.core.log_address();
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
    this.core.log_clear();
  }
}
