/**
 * The game around a simulation: pause, speed, restart, win, score, play time.
 * Pure state (no DOM, no canvas); the same rules as Python's `game/rules.py`.
 *
 * Time: the physics runs in whole frames of 1/30 s of play (x speed). Trap-height
 * changes wait for the next frame boundary, so a run depends on what the player did
 * in which frame, never on the display's rate; between boundaries the exact physics is
 * advanced to the moment drawn, so motion stays smooth at 60 or 120 Hz. That clock, the
 * moves it records, the win seen at a frame's end and the score fixed there are the core's
 * (core/play.c, the same C as the desktop's: GameSim.playTo).
 */
import {
  FPS,
  N_ATOMS,
  ATOM_RADIUS,
  REACH_NAMES,
  TC_EXPONENT_SEED,
  TRAP_HEIGHT,
  type GamePhysics,
} from "./engine";
import type { GameSim } from "./sim";
import { APPLET_HEIGHT, APPLET_SPEED } from "../limits";

/** The trap-height slider's range (limits.json's APPLET_HEIGHT) and its start. */
export const HEIGHT_MIN = APPLET_HEIGHT.low;
export const HEIGHT_MAX = APPLET_HEIGHT.high;
export const HEIGHT_START = TRAP_HEIGHT;
export const SPEED_MIN = APPLET_SPEED.low;
export const SPEED_MAX = APPLET_SPEED.high;
/**
 * One drawn frame never advances more than this much play (s): when frames fall behind (a
 * slow device, thousands of atoms) the game slows down instead of taking ever larger steps,
 * each costlier than the last; a stalled tab does not jump ahead. At 1x: at most 2 physics
 * frames a drawn frame (the desktop's number).
 */
export const MAX_WALL_STEP = 1 / 15;

export interface GameConfig extends GamePhysics {
  speed: number;
}

export const DEFAULT_CONFIG: GameConfig = {
  nAtoms: N_ATOMS,
  radius: ATOM_RADIUS,
  seed: null,
  speed: 1,
  tcExponent: TC_EXPONENT_SEED,
  escape: "rim",
};

export type SimFactory = (config: GameConfig) => GameSim;

/** The speed as a number, or RangeError naming the allowed range. */
export function checkSpeed(speed: unknown): number {
  if (typeof speed === "number" && APPLET_SPEED.contains(speed)) return speed;
  throw new RangeError(`speed must be ${APPLET_SPEED.allowed()} (got ${String(speed)})`);
}

/** The speed doubled (up) or halved, within the range (the +/- keys). */
export function nextSpeed(speed: number, up: boolean): number {
  return up ? Math.min(SPEED_MAX, speed * 2) : Math.max(SPEED_MIN, speed / 2);
}

/** A height within the slider's range; NaN (a broken rule) gives the top of the range. */
export function clampHeight(h: number): number {
  return Number.isNaN(h) ? HEIGHT_MAX : Math.min(HEIGHT_MAX, Math.max(HEIGHT_MIN, h));
}

export class Game {
  config: GameConfig;
  speed: number;
  sim!: GameSim;
  private pausedNow = true;
  /** Play time (s) at which the win was first seen; null before. */
  wonAt: number | null = null;
  /** Bumped by every restart so views can drop per-game caches. */
  generation = 0;
  readonly onWin: Array<(game: Game) => void> = [];
  /** Called at the end of each whole physics frame up to the win with the height held
   * during it (the moves themselves are the core's: moves()). */
  readonly onFrame: Array<(height: number) => void> = [];

  constructor(
    private readonly factory: SimFactory,
    config: Partial<GameConfig> = {},
  ) {
    this.config = { ...DEFAULT_CONFIG, ...config };
    this.speed = checkSpeed(this.config.speed);
    this.restart();
  }

  /** New atoms, trap at 400, paused; a config the physics rejects throws and changes nothing. */
  restart(config?: GameConfig): void {
    const sim = this.factory(config ?? this.config);
    if (config) this.config = config;
    sim.trapHeight = HEIGHT_START;
    this.sim = sim;
    this.paused = true;
    this.wonAt = null;
    this.generation += 1;
  }

  get paused(): boolean {
    return this.pausedNow;
  }

  /** Pausing finishes the frame in flight: a paused game stands on a whole frame, so a
   * height set while paused takes effect at one (the rule replays rely on). */
  set paused(p: boolean) {
    if (p && !this.pausedNow) this.finishFrame();
    this.pausedNow = p;
  }

  private finishFrame(): void {
    const t = this.sim.time;
    if (!Number.isInteger(t)) this.playTo(Math.floor(t) + 1);
  }

