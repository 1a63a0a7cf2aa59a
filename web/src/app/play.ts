/**
 * The game's clock: the game played (in the physics worker, or the page's own when there is
 * none or it failed), its seed and what forces its settings (a watched replay, a class
 * challenge), the autopilot, the trap height's speech, and advancing it all by the display
 * frames' wall time (the applet's own clock for notices and animations, and its pace).
 */
import { ParameterError } from "../limits";
import { FPS } from "../game/engine";
import { Autopilot } from "../game/autopilot";
import { forceWin, randomSeed, replayGolden } from "../game/engine";
import { configOf, type Recording, type ReplaySettings } from "../game/replay";
import { DEFAULT_CONFIG, Game, type GameConfig, type SimFactory } from "../game/rules";
import type { Settings } from "../game/settings";
import { t } from "../i18n";
import type { Challenge } from "./classmode";
import type { Hints } from "./hints";
import { configFor, type SettingsEditor } from "./options";
import { PaceMeter } from "./pace";
import { ADDRESS_NAMES } from "./params";
import { RemoteGame, type GameLike } from "../runtime/remote";

/** Wait this long after the last trap move before speaking the height, ms. */
const HEIGHT_SPEECH_MS = 400;

export interface PlayOptions {
  factory: SimFactory;
  config?: Partial<GameConfig>;
  /** The physics worker to play in (absent: the page's own loop plays). */
  worker?: Worker | null;
}

/** What the game tells the page around it. */
export interface PlayEvents {
  readonly hints: Hints;
  notify(text: string): void;
  say(text: string): void;
  /** The game was won (the win screen takes it from here). */
  won(): void;
  /** The game left the worker for the page's own loop (the frame clock starts again). */
  moved(): void;
}

export class Play {
  /** The game: in the physics worker, or the page's own (no worker, or it failed). */
  game: GameLike;
  readonly pace = new PaceMeter();
  /** The applet's clock (s): notices and the condensate's animation. */
  animTime = 0;
  /** The seed every game plays (the address's ?seed=, a class challenge's, a replay's), or
   * null: a fresh one each game. Games always get an explicit seed, so each can be recorded. */
  fixedSeed: number | null;
  /** A recording being watched (?replay=CODE), played again by each restart. */
  replaying: Recording | null = null;
  /** The class challenge played (class mode): its settings at every restart. */
  challengeSettings: ReplaySettings | null = null;
  /** The autopilot (key A or its wheel button): the demo strategy, made on first use. */
  autopilot: Autopilot | null = null;
  private lastHeightSpoken = 400;
  private heightTimer: ReturnType<typeof setTimeout> | null = null;
  private saidSlow: string | null = null;

  constructor(
    private readonly events: PlayEvents,
    private readonly opts: PlayOptions,
    options: SettingsEditor,
  ) {
    this.fixedSeed = opts.config?.seed ?? null;
    this.game = this.firstGame(options);
  }

  /** The first game: the address's settings, or the saved ones if the physics refuses those. */
  private firstGame(options: SettingsEditor): GameLike {
    try {
      return this.makeGame(configFor(options.runSettings()));
    } catch (err) {
      if (!(err instanceof RangeError) || !Object.keys(options.overrides).length) throw err;
      const line = err instanceof ParameterError ? err.render(ADDRESS_NAMES) : err.message;
      this.events.notify(t("page.address_saved_settings", { problem: line }));
      options.overrides = {};
      return this.makeGame(configFor(options.runSettings()));
    }
  }

  /** A game in the worker if there is one, else on the page (RangeError if refused). */
  private makeGame(settings: Partial<GameConfig>): GameLike {
    const config = { ...DEFAULT_CONFIG, ...this.opts.config, ...settings, seed: this.freshSeed() };
    const worker = this.opts.worker;
    if (worker)
      return new RemoteGame(worker, this.opts.factory, config, {
        won: () => this.events.won(),
        failed: (message) => this.workerFailed(message),
      });
    return this.pageGame(config);
  }

  private pageGame(config: GameConfig): Game {
    const game = new Game(this.opts.factory, config);
    game.onWin.push(() => this.events.won());
    return game;
  }

  /** The worker stopped: the same game's settings go on in the page's own loop. */
  private workerFailed(message: string): void {
    if (!(this.game instanceof RemoteGame)) return;
    console.warn(`evapcool: the physics worker failed (${message}); playing without it.`);
    const remote = this.game;
    remote.stop();
    this.opts.worker = null;
    this.game = this.pageGame(remote.config);
    this.events.moved();
  }

  /** The seed of the next game. */
  freshSeed(): number {
    return this.fixedSeed ?? randomSeed();
  }

  /** Play this recording's settings, seed and heights from the next restart on. */
  watch(rec: Recording): void {
    this.replaying = rec;
    this.fixedSeed = rec.seed;
  }

  /** Class mode: play this challenge's settings and seed from the next restart on. */
  playChallenge(challenge: Challenge): void {
    this.challengeSettings = challenge.settings;
    this.fixedSeed = challenge.seed;
  }

