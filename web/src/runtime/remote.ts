/**
 * The game played in the physics worker, seen from the page: the same surface as the
 * page's own `Game` (what the app and the view read and call), with the controls' state
 * (pause, speed, the trap height asked for) answered at once on the page and sent to the
 * worker in order, and the physics' state read from the newest frame buffer it posted.
 */
import { FPS } from "../game/engine";
import {
  checkSpeed,
  clampHeight,
  Game,
  HEIGHT_START,
  LOSE_REASONS,
  nextSpeed,
  type GameConfig,
  type LoseReason,
  type SimFactory,
} from "../game/rules";
import { CLASSIC_ROOM, coreBytes, randomSeed, type Room } from "../game/engine";
import type { AtomArrays, SimLike } from "../game/sim";
import {
  frameViews,
  HEADER,
  type Command,
  type FrameViews,
  type FromWorker,
  type ToWorker,
} from "./worker-protocol";

/** What the page uses of a game: the page's own `Game`, or the worker's seen through this
 * (whose sim the page only reads: a SimLike). */
export type GameLike = { readonly sim: SimLike } & Pick<
  Game,
  | "config"
  | "paused"
  | "speed"
  | "generation"
  | "wonAt"
  | "won"
  | "score"
  | "allEscaped"
  | "trapHeight"
  | "playTime"
  | "togglePause"
  | "faster"
  | "slower"
  | "setTrapHeight"
  | "nudgeHeight"
  | "step"
  | "update"
  | "tooFewAtoms"
  | "restart"
>;

/** The physics' state as of the newest frame buffer (a SimLike the view draws). */
export class MirrorSim implements SimLike {
  frame: FrameViews | null = null;
  private roomSeen: Room = CLASSIC_ROOM;

  private at(slot: number): number {
    return this.frame ? this.frame.header[slot] : 0;
  }
  get time() {
    return this.at(HEADER.time);
  }
  get nAtoms() {
    return this.at(HEADER.nAtoms);
  }
  get nTrapped() {
    return this.at(HEADER.nTrapped);
  }
  get nEscaped() {
    return this.at(HEADER.nEscaped);
  }
  get trapHeight() {
    return this.at(HEADER.trapHeight);
  }
  set trapHeight(_h: number) {
    throw new Error("the worker's trap height is set through the game");
  }
  get rimHalfWidth() {
    return this.at(HEADER.rimHalfWidth);
  }
  get curvature() {
    return this.at(HEADER.curvature);
  }
  get gravity() {
    return this.at(HEADER.gravity);
  }
  get temperature() {
    return this.at(HEADER.temperature);
  }
  get initialTemperature() {
    return this.at(HEADER.initialTemperature);
  }
  get criticalTemperature() {
    return this.at(HEADER.criticalTemperature);
  }
  get tcExponent() {
    return this.at(HEADER.tcExponent);
  }
  get won() {
    return this.at(HEADER.won) === 1;
  }
  get winRule() {
    return this.at(HEADER.winRule) === 1;
  }
  get collisionCount() {
    return this.at(HEADER.collisionCount);
  }
  get room(): Room {
    const [left, right, below, above] = [
      this.at(HEADER.roomLeft),
      this.at(HEADER.roomRight),
      this.at(HEADER.roomBelow),
      this.at(HEADER.roomAbove),
    ];
    const r = this.roomSeen;
    if (r.left !== left || r.right !== right || r.below !== below || r.above !== above)
      this.roomSeen = { left, right, below, above };
    return this.roomSeen;
  }
  get originLift(): number {
    return this.at(HEADER.originLift);
  }
  advance(): void {
    throw new Error("the worker advances the physics");
  }
  trapped(): AtomArrays {
    return this.frame!.trapped;
  }
  escaped(): AtomArrays {
    return this.frame!.escaped;
  }
}

export interface RemoteHooks {
  /** The gas condensed (once per game). */
  won(): void;
  /** The worker failed: play on the page's own loop from here. */
  failed(message: string): void;
}

/** A worker that has not said hello after this long is taken for failed, ms. */
const HELLO_MS = 3000;

/** Whole configs the physics accepted (a restart with one of them needs no check). */
const configKey = (c: GameConfig) => `${c.nAtoms}|${c.radius}|${c.tcExponent}|${c.escape}`;

