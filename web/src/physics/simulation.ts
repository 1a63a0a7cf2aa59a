/**
 * `Simulation`: the public face of the physics, the TypeScript twin of Python's
 * `evapcool.Simulation` (SPEC section 3) in camelCase.
 *
 * Trap coordinates: x right, y up, origin at the lowest point an atom centre can reach;
 * lengths in px, time in frames (1/30 s), mass in atom masses. Arrays of points are
 * interleaved: [x0, y0, x1, y1, ...].
 * Python's twin: `src/evapcool/physics/simulation.py` (docs/twins.md).
 */
import {
  ATOM_RADIUS,
  ESCAPED,
  EVENT_NAMES,
  N_ATOMS,
  STATUS_NAMES,
  TRAPPED,
  type EscapeRule,
  type PhysicsEvent,
} from "./constants";
import { checkedConfig, points, type SimulationOptions } from "./config";
import { roomTop, type Room } from "./room";
import { randomSeed } from "./start";
import {
  STATE_FORMAT,
  STATE_VERSION,
  bad,
  checkState,
  parseState,
  windowOfRoom,
  type SimulationState,
  type StateInput,
} from "./state";
import { loadCup } from "./instance";
import { STORED, WasmEngine, type EngineAtoms, type EngineRules } from "./wasm";
import {
  countOf,
  interleaved,
  snapshot,
  trappedEnergies,
  type AtomGroup,
  type AtomSnapshot,
} from "./snapshot";
import { CONTACT_TOLERANCE, DT, TRAP_HEIGHT as TRAP_HEIGHT_RANGE } from "../limits";

/** Hard disks in a parabolic cup under gravity, advanced event by event, exactly. */
export class Simulation {
  private engine!: WasmEngine;
  private seedUsed!: number | null;

  /** A simulation of options checked once, here (checkedConfig); nothing below checks them
   * again but whether the atoms fit the cup (the loader's). */
  constructor(options: SimulationOptions = {}) {
    const c = checkedConfig(options);
    const n = c.nAtoms;
    let start = c.start;
    let seed: number | null = null;
    if (start === null) {
      seed = c.seed ?? randomSeed();
      const cup = loadCup(n, c.radius[0], c.curvature, roomTop(c.room, c.radius[0]), seed);
      const [x, y] = points("positions", cup.positions, n);
      const [vx, vy] = points("velocities", cup.velocities, n);
      start = { x, y, vx, vy };
    }
    const atoms: EngineAtoms = {
      ...start,
      t: new Float64Array(n),
      radius: c.radius,
      mass: c.mass,
      status: new Int8Array(n),
      time: 0,
      won: false,
      pairCount: 0,
      wallCount: 0,
    };
    this.init(c, atoms, seed);
  }

  private init(rules: EngineRules, atoms: EngineAtoms, seed: number | null): void {
    this.seedUsed = seed;
    this.engine = new WasmEngine(rules, atoms);
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
    const recordEvents = options.recordEvents ?? false;
    if (typeof recordEvents !== "boolean") throw bad("recordEvents", "true or false", recordEvents);
    checkState(p);
    const sim = Object.create(Simulation.prototype) as Simulation;
    sim.init({ ...p, recordEvents }, p, null);
    if (p.energySum !== undefined) {
      const e = sim.engine;
      const sum = e.read("core_sequential_energy_sum");
      let scale = 0;
      for (let i = 0; i < e.nAtoms; i++)
        if (p.status[i] === TRAPPED) scale += Math.abs(e.atomEnergy(i));
      if (!(Math.abs(p.energySum - sum) <= CONTACT_TOLERANCE * Math.max(1, scale)))
        throw bad("state.energy_sum", `the trapped atoms' energy sum, ${sum}`, p.energySum);
    }
    return sim;
  }