  /** Hold a recording's [height, frames] moves frame by frame from the start (a recording
   * watched); the player's input is ignored until they end or `playback(null)`. */
  playback(moves: ReadonlyArray<readonly [number, number]> | null): void {
    this.sim.hold((moves ?? []).map(([h, n]) => [clampHeight(h), n] as const));
  }

  /** The [height, frames] runs held since the (re)start, up to the win: the game's moves. */
  moves(): Array<[number, number]> {
    return this.sim.moves();
  }

  togglePause(): void {
    this.paused = !this.paused;
  }

  faster(): void {
    this.speed = nextSpeed(this.speed, true);
  }

  slower(): void {
    this.speed = nextSpeed(this.speed, false);
  }

  /** The height the trap has, or will have at the next frame boundary. */
  get trapHeight(): number {
    return this.sim.askedHeight;
  }

  /** Ask for a rim height, clamped to the slider's range: the one clamp on its way down. */
  setTrapHeight(height: number): boolean {
    return Number.isFinite(height) && this.holdHeight(clampHeight(height));
  }

  /** Hold a height of the slider's range from the next whole frame (the physics worker's:
   * the page's mirror clamped it, runtime/remote.ts); refused once the gas condensed, while
   * a recording plays and if already asked (the core's rule: GameSim.askHeight). */
  holdHeight(h: number): boolean {
    return this.sim.askHeight(h, this.paused);
  }

  nudgeHeight(delta: number): boolean {
    return this.setTrapHeight(this.trapHeight + delta);
  }

  /** Advance by elapsed wall time x 30 x speed (capped); returns the frames advanced. */
  update(wallSeconds: number): number {
    if (this.paused || !(wallSeconds > 0)) return 0;
    return this.advance(Math.min(wallSeconds, MAX_WALL_STEP) * FPS * this.speed);
  }

  /** Advance exactly n display frames of 1 physics frame x speed (tests, benchmarks). */
  runFrames(n = 1): number {
    if (this.paused) return 0;
    return this.advance(n * this.speed);
  }

  /** One physics frame forward, only while paused (frame-by-frame study). */
  step(): number {
    if (!this.paused) return 0;
    return this.advance(1);
  }

  private advance(frames: number): number {
    this.playTo(this.sim.time + frames);
    return frames;
  }

  /** Play to `end` (the core's clock, whole frame by whole frame: a game, its win and its
   * score depend on the heights of whole frames, not on the display's step); the frame
   * listeners hear each frame up to the win. */
  private playTo(end: number): void {
    this.sim.playTo(end, this.onFrame.length ? (h) => this.framePlayed(h) : null);
    this.checkWin();
  }

  private framePlayed(height: number): void {
    for (const listener of this.onFrame) listener(height);
    this.checkWin();
  }

  /** The win seen at a frame's end (the score fixed there), once. */
  private checkWin(): void {
    if (this.sim.score !== null && this.wonAt === null) {
      this.wonAt = (this.sim.winFrame ?? 0) / FPS;
      for (const callback of [...this.onWin]) callback(this);
    }
  }

  /** Simulated seconds since the (re)start, independent of the speed setting. */
  get playTime(): number {
    return this.sim.time / FPS;
  }

  get won(): boolean {
    return this.sim.won;
  }

  /** Atoms in the cup when the win was seen (at a whole frame, fixed then); null before. */
  get score(): number | null {
    if (!this.sim.won) return null;
    return this.sim.score ?? this.sim.nTrapped;
  }

  /** Every atom has left the cup: nothing can happen but a restart. */
  get allEscaped(): boolean {
    return this.sim.nTrapped === 0 && !this.sim.won;
  }

  /** Why the gas can no longer condense (a message key: lose.*), or null: the core's reach
   * rule (core_out_of_reach) for the slider's lowest rim and the trap asked for. */
  tooFewAtoms(): LoseReason | null {
    return LOSE_REASONS[this.sim.outOfReach(HEIGHT_MIN, this.trapHeight)];
  }
}

/** The reach rule's answers as message keys: lose. and a name of the core's (REACH_NAMES). */
export type LoseReason = `lose.${Exclude<(typeof REACH_NAMES)[number], "within">}`;
/** Each code of the core's reach rule (the physics worker posts it) as its key; null: within.
 * Written out, not built from REACH_NAMES: the page keeps the catalog keys its code quotes. */
export const LOSE_REASONS: ReadonlyArray<LoseReason | null> = [
  null,
  "lose.all_escaped",
  "lose.one_atom",
  "lose.stuck",
  "lose.stuck_here",
];