export class RemoteGame implements GameLike {
  readonly sim = new MirrorSim();
  config: GameConfig;
  speed: number;
  /** Games started (the worker's generation once its first frame of the newest arrived). */
  private asked = 1;
  private pausedNow = true;
  private height = HEIGHT_START;
  private wonAtNow: number | null = null;
  private seq = 0;
  private applied = 0;
  private toReturn: ArrayBuffer | null = null;
  private waiting: Array<() => void> = [];
  private replies = new Map<number, (text: string) => void>();
  private movesAsked = new Map<number, (runs: Array<[number, number]>) => void>();
  private readonly checked = new Set<string>();
  private alive = false;

  constructor(
    private readonly worker: Worker,
    /** The page's own factory: checks a config (RangeError) before the worker gets it. */
    private readonly factory: SimFactory,
    config: GameConfig,
    private readonly hooks: RemoteHooks,
  ) {
    this.config = config;
    this.speed = checkSpeed(config.speed);
    this.check(config);
    worker.onmessage = (ev: MessageEvent<FromWorker>) => this.receive(ev.data);
    worker.onerror = (ev) => this.fail(ev.message || "the physics worker stopped");
    this.send({ type: "start", config: this.withSeed(config), core: coreBytes() });
  }

  /**
   * Resolves once the worker's first frame has arrived, or it failed (a worker the page's
   * policy blocks may not even report an error: no word from it within `helloMs` is failure).
   */
  ready(helloMs = HELLO_MS): Promise<void> {
    if (this.frame) return Promise.resolve();
    const watchdog = setTimeout(() => {
      if (!this.alive) this.fail("no answer from the physics worker");
    }, helloMs);
    return this.settled().finally(() => clearTimeout(watchdog));
  }

  private get frame(): FrameViews | null {
    return this.sim.frame;
  }

  private send(msg: ToWorker, transfer: Transferable[] = []): void {
    this.worker.postMessage(msg, transfer);
  }

  private command(command: Command): void {
    this.seq += 1;
    this.send({ type: "command", seq: this.seq, command });
  }

  /** Throws the physics' RangeError for a config it refuses (as Game.restart would). */
  private check(config: GameConfig): void {
    const key = configKey(config);
    if (this.checked.has(key)) return;
    this.factory(this.withSeed(config));
    this.checked.add(key);
  }

  private withSeed(config: GameConfig): GameConfig {
    return { ...config, seed: config.seed ?? randomSeed() };
  }

  private receive(msg: FromWorker): void {
    if (msg.type === "hello") {
      this.alive = true;
    } else if (msg.type === "failed") {
      this.fail(msg.message);
    } else if (msg.type === "moves") {
      this.movesAsked.get(msg.id)?.(msg.runs);
      this.movesAsked.delete(msg.id);
    } else if (msg.type === "replayed") {
      this.replies.get(msg.id)?.(msg.text);
      this.replies.delete(msg.id);
    } else if (msg.type === "frame") {
      // The buffer drawn so far goes back with the next display frame; one not drawn at all
      // goes back now.
      if (this.toReturn) this.send({ type: "give", buffer: this.toReturn }, [this.toReturn]);
      this.toReturn = this.frame ? this.frame.buffer : null;
      this.sim.frame = frameViews(msg.buffer);
      this.took(this.sim.frame.header);
    }
  }

  /** The worker failed: whoever waits on it goes on (the page plays without it). */
  private fail(message: string): void {
    this.hooks.failed(message);
    const done = this.waiting;
    this.waiting = [];
    done.forEach((f) => f());
  }

  /** What a new frame tells: a restart done, the win, the commands applied. */
  private took(h: Float64Array): void {
    this.applied = h[HEADER.seq];
    if (h[HEADER.generation] === this.asked) {
      const wonAt = h[HEADER.wonAt];
      if (this.wonAtNow === null && !Number.isNaN(wonAt)) {
        this.wonAtNow = wonAt;
        this.hooks.won();
      }
    }
    if (this.applied >= this.seq) {
      const done = this.waiting;
      this.waiting = [];
      done.forEach((f) => f());
    }
  }

  /** Resolves once the worker has applied every command sent so far and posted the result. */
  settled(): Promise<void> {
    if (this.frame && this.applied >= this.seq) return Promise.resolve();
    return new Promise((resolve) => this.waiting.push(resolve));
  }

  // -- the Game's surface --------------------------------------------------------------------
  get paused(): boolean {
    return this.pausedNow;
  }
  set paused(p: boolean) {
    if (p === this.pausedNow) return;
    this.pausedNow = p;
    this.command({ kind: "paused", paused: p });
  }

