/**
 * The engine's tables: what it knows about every atom, and its running scalars
 * (src/evapcool/physics/fast/tables.py): a field's offset in its row is TABLE_FIELD, e.g.
 * PLAN_PARTNER_COUNT for PLAN's partner_count (plain constants: offsets as fields of an
 * object cost 6-9% of the collision rate in `npm run bench`, measured).
 *
 * Three typed arrays hold one row per atom each, a row filling cache lines: STATE (the
 * stored state the pair scan reads), PLAN (the pending events and where the atom is) and
 * QUEUED (event times and mass). Row r of every table belongs to the same atom, but not
 * to atom r of the world: the rows are renumbered in cell order now and then
 * (driver.ts), and `atom` holds the world index. Everything that orders events or is seen
 * outside (tie breaks, the log, the knife's ascending order) uses that index, never the
 * row. Everything is allocated once: no allocation per event.
 */
import { TRAPPED } from "./constants";
import { EventQueue } from "./calendar";
import { IO_SIZE, atomEnergy } from "./kernels";

/** STATE, 8 floats a row: the stored state at the atom's own time (both integers exact). */
export const STATE_X = 0; // stored position (trap coordinates, px) ...
export const STATE_Y = 1;
export const STATE_VX = 2; // ... and velocity (px/frame) ...
export const STATE_VY = 3;
export const STATE_T = 4; // ... at this time (frames): the atom's own clock
export const STATE_RADIUS = 5;
export const STATE_COUNT = 6; // events so far: a partner's pair event is stale once it moved on
export const STATE_ATOM = 7; // world index
export const STATE_WIDTH = 8;

/** PLAN, 16 integers a row: the atom's pending events (kinds, key parts, partner), its cell. */
export const PLAN_STATUS = 0; // TRAPPED, ESCAPED or GONE (constants.ts)
export const PLAN_PARTNER_COUNT = 1; // the partner's count when the pair was predicted (low 32 bits)
export const PLAN_CELL_X = 2; // the cell it is filed in (trapped atoms only)
export const PLAN_CELL_Y = 3;
export const PLAN_CELL_PREV = 4; // previous row in that cell, -1 if first
export const PLAN_REAL_KIND = 5; // KIND_PAIR, KIND_WALL, KIND_EXIT or KIND_NONE
export const PLAN_PARTNER = 6; // row of the partner of a pair event
export const PLAN_REAL_RANK = 8; // the real event's key parts (rank, a, b)
export const PLAN_REAL_A = 9;
export const PLAN_REAL_B = 10;
export const PLAN_CROSS_AXIS = 11; // KIND_CROSS_X, KIND_CROSS_Y or KIND_NONE
export const PLAN_CROSS_TO = 12; // cell column (x) or row (y) the crossing enters
export const PLAN_ATOM = 13; // world index
export const PLAN_WIDTH = 16;

/** QUEUED, 4 floats a row: the times an atom's key is chosen from, and its mass. */
export const QUEUED_REAL_T = 0; // time of its real event (pair, wall or exit), Infinity if none
export const QUEUED_CROSS_T = 1; // time of its next cell crossing, Infinity if none
export const QUEUED_ARC_CROSS_T = 2; // last y crossing taken on the current arc (-Infinity: none)
export const QUEUED_MASS = 3;
export const QUEUED_WIDTH = 4;

// Event kinds inside the engine (the log uses constants.ts's EV_*).
export const KIND_NONE = 0;
export const KIND_PAIR = 1;
export const KIND_WALL = 2;
export const KIND_EXIT = 3;
export const KIND_CROSS_X = 4; // into the next column of cells
export const KIND_CROSS_Y = 5; // into the next row of cells

// Ranks order events of equal time: a crossing changes no state and may reveal a partner,
// so it goes first; then solo events by atom index; then pairs by (lower, higher) index.
export const RANK_CROSS = -1;
export const RANK_SOLO = 0;
export const RANK_PAIR = 1;

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

