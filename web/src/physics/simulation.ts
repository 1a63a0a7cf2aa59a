/**
 * `Simulation`: the public face of the physics, the TypeScript twin of Python's
 * `evapcool.Simulation` (SPEC section 3) in camelCase.
 *
 * Trap coordinates: x right, y up, origin at the lowest point an atom centre can reach;
 * lengths in px, time in frames (1/30 s), mass in atom masses. Arrays of points are
 * interleaved: [x0, y0, x1, y1, ...].
 */
import {
  ATOM_RADIUS,
  CURVATURE,
  ESCAPE_RULES,
  ESCAPED,
  EVENT_NAMES,
  GRAVITY,
  N_ATOMS,
  STATUS_NAMES,
  TC_EXPONENT_SEED,
  TRAP_HEIGHT,
  TRAPPED,
  type EscapeRule,
  type EventName,
} from "./constants";
import { checkedConfig, type SimulationConfig, type SimulationOptions } from "./config";
import { escapeBox, roomTop, type Room } from "./room";
import { randomSeed } from "./start";
import {
  STATE_FORMAT,
  STATE_VERSION,
  bad,
  checkPlacement,
  parseState,
  windowOfRoom,
  type SimulationState,
  type StateInput,
} from "./state";
import { STORED, WasmEngine, loadCup, type EngineAtoms, type EngineCore } from "./wasm";
import { checkStart, checkWorld } from "./validation";
import {
  CURVATURE as CURVATURE_RANGE,
  GRAVITY as GRAVITY_RANGE,
  MASS as MASS_RANGE,
  N_ATOMS as N_ATOMS_RANGE,
  RADIUS as RADIUS_RANGE,
  TC_EXPONENT as TC_EXPONENT_RANGE,
  TRAP_HEIGHT as TRAP_HEIGHT_RANGE,
  pyFloat,
  type Range,
} from "../limits";

/** One processed event: kind, atoms (j = -1 for solo events) and time in frames. */
export interface PhysicsEvent {
  kind: EventName;
  i: number;
  j: number;
  time: number;
}

/** Per-atom columns of trapped or escaped atoms now; `count` rows are valid. */
export interface AtomSnapshot {
  count: number;
  /** The atom's index (stable for the whole run: colours, selection). */
  index: Int32Array;
  x: Float64Array;
  y: Float64Array;
  vx: Float64Array;
  vy: Float64Array;
  radius: Float64Array;
  mass: Float64Array;
  /** 1/2 m v^2 + m g y. */
  energy: Float64Array;
}

/** Mid-run states may have atoms touching or on the wall up to round-off: this much, relative. */
const STATE_TOLERANCE = 1e-9;

/** Interleaved points [x0, y0, ...] of the loader as two columns. */
function columns(xy: Float64Array, n: number): [Float64Array, Float64Array] {
  const xs = new Float64Array(n);
  const ys = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    xs[i] = xy[2 * i];
    ys[i] = xy[2 * i + 1];
  }
  return [xs, ys];
}

/** NumPy's pairwise summation (np.sum of a float64 array), so sums match Python's bits. */
export function pairwiseSum(a: Float64Array, start: number, n: number): number {
  if (n < 8) {
    let res = 0.0;
    for (let i = 0; i < n; i++) res += a[start + i];
    return res;
  }
  if (n <= 128) {
    let r0 = a[start];
    let r1 = a[start + 1];
    let r2 = a[start + 2];
    let r3 = a[start + 3];
    let r4 = a[start + 4];
    let r5 = a[start + 5];
    let r6 = a[start + 6];
    let r7 = a[start + 7];
    let i = 8;
    for (; i < n - (n % 8); i += 8) {
      const b = start + i;
      r0 += a[b];
      r1 += a[b + 1];
      r2 += a[b + 2];
      r3 += a[b + 3];
      r4 += a[b + 4];
      r5 += a[b + 5];
      r6 += a[b + 6];
      r7 += a[b + 7];
    }
    let res = r0 + r1 + (r2 + r3) + (r4 + r5 + (r6 + r7));
    for (; i < n; i++) res += a[start + i];
    return res;
  }
  let n2 = Math.floor(n / 2);
  n2 -= n2 % 8;
  return pairwiseSum(a, start, n2) + pairwiseSum(a, start + n2, n - n2);
}