  /** The state as a JSON-ready object (docs/state.md): exact, resumable with fromState. */
  toState(): SimulationState {
    const e = this.engine;
    const n = e.nAtoms;
    const col = (k: number): number[] => Array.from({ length: n }, (_, i) => e.storedOf(i, k));
    const status = Array.from({ length: n }, (_, i) => STATUS_NAMES[e.statusOf(i)]);
    return {
      format: STATE_FORMAT,
      version: STATE_VERSION,
      time: this.time,
      trap_height: Number.isFinite(this.trapHeight) ? this.trapHeight : "inf",
      curvature: this.curvature,
      gravity: this.gravity,
      window: windowOfRoom(this.room),
      escape: this.escape,
      tc_exponent: this.tcExponent,
      win: this.winRule,
      won: this.won,
      initial_temperature: e.initialTemperature,
      energy_sum: e.read("core_energy_sum"),
      pair_collisions: this.pairCollisionCount,
      wall_collisions: this.wallCollisionCount,
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

  // -- time ------------------------------------------------------------------------------
  /** Advance by dt frames, processing every event exactly. */
  advance(dt: number): void {
    this.engine.advanceTo(this.time + DT.check("dt", dt));
  }

  /** Simulation time in frames. */
  get time(): number {
    return this.engine.read("core_time");
  }

  // -- the trap --------------------------------------------------------------------------
  /** Rim height H in px above the lowest centre position. */
  get trapHeight(): number {
    return this.engine.read("core_trap_height");
  }

  set trapHeight(value: number) {
    this.engine.setTrapHeight(TRAP_HEIGHT_RANGE.check("trapHeight", value));
  }

  /** x_rim = sqrt(H / a): the wall ends at |x| = x_rim. */
  get rimHalfWidth(): number {
    return this.engine.read("core_x_rim");
  }

  get curvature(): number {
    return this.engine.rules.curvature;
  }

  get gravity(): number {
    return this.engine.rules.gravity;
  }

  /** "rim" (fly over the rim) or "knife" (energy above m g H removed at once). */
  get escape(): EscapeRule {
    return this.engine.rules.escape;
  }

  /** The room around the cup: where escaped atoms are gone (physics/room.ts). */
  get room(): Room {
    return this.engine.rules.room;
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
    return this.engine.read("core_n_trapped");
  }

  /** Atoms that left the trap and are still falling inside the window. */
  get nEscaped(): number {
    return countOf(this.engine, ESCAPED);
  }

  /** Centres of the trapped atoms now, [x0, y0, x1, y1, ...], trap coordinates (y up), px. */
  get positions(): Float64Array {
    const s = this.atoms();
    return interleaved(s.x, s.y, s.count);
  }

  /** Velocities of the trapped atoms now, [vx0, vy0, ...], px / frame. */
  get velocities(): Float64Array {
    const s = this.atoms();
    return interleaved(s.vx, s.vy, s.count);
  }

  get radii(): Float64Array {
    const s = this.atoms();
    return s.radius.slice(0, s.count);
  }

  /** Centres of the atoms falling out of the window, [x0, y0, ...]. */
  get escapedPositions(): Float64Array {
    const s = this.atoms("escaped");
    return interleaved(s.x, s.y, s.count);
  }

  /**
   * Trapped (or escaped) atoms now in per-atom columns, written into `out` when it has room
   * (no allocation per frame for a view that keeps its snapshot).
   */
  atoms(which: AtomGroup = "trapped", out?: AtomSnapshot): AtomSnapshot {
    return snapshot(this.engine, which, this.time, out);
  }

  /** Energy 1/2 m v^2 + m g y of each trapped atom. */
  energies(): Float64Array {
    return trappedEnergies(this.engine, this.nTrapped);
  }

  /** Sum of 1/2 m v^2 + m g y over trapped atoms (the core sums as NumPy does: the same bits). */
  totalEnergy(): number {
    return this.engine.read("core_total_energy");
  }

  // -- thermodynamics (seed Eqs. 1 and 46) --------------------------------------------------
  /** Mean energy per trapped atom, seed Eq. (1); 0 for an empty cup. */
  get temperature(): number {
    const n = this.nTrapped;
    return n > 0 ? this.totalEnergy() / n : 0;
  }

  get initialTemperature(): number {
    return this.engine.initialTemperature;
  }

  /** Tc(N) = Tc0 (N / N0)^p with Tc0 = 0.75 T(0), seed Eq. (46). */
  get criticalTemperature(): number {
    return this.engine.criticalTemperatureOf(this.nTrapped);
  }

  get tcExponent(): number {
    return this.engine.rules.tcExponent;
  }

  /** True once T < Tc(N) (latched): the gas has condensed. Never with win: false. */
  get won(): boolean {
    return this.engine.read("core_won") !== 0;
  }

  /** False if the game's win rule is off (win: false). */
  get winRule(): boolean {
    return this.engine.rules.win;
  }

  /** Declare the gas condensed now (demonstrations and tests). */
  forceWin(): void {
    this.engine.forceWin();
  }

  // -- the game's clock (core/play.c: written once for both editions) -------------------
  /** Play to `end` frames, stopping at each whole frame: the height held recorded (moves, up
   * to the win), the win seen, the next height applied; onFrame(height held) after each. */
  playTo(end: number, onFrame: ((height: number) => void) | null = null): void {
    if (Number.isNaN(end)) throw new RangeError("end must be a number of frames (got NaN)");
    this.engine.playTo(end, onFrame);
  }

  /** A rim height from the next whole frame (at once if `now` or on one), or refused (false). */
  askHeight(height: number, now = false): boolean {
    return this.engine.askHeight(height, now);
  }

  /** The rim's height now, or the one it takes at the next whole frame. */
  get askedHeight(): number {
    return this.engine.read("core_asked_height");
  }

  /** Hold [height, frames] runs (a recording watched) from the start; none: the player's. */
  hold(runs: ReadonlyArray<readonly [number, number]>): void {
    this.engine.hold(runs);
  }

  /** The [height, frames] runs held so far, up to the frame the win was seen in. */
  moves(): Array<[number, number]> {
    return this.engine.moves();
  }

  /** The whole frame at whose end the win was seen; null before. */
  get winFrame(): number | null {
    return this.score === null ? null : this.engine.read("core_win_frame");
  }

  /** Atoms trapped at the end of the frame the win was seen in; null before. */
  get score(): number | null {
    const score = this.engine.read("core_score");
    return score < 0 ? null : score;
  }

  /** [height, frames] runs played from a whole frame to the win's or `limit`: frames played. */
  replay(runs: ReadonlyArray<readonly [number, number]>, limit: number): number {
    return this.engine.replay(runs, limit);
  }

  /** The (N, T) path of runs played as `replay` plays them (core_path): rows [k, N, T, h] at
   * frame 0 (height h0), every stride-th frame, the last and the win's, with N, T > 0. */
  path(runs: ReadonlyArray<readonly [number, number]>, limit: number, stride: number, h0: number) {
    return this.engine.path(runs, limit, stride, h0);
  }

  /** The reach rule (REACH_*: core_out_of_reach), the lowest rim the player can set, the rim now. */
  outOfReach(lowest: number, height: number): number {
    return this.engine.outOfReach(lowest, height);
  }

  // -- counters --------------------------------------------------------------------------
  get pairCollisionCount(): number {
    return this.engine.read("core_pairs");
  }

  get wallCollisionCount(): number {
    return this.engine.read("core_walls");
  }

  get collisionCount(): number {
    return this.pairCollisionCount + this.wallCollisionCount;
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
    return Array.from({ length: this.engine.nLog }, (_, k) => this.eventAt(k));
  }

  /** Engine diagnostics: cell crossings and stale pair events processed, grid shape. */
  get engineStats() {
    const e = this.engine;
    return {
      crossings: e.read("core_crossings"),
      stale: e.read("core_stale"),
      cells: [e.read("core_nx"), e.read("core_ny")] as [number, number],
      cellSize: e.read("core_cell"),
      gridErrors: e.read("core_grid_errors"),
    };
  }
}