  /** New atoms with these settings (or the replay's, the challenge's), trap at 400, paused. */
  restart(s: Settings): void {
    try {
      const forced = this.replaying?.settings ?? this.challengeSettings;
      const settings = forced ? configOf(forced, this.fixedSeed ?? 0) : configFor(s);
      this.game.restart({ ...this.game.config, ...settings, seed: this.freshSeed() });
    } catch (err) {
      this.events.notify(t("notice.settings_failed", { problem: (err as Error).message }));
      this.game.restart();
    }
    this.autopilot?.newGame();
    this.autopilot?.steer(this.game);
    // A watched replay's heights from the start of this game (the page's own game).
    const rec = this.replaying;
    if (rec && this.game instanceof Game) this.game.playback(rec.moves);
  }

  /** The win's notice when the autopilot or a replay won (never a player's score). */
  notAPlayer(score: number): string | null {
    if (this.replaying) return t("page.replay_won", { n: score, claimed: this.replaying.score });
    // Class mode: the class bar tells what became of the game (not over the condensate).
    if (this.challengeSettings) return "";
    const pilot = this.autopilot;
    if (pilot?.flew)
      return t("page.autopilot_won", {
        name: t("autopilot.label", { name: pilot.name }),
        n: score,
      });
    return null;
  }

  // -- the autopilot and the trap -----------------------------------------------------------
  get autopilotEngaged(): boolean {
    return this.autopilot?.engaged ?? false;
  }

  /** The player touched the trap: the autopilot lets go (and says so). */
  takeOver(): void {
    if (!this.autopilot?.engaged) return;
    this.autopilot.takeOver();
    this.events.notify(this.events.hints.youHaveTheTrap);
  }

  /** Key A or the wheel: the demo autopilot takes the trap, or hands it back. */
  toggleAutopilot(): void {
    if (this.game.won) return;
    if (this.autopilot?.engaged) {
      this.takeOver();
      return;
    }
    this.autopilot ??= Autopilot.demo();
    this.autopilot.engage();
    this.autopilot.steer(this.game);
    this.events.notify(this.events.hints.autopilotPlays(this.autopilot.name));
  }

  /** The trap was moved by hand: its height is spoken once the player stops moving it. */
  heightChanged(): void {
    this.quietHeight();
    this.heightTimer = setTimeout(() => {
      const h = Math.round(this.game.trapHeight);
      if (h !== this.lastHeightSpoken) this.events.say(t("page.height_spoken", { h }));
      this.lastHeightSpoken = h;
    }, HEIGHT_SPEECH_MS);
  }

  /** Drop a trap height still waiting to be spoken. */
  quietHeight(): void {
    if (this.heightTimer !== null) clearTimeout(this.heightTimer);
    this.heightTimer = null;
  }

  // -- the clock -------------------------------------------------------------------------
  /** One display frame of dt seconds of wall clock. */
  advance(dt: number): void {
    const g = this.game;
    this.autopilot?.steer(g); // the trap for this frame, from the gas as it is now
    g.update(dt);
    this.animTime += Math.min(dt, 0.25);
    this.pace.add(performance.now(), g.sim.time, g.speed, !g.paused, `${g.speed}|${g.generation}`);
    const note = this.slowNote();
    if (note !== this.saidSlow) {
      this.saidSlow = note;
      if (note) this.events.say(note);
    }
  }

  /** The slow-motion line while playing below real time, else null. */
  slowNote(): string | null {
    return this.game.paused ? null : this.pace.note();
  }

  /** Whether the game is playing (the loop counts only these frames for the display rate). */
  running(): boolean {
    return !this.game.paused && !this.game.won;
  }

  /** Advance n display frames of one physics frame x speed each, drawing each (tests). */
  async runFrames(n: number, draw: () => void): Promise<void> {
    const g = this.game;
    for (let k = 0; k < n; k++) {
      this.autopilot?.steer(g);
      if (g instanceof RemoteGame) await g.runFrames(1);
      else (g as Game).runFrames(1);
      this.animTime += 1 / FPS;
      draw();
    }
  }

  /** n physics frames at once, not drawn between (benchmarks); the page's own game draws none. */
  physicsFrames(n: number): Promise<void> {
    const g = this.game;
    if (g instanceof RemoteGame) return g.runFrames(n);
    (g as Game).runFrames(n);
    return Promise.resolve();
  }

  // -- where the physics runs --------------------------------------------------------------
  /** Resolves once the worker (if any) has applied all input so far and posted the result. */
  settled(): Promise<void> {
    return this.game instanceof RemoteGame ? this.game.settled() : Promise.resolve();
  }

  /** Resolves once the game has a first state to draw (the worker's first frame). */
  ready(): Promise<void> {
    return this.game instanceof RemoteGame ? this.game.ready() : Promise.resolve();
  }

  /** The physics' own switch to the won state (tests of the condensate). */
  forceWin(): Promise<void> {
    const g = this.game;
    if (g instanceof RemoteGame) return g.forceWin();
    forceWin(g.sim);
    return Promise.resolve();
  }

  /** A golden trace's text replayed by the engine the game plays with (tests). */
  replay(text: string): Promise<string> {
    const g = this.game;
    return g instanceof RemoteGame ? g.replay(text) : Promise.resolve(replayGolden(text));
  }

  /** The worker's ms spent on the physics for its newest frame (NaN without a worker). */
  get physicsMs(): number {
    const g = this.game;
    return g instanceof RemoteGame ? g.physicsMs : NaN;
  }

  /** "worker" or "page": where the physics runs. */
  get engine(): string {
    return this.game instanceof RemoteGame ? "worker" : "page";
  }
}