/** Hard disks in a parabolic cup under gravity, advanced event by event, exactly. */
export class Simulation {
  private engine!: EngineCore;
  private roomAround!: Room;
  private seedUsed!: number | null;
  private scratch!: Float64Array;

  constructor(options: SimulationOptions = {}) {
    this.build(checkedConfig(options));
  }

  /** A simulation of a config checked once at the boundary (checkedConfig); nothing is
   * checked again here but whether the atoms fit the cup (the loader's). */
  static fromConfig(config: SimulationConfig): Simulation {
    const sim = Object.create(Simulation.prototype) as Simulation;
    sim.build(config);
    return sim;
  }

  private build(c: SimulationConfig): void {
    const n = c.nAtoms;
    const radius = c.radius;
    let xs: Float64Array;
    let ys: Float64Array;
    let vxs: Float64Array;
    let vys: Float64Array;
    this.seedUsed = null;
    if (c.start === null) {
      const s = c.seed ?? randomSeed();
      this.seedUsed = s;
      const start = loadCup(n, radius[0], c.curvature, roomTop(c.room, radius[0]), s);
      [xs, ys] = columns(start.positions, n);
      [vxs, vys] = columns(start.velocities, n);
    } else {
      ({ x: xs, y: ys, vx: vxs, vy: vys } = c.start);
    }
    this.init(
      c.room,
      {
        curvature: c.curvature,
        gravity: c.gravity,
        tcExponent: c.tcExponent,
        escape: c.escape,
        win: c.win,
        trapHeight: c.trapHeight,
        recordEvents: c.recordEvents,
      },
      {
        x: xs,
        y: ys,
        vx: vxs,
        vy: vys,
        t: new Float64Array(n),
        radius,
        mass: c.mass,
        status: new Int8Array(n),
        time: 0,
        won: false,
        pairCount: 0,
        wallCount: 0,
      },
    );
  }

  private init(
    room: Room,
    rules: {
      curvature: number;
      gravity: number;
      tcExponent: number;
      escape: EscapeRule;
      win: boolean;
      trapHeight: number;
      recordEvents: boolean;
    },
    atoms: EngineAtoms,
  ): void {
    // The trap origin lies the first atom's radius above the wall's lowest point.
    const [xLeft, xRight, yBottom] = escapeBox(room, atoms.radius[0]);
    this.scratch = new Float64Array(4);
    this.roomAround = room;
    this.engine = new WasmEngine(
      {
        curvature: rules.curvature,
        gravity: rules.gravity,
        trapHeight: rules.trapHeight,
        xLeft,
        xRight,
        yBottom,
        tcExponent: rules.tcExponent,
        knife: rules.escape === "knife",
        winRule: rules.win,
        recordEvents: rules.recordEvents,
      },
      atoms,
    );
    this.engine.setTrapHeight(rules.trapHeight);
  }

  /** The original applet's start: 49 atoms of radius 12 in the cup, H = 400. */
  static classic(seed?: number, overrides: SimulationOptions = {}): Simulation {
    return new Simulation({ nAtoms: N_ATOMS, radius: ATOM_RADIUS, seed, ...overrides });
  }

  /**
   * A simulation that goes on exactly from a state (object or JSON text, docs/state.md).
   * RangeError naming the field if the state is malformed, atoms overlap or lie outside the cup.
   */
  static fromState(
    state: StateInput | SimulationState | string,
    options: { recordEvents?: boolean } = {},
  ): Simulation {
    const p = parseState(state);
    const record = options.recordEvents ?? false;
    if (typeof record !== "boolean") throw bad("recordEvents", "true or false", record);
    const n = p.x.length;
    // Trapped atoms where they are now: inside the cup, not overlapping (up to round-off).
    const halfG = 0.5 * p.gravity;
    const xn = new Float64Array(n);
    const yn = new Float64Array(n);
    for (let i = 0; i < n; i++) {
      const dt = p.time - p.t[i];
      xn[i] = p.x[i] + p.vx[i] * dt;
      yn[i] = p.y[i] + p.vy[i] * dt - halfG * dt * dt;
    }
    checkPlacement(
      "state.atoms",
      xn,
      yn,
      p.radius,
      (i) => p.status[i] === TRAPPED,
      p.curvature,
      STATE_TOLERANCE,
      !p.won, // the condensate's atoms no longer collide: they may overlap
    );
    checkWorld({ ...p, trapped: (i) => p.status[i] === TRAPPED });
    const sim = Object.create(Simulation.prototype) as Simulation;
    sim.seedUsed = null;
    sim.init(
      p.room,
      {
        curvature: p.curvature,
        gravity: p.gravity,
        tcExponent: p.tcExponent,
        escape: p.escape,
        win: p.win,
        trapHeight: p.trapHeight,
        recordEvents: record,
      },
      {
        x: p.x,
        y: p.y,
        vx: p.vx,
        vy: p.vy,
        t: p.t,
        radius: p.radius,
        mass: p.mass,
        status: p.status,
        time: p.time,
        energySum: p.energySum,
        initialTemperature: p.initialTemperature,
        won: p.won,
        pairCount: p.pairCount,
        wallCount: p.wallCount,
      },
    );
    if (p.energySum !== undefined) {
      const e = sim.engine;
      const sum = e.sequentialEnergySum();
      let scale = 0;
      for (let i = 0; i < n; i++) if (p.status[i] === TRAPPED) scale += Math.abs(e.atomEnergy(i));
      if (!(Math.abs(p.energySum - sum) <= STATE_TOLERANCE * Math.max(1, scale)))
        throw bad("state.energy_sum", `the trapped atoms' energy sum, ${sum}`, p.energySum);
    }
    return sim;
  }