  togglePause(): void {
    this.paused = !this.paused;
  }

  faster(): void {
    this.setSpeed(nextSpeed(this.speed, true));
  }

  slower(): void {
    this.setSpeed(nextSpeed(this.speed, false));
  }

  private setSpeed(speed: number): void {
    this.speed = speed;
    this.command({ kind: "speed", speed });
  }

  /** The game of the frame drawn (a restart counts once the worker's first frame of it arrived). */
  get generation(): number {
    return this.frame ? this.frame.header[HEADER.generation] : 0;
  }

  /** The frame drawn is of an older game than the one asked for (a restart in flight). */
  private get stale(): boolean {
    return this.generation !== this.asked;
  }

  get won(): boolean {
    return !this.stale && this.sim.won;
  }

  get wonAt(): number | null {
    return this.wonAtNow;
  }

  /** The worker's Game.score (fixed at the whole frame the win was seen). */
  get score(): number | null {
    const score = this.stale || !this.frame ? NaN : this.frame.header[HEADER.score];
    return Number.isNaN(score) ? null : score;
  }

  get allEscaped(): boolean {
    return !this.stale && this.frame?.header[HEADER.allEscaped] === 1;
  }

  get playTime(): number {
    return this.sim.time / FPS;
  }

  /** The height asked for last (the worker applies it at its next frame boundary). */
  get trapHeight(): number {
    return this.height;
  }

  /** The one clamp on the height's way down: the worker holds it as sent (Game.holdHeight). */
  setTrapHeight(height: number): boolean {
    if (this.won || !Number.isFinite(height)) return false;
    const h = clampHeight(height);
    if (h === this.height) return false;
    this.height = h;
    this.command({ kind: "height", height: h });
    return true;
  }

  nudgeHeight(delta: number): boolean {
    return this.setTrapHeight(this.height + delta);
  }

  step(): number {
    if (!this.paused) return 0;
    this.command({ kind: "step" });
    return 1;
  }

  /** A display frame began: the worker advances by the time since the last one. */
  update(wallSeconds: number): number {
    const buffer = this.toReturn;
    this.toReturn = null;
    const frameSeconds = Math.min(1 / 20, Math.max(1 / 240, wallSeconds || 1 / 60));
    this.send({ type: "vsync", frameSeconds, buffer }, buffer ? [buffer] : []);
    return 0;
  }

  /** n frames of 1 physics frame x speed each, in the worker; resolves once they are shown. */
  runFrames(n: number): Promise<void> {
    if (!this.paused) this.command({ kind: "frames", n });
    return this.settled();
  }

  /** New atoms, trap at 400, paused; a config the physics refuses throws and changes nothing. */
  restart(config?: GameConfig): void {
    const c = config ?? this.config;
    this.check(c);
    this.config = c;
    this.pausedNow = true;
    this.height = HEIGHT_START;
    this.wonAtNow = null;
    this.asked += 1;
    this.command({ kind: "restart", config: this.withSeed(c) });
  }

  /** The worker's answer to the reach rule (Game.tooFewAtoms) for the frame drawn. */
  tooFewAtoms(): LoseReason | null {
    const k = this.stale || !this.frame ? 0 : this.frame.header[HEADER.tooFew];
    return LOSE_REASONS[k] ?? null;
  }

  /** The worker's ms spent on the physics for its newest frame. */
  get physicsMs(): number {
    return this.frame ? this.frame.header[HEADER.physicsMs] : NaN;
  }

  /** The physics' own switch to the won state (tests of the condensate). */
  forceWin(): Promise<void> {
    this.command({ kind: "forceWin" });
    return this.settled();
  }

  /** A golden trace's text replayed by the worker's engine (tests). */
  replay(text: string): Promise<string> {
    const id = this.seq + 1 + this.replies.size;
    return new Promise((resolve) => {
      this.replies.set(id, resolve);
      this.send({ type: "replay", id, text });
    });
  }

  /** The heights held per whole frame so far, run-length coded (after all input sent). */
  moves(): Promise<Array<[number, number]>> {
    const id = this.seq + 1 + this.replies.size + this.movesAsked.size;
    return new Promise((resolve) => {
      this.movesAsked.set(id, resolve);
      this.send({ type: "moves", id });
    });
  }

  stop(): void {
    this.worker.terminate();
  }
}