/** The tables and the engine's scalars (Python's RUN record), shared by every room. */
export class Tables {
  // fixed for the engine's life
  readonly n: number;
  readonly gravity: number;
  readonly curvature: number;
  readonly xLeft: number;
  readonly xRight: number;
  readonly yBottom: number;
  readonly knife: boolean;
  readonly winRule: boolean;
  readonly tcExponent: number;
  readonly recordEvents: boolean;
  // the cell grid (grid.ts): edge, shape, left and bottom edges of cell (0, 0)
  cellSize = 0.5;
  nx = 0;
  ny = 0;
  gridX0 = 0.5;
  gridY0 = 0.5;
  nCells = 0;
  /** First row of every cell (row-major), then the next row in the same cell of every row. */
  cells = new Int32Array(0);
  // the tables, their spares for renumbering, and row[i]: the row of world atom i
  state: Float64Array;
  plan: Int32Array;
  queued: Float64Array;
  spareState: Float64Array;
  sparePlan: Int32Array;
  spareQueued: Float64Array;
  readonly order: Int32Array;
  readonly row: Int32Array;
  readonly calendar: EventQueue;
  /** The velocity kernels' in/out buffer (kernels.ts). */
  readonly io = new Float64Array(IO_SIZE);
  // the running state
  time = 0.5;
  trapHeight: number;
  xRim: number;
  won = false;
  nTrapped = 0;
  pairs = 0;
  walls = 0;
  energySum = 0.5;
  initialTemperature = 0.5;
  tc0 = 0.5;
  // engine-only counts
  crossings = 0;
  stale = 0;
  renumbers = 0;
  sinceMaintain = 0;
  /** predict.ts's scratch: the row of cells a y crossing enters. */
  crossYTo = 0;
  // the event log: kind, atom, other atom or -1, time
  logKind = new Uint8Array(0);
  logA = new Int32Array(0);
  logB = new Int32Array(0);
  logT = new Float64Array(0);
  nLog = 0;

  constructor(setup: EngineSetup, n: number) {
    this.n = n;
    this.gravity = setup.gravity;
    this.curvature = setup.curvature;
    this.xLeft = setup.xLeft;
    this.xRight = setup.xRight;
    this.yBottom = setup.yBottom;
    this.knife = setup.knife;
    this.winRule = setup.winRule;
    this.tcExponent = setup.tcExponent;
    this.recordEvents = setup.recordEvents;
    this.trapHeight = setup.trapHeight;
    this.xRim = Math.sqrt(setup.trapHeight / setup.curvature);
    this.state = new Float64Array(STATE_WIDTH * n);
    this.plan = new Int32Array(PLAN_WIDTH * n);
    this.queued = new Float64Array(QUEUED_WIDTH * n);
    this.spareState = new Float64Array(STATE_WIDTH * n);
    this.sparePlan = new Int32Array(PLAN_WIDTH * n);
    this.spareQueued = new Float64Array(QUEUED_WIDTH * n);
    this.order = new Int32Array(n);
    this.row = new Int32Array(n);
    this.calendar = new EventQueue(n);
  }
}

/** Fill the tables with the atoms (row i = world atom i) and the running sums. */
export function loadAtoms(tb: Tables, atoms: EngineAtoms): void {
  const S = tb.state;
  for (let i = 0; i < tb.n; i++) {
    const s = STATE_WIDTH * i;
    const p = PLAN_WIDTH * i;
    const q = QUEUED_WIDTH * i;
    S[s + STATE_X] = atoms.x[i];
    S[s + STATE_Y] = atoms.y[i];
    S[s + STATE_VX] = atoms.vx[i];
    S[s + STATE_VY] = atoms.vy[i];
    S[s + STATE_T] = atoms.t[i];
    S[s + STATE_RADIUS] = atoms.radius[i];
    S[s + STATE_ATOM] = i;
    tb.queued[q + QUEUED_MASS] = atoms.mass[i];
    tb.queued[q + QUEUED_ARC_CROSS_T] = -Infinity;
    tb.plan[p + PLAN_STATUS] = atoms.status[i];
    tb.plan[p + PLAN_ATOM] = i;
    tb.plan[p + PLAN_CELL_PREV] = -1;
    tb.row[i] = i;
    if (atoms.status[i] === TRAPPED) tb.nTrapped++;
  }
  tb.time = atoms.time;
  tb.won = atoms.won;
  tb.pairs = atoms.pairCount;
  tb.walls = atoms.wallCount;
  tb.energySum = atoms.energySum ?? sequentialEnergySum(tb);
  tb.initialTemperature =
    atoms.initialTemperature ?? (tb.nTrapped > 0 ? tb.energySum / tb.nTrapped : 0);
  // seed Eq. (46): Tc0 is 3/4 of the starting temperature.
  tb.tc0 = 0.75 * tb.initialTemperature;
}

/** Energy of row r from its stored state (conserved in flight), seed Eq. (1)'s summand. */
export function rowEnergy(tb: Tables, r: number): number {
  const S = tb.state;
  const s = STATE_WIDTH * r;
  return atomEnergy(
    tb.queued[QUEUED_WIDTH * r + QUEUED_MASS],
    S[s + STATE_Y],
    S[s + STATE_VX],
    S[s + STATE_VY],
    tb.gravity,
  );
}

/** Sum of trapped energies added in world index order (the engines continue it). */
export function sequentialEnergySum(tb: Tables): number {
  let total = 0.0;
  for (let i = 0; i < tb.n; i++) {
    const r = tb.row[i];
    if (tb.plan[PLAN_WIDTH * r + PLAN_STATUS] === TRAPPED) total += rowEnergy(tb, r);
  }
  return total;
}