  /** The state as a JSON-ready object (docs/state.md): exact, resumable with fromState. */
  toState(): SimulationState {
    const e = this.engine;
    const n = e.nAtoms;
    const col = (k: number): number[] => {
      const out = new Array<number>(n);
      for (let i = 0; i < n; i++) out[i] = e.storedOf(i, k);
      return out;
    };
    const status = new Array<(typeof STATUS_NAMES)[number]>(n);
    for (let i = 0; i < n; i++) status[i] = STATUS_NAMES[e.statusOf(i)];
    return {
      format: STATE_FORMAT,
      version: STATE_VERSION,
      time: e.time,
      trap_height: Number.isFinite(e.trapHeight) ? e.trapHeight : "inf",
      curvature: e.curvature,
      gravity: e.gravity,
      window: windowOfRoom(this.roomAround),
      escape: e.knife ? "knife" : "rim",
      tc_exponent: e.tcExponent,
      win: e.winRule,
      won: e.won,
      initial_temperature: e.initialTemperature,
      energy_sum: e.energySum,
      pair_collisions: e.pairCount,
      wall_collisions: e.wallCount,
      atoms: {
        x: col(STORED.x),
        y: col(STORED.y),
        vx: col(STORED.vx),
        vy: col(STORED.vy),
        t: col(STORED.t),
        radius: col(STORED.radius),
        mass: col(STORED.mass),
        status,
      },
    };
  }

  /** JSON.stringify(sim) writes the state. */
  toJSON(): SimulationState {
    return this.toState();
  }

  // -- time ------------------------------------------------------------------------------
  /** Advance by dt frames, processing every event exactly. */
  advance(dt: number): void {
    if (typeof dt !== "number" || !Number.isFinite(dt) || dt < 0)
      throw bad("dt", "a finite number of frames >= 0", dt);
    this.engine.advanceTo(this.engine.time + dt);
  }

  /** Simulation time in frames. */
  get time(): number {
    return this.engine.time;
  }

  // -- the trap --------------------------------------------------------------------------
  /** Rim height H in px above the lowest centre position. */
  get trapHeight(): number {
    return this.engine.trapHeight;
  }

  set trapHeight(value: number) {
    this.engine.setTrapHeight(TRAP_HEIGHT_RANGE.check("trapHeight", value));
  }

  /** x_rim = sqrt(H / a): the wall ends at |x| = x_rim. */
  get rimHalfWidth(): number {
    return this.engine.xRim;
  }

  get curvature(): number {
    return this.engine.curvature;
  }

  get gravity(): number {
    return this.engine.gravity;
  }

  /** "rim" (fly over the rim) or "knife" (energy above m g H removed at once). */
  get escape(): EscapeRule {
    return this.engine.knife ? "knife" : "rim";
  }

  /** Python's name for `escape`. */
  get escapeRule(): EscapeRule {
    return this.escape;
  }

  /** The room around the cup: where escaped atoms are gone (physics/room.ts). */
  get room(): Room {
    return this.roomAround;
  }

  /** The trap origin's height above the cup wall's lowest point: the first atom's radius. */
  get originLift(): number {
    return this.engine.storedOf(0, STORED.radius);
  }

  /** The start's seed (drawn at random if none was given); null for a loaded state. */
  get seed(): number | null {
    return this.seedUsed;
  }

  // -- atoms -----------------------------------------------------------------------------
  /** Atoms at the start (N0), gone ones included. */
  get nAtoms(): number {
    return this.engine.nAtoms;
  }

  get nTrapped(): number {
    return this.engine.nTrapped;
  }

  /** Atoms that left the trap and are still falling inside the window. */
  get nEscaped(): number {
    const e = this.engine;
    let k = 0;
    for (let i = 0; i < e.nAtoms; i++) if (e.statusOf(i) === ESCAPED) k++;
    return k;
  }

  private indices(status: number): Int32Array {
    const e = this.engine;
    let k = 0;
    for (let i = 0; i < e.nAtoms; i++) if (e.statusOf(i) === status) k++;
    const out = new Int32Array(k);
    k = 0;
    for (let i = 0; i < e.nAtoms; i++) if (e.statusOf(i) === status) out[k++] = i;
    return out;
  }

  get trappedIndices(): Int32Array {
    return this.indices(TRAPPED);
  }

  get escapedIndices(): Int32Array {
    return this.indices(ESCAPED);
  }

  private column(status: number, what: "pos" | "vel" | "radius" | "mass"): Float64Array {
    const idx = this.indices(status);
    const e = this.engine;
    const s = this.scratch;
    const wide = what === "pos" || what === "vel";
    const out = new Float64Array(wide ? 2 * idx.length : idx.length);
    for (let k = 0; k < idx.length; k++) {
      const i = idx[k];
      if (what === "radius") out[k] = e.storedOf(i, STORED.radius);
      else if (what === "mass") out[k] = e.storedOf(i, STORED.mass);
      else {
        e.stateAt(i, e.time, s);
        out[2 * k] = what === "pos" ? s[0] : s[2];
        out[2 * k + 1] = what === "pos" ? s[1] : s[3];
      }
    }
    return out;
  }

  /** Centres of the trapped atoms now, [x0, y0, x1, y1, ...], trap coordinates (y up), px. */
  get positions(): Float64Array {
    return this.column(TRAPPED, "pos");
  }

  /** Velocities of the trapped atoms now, [vx0, vy0, ...], px / frame. */
  get velocities(): Float64Array {
    return this.column(TRAPPED, "vel");
  }

  get radii(): Float64Array {
    return this.column(TRAPPED, "radius");
  }

  get masses(): Float64Array {
    return this.column(TRAPPED, "mass");
  }

  /** Centres of the atoms falling out of the window, [x0, y0, ...]. */
  get escapedPositions(): Float64Array {
    return this.column(ESCAPED, "pos");
  }

  get escapedVelocities(): Float64Array {
    return this.column(ESCAPED, "vel");
  }

  get escapedRadii(): Float64Array {
    return this.column(ESCAPED, "radius");
  }

  /**
   * Trapped (or escaped) atoms now in per-atom columns, written into `out` when it has room
   * (no allocation per frame for a view that keeps its snapshot).
   */
  atoms(which: "trapped" | "escaped" = "trapped", out?: AtomSnapshot): AtomSnapshot {
    const e = this.engine;
    const status = which === "trapped" ? TRAPPED : which === "escaped" ? ESCAPED : -1;
    if (status < 0) throw bad("which", `"trapped" or "escaped"`, which);
    let snap = out;
    if (snap === undefined || snap.index.length < e.nAtoms) {
      const n = e.nAtoms;
      snap = {
        count: 0,
        index: new Int32Array(n),
        x: new Float64Array(n),
        y: new Float64Array(n),
        vx: new Float64Array(n),
        vy: new Float64Array(n),
        radius: new Float64Array(n),
        mass: new Float64Array(n),
        energy: new Float64Array(n),
      };
    }
    const s = this.scratch;
    let k = 0;
    for (let i = 0; i < e.nAtoms; i++) {
      if (e.statusOf(i) !== status) continue;
      e.stateAt(i, e.time, s);
      snap.index[k] = i;
      snap.x[k] = s[0];
      snap.y[k] = s[1];
      snap.vx[k] = s[2];
      snap.vy[k] = s[3];
      snap.radius[k] = e.storedOf(i, STORED.radius);
      snap.mass[k] = e.storedOf(i, STORED.mass);
      snap.energy[k] = e.atomEnergy(i);
      k++;
    }
    snap.count = k;
    return snap;
  }

  /** Energy 1/2 m v^2 + m g y of each trapped atom. */
  energies(): Float64Array {
    const e = this.engine;
    const out = new Float64Array(e.nTrapped);
    let k = 0;
    for (let i = 0; i < e.nAtoms; i++) if (e.statusOf(i) === TRAPPED) out[k++] = e.atomEnergy(i);
    return out;
  }

  /** Sum of 1/2 m v^2 + m g y over trapped atoms (summed as NumPy does: the same bits). */
  totalEnergy(): number {
    const en = this.energies();
    return pairwiseSum(en, 0, en.length);
  }

  // -- thermodynamics (seed Eqs. 1 and 46) --------------------------------------------------
  /** Mean energy per trapped atom, seed Eq. (1); 0 for an empty cup. */
  get temperature(): number {
    const n = this.engine.nTrapped;
    return n > 0 ? this.totalEnergy() / n : 0;
  }

  get initialTemperature(): number {
    return this.engine.initialTemperature;
  }

  /** Tc(N) = Tc0 (N / N0)^p with Tc0 = 0.75 T(0), seed Eq. (46). */
  get criticalTemperature(): number {
    return this.engine.criticalTemperatureOf(this.engine.nTrapped);
  }

  get tcExponent(): number {
    return this.engine.tcExponent;
  }

  /** True once T < Tc(N) (latched): the gas has condensed. Never with win: false. */
  get won(): boolean {
    return this.engine.won;
  }

  /** False if the game's win rule is off (win: false). */
  get winRule(): boolean {
    return this.engine.winRule;
  }

  /** Declare the gas condensed now (demonstrations and tests). */
  forceWin(): void {
    this.engine.forceWin();
  }

  // -- the game's frame (core/game.c: written once for both editions) -------------------
  /**
   * One whole frame from a whole frame, the trap at `height` during it: the height takes
   * effect at the frame's start (not after the win: the score is the atoms left), and the
   * frame's end sees the win and fixes the score. height: within the trap's limits.
   */
  frame(height: number): void {
    this.engine.frame(height);
  }

  /** The end of a whole frame reached by advance: the win seen now, the score fixed. */
  frameEnd(): void {
    this.engine.frameEnd();
  }

  /** Atoms trapped at the end of the whole frame the win was seen in; null before. */
  get score(): number | null {
    return this.engine.score;
  }

  /** Hold each [height, frames] run's height for that many whole frames (frame), from a whole
   * frame, up to the end of the frame the win is seen in or `limit` frames: the frames played. */
  replay(runs: ReadonlyArray<readonly [number, number]>, limit: number): number {
    return this.engine.replay(runs, limit);
  }

  // -- counters --------------------------------------------------------------------------
  get pairCollisionCount(): number {
    return this.engine.pairCount;
  }

  get wallCollisionCount(): number {
    return this.engine.wallCount;
  }

  get collisionCount(): number {
    return this.engine.pairCount + this.engine.wallCount;
  }

  /** Events recorded so far (recordEvents), without building the log. */
  get eventCount(): number {
    return this.engine.nLog;
  }

  /** Recorded event k (0 <= k < eventCount). */
  eventAt(k: number): PhysicsEvent {
    if (!Number.isInteger(k) || k < 0 || k >= this.engine.nLog)
      throw bad("k", `a whole number from 0 to ${this.engine.nLog - 1}`, k);
    const [kind, i, j, time] = this.engine.logEntry(k);
    return { kind: EVENT_NAMES[kind], i, j, time };
  }

  /** Every event so far if recordEvents was set, else []. */
  get eventLog(): PhysicsEvent[] {
    const e = this.engine;
    const out: PhysicsEvent[] = [];
    for (let k = 0; k < e.nLog; k++) {
      const [kind, i, j, time] = e.logEntry(k);
      out.push({ kind: EVENT_NAMES[kind], i, j, time });
    }
    return out;
  }

  /** Engine diagnostics: cell crossings and stale pair events processed, grid shape. */
  get engineStats(): {
    crossings: number;
    stale: number;
    cells: [number, number];
    cellSize: number;
    gridErrors: number;
  } {
    const e = this.engine;
    return {
      crossings: e.crossingCount,
      stale: e.staleCount,
      cells: [e.gridColumns, e.gridRows],
      cellSize: e.cellSize,
      gridErrors: e.gridErrors(),
    };
  }
}
