/**
 * The applet in the page, composed of its rooms: the screen's layout (layout.ts), the
 * controls over the canvas (controls.ts), input (input.ts), the frame loop and its clock
 * (loop.ts), notices and the live region (notices.ts), the settings screen (options.ts),
 * the win and the scores (scoring.ts) and the charts (charts.ts). This file holds the
 * applet's state, its actions and the frame's picture.
 */
import { MIN_TARGET_CSS } from "../view/geometry";
import { ParameterError } from "../limits";
import { ADDRESS_NAMES } from "./params";
import { FPS } from "../game/constants";
import { forceWin, randomSeed, replayGolden } from "../game/engine";
import { NAME_MAX } from "../game/highscores";
import { DEFAULT_CONFIG, Game, type GameConfig, type SimFactory } from "../game/rules";
import type { Settings } from "../game/settings";
import { emptyAtoms, type AtomArrays } from "../game/sim";
import type { KeyValue } from "../game/store";
import { Condensate } from "../view/condensate";
import { PLAY_RECT, type Layout } from "../view/geometry";
import {
  drawHelp,
  drawMessageButtons,
  drawNameFrame,
  drawNotices,
  drawSettings,
  drawVerify,
  drawTable,
  type TableCell,
  type Target,
} from "../view/overlays";
import { drawReadout } from "../view/readout";
import { Scene, speedText } from "../view/scene";
import { drawText } from "../view/text";
import { Autopilot } from "../game/autopilot";
import { helpRows, HEIGHT_STEP, type Action } from "./bindings";
import { KEY_HINTS, TOUCH_HINTS, type Hints } from "./hints";
import { Charts } from "./charts";
import { Controls } from "./controls";
import { Input } from "./input";
import { Screen, type Zoom } from "./layout";
import { FrameLoop, type Animated } from "./loop";
import { Notices, StatusLine } from "./notices";
import { configFor, SettingsEditor } from "./options";
import { PaceMeter } from "./pace";
import { RemoteGame, type GameLike } from "./remote";
import { Replays } from "./replays";
import { heightsOf } from "../game/moves";
import { configOf, type Recording, type ReplaySettings } from "../game/replay";
import type { Challenge, ClassMode } from "./classmode";
import { decode } from "../game/replaycode";
import { PASTE_BOX, Verifier } from "./verifier";
import { describeRun, Scoreboard } from "./scoring";
import { formatFixed, t } from "../i18n";

export { pickTarget } from "./input";

/** The slow-motion line's colour: dark on the play area's grey. */
const SLOW_TEXT = "rgb(30,30,30)";
/** Wait this long after the last trap move before speaking the height, ms. */
const HEIGHT_SPEECH_MS = 400;

export interface Elements {
  root: HTMLElement;
  canvas: HTMLCanvasElement;
  live: HTMLElement;
  status: HTMLElement;
  nameInput: HTMLInputElement;
}

export interface AppOptions {
  factory: SimFactory;
  storage: KeyValue;
  /** Settings for this visit from the address (not saved), and their notices. */
  overrides?: Partial<Settings>;
  config?: Partial<GameConfig>;
  notices?: string[];
  /** The physics worker to play in (absent: the page's own loop plays). */
  worker?: Worker | null;
  /** Makes the verify panel's worker (absent: the panel replays codes in the page). */
  verifyWorker?: () => Worker;
  /** The language of the browser and the address (the language menu's "as the browser"). */
  browserLocale?: string;
}

export type Overlay = null | "help" | "table" | "settings" | "verify";

/** What the last drawn frame showed of the controls (tests count frames from a key to it). */
export interface DrawnControls {
  /** The display frame (FrameLoop.frames) it was drawn in. */
  frame: number;
  trapHeight: number;
  paused: boolean;
  speed: number;
  energy: boolean;
  overlay: Overlay;
}

export class App implements Animated {
  /** The game: in the physics worker, or the page's own (no worker, or it failed). */
  game: GameLike;
  readonly pace = new PaceMeter();
  readonly scene = new Scene();
  readonly condensate = new Condensate();
  readonly charts = new Charts();
  readonly screen: Screen;
  readonly notices: Notices;
  readonly options: SettingsEditor;
  readonly scores: Scoreboard;
  readonly replays: Replays;
  readonly verifier: Verifier;
  /** Class mode (the page served by `evapcool class`), or null. */
  classMode: ClassMode | null = null;
  /** The seed every game plays (the address's ?seed=, a class challenge's), or null: a
   * fresh one each game. Games always get an explicit seed, so each can be recorded. */
  fixedSeed: number | null;
  readonly controls = new Controls(this);
  readonly input = new Input(this);
  readonly loop = new FrameLoop(this);
  private readonly statusLine: StatusLine;
  overlay: Overlay = null;
  /** The applet's clock (s): notices and the condensate's animation. */
  animTime = 0;
  /** Set by any input: the next frame draws. */
  dirty = true;
  /** The drawn panels' tap targets, in the panel's own coordinates (last frame drawn). */
  targets: Target[] = [];
  /** The score table's words and where they were drawn (the last table drawn). */
  tableCells: TableCell[] = [];
  /** The help's row size as last drawn (logical px; tests check it is legible). */
  helpSize = 0;
  /** The tall readout's atom count size as last drawn (logical px; 0: none drawn). */
  readoutSize = 0;
  /** Whether those targets were drawn zoomed with the panels (overlayZoom) or on the scene. */
  targetsZoomed = false;
  readonly drawn: DrawnControls = {
    frame: -1,
    trapHeight: 0,
    paused: true,
    speed: 1,
    energy: false,
    overlay: null,
  };
  private ctx: CanvasRenderingContext2D;
  private atoms: AtomArrays = emptyAtoms();
  private lastHeightSpoken = 400;
  private heightTimer: ReturnType<typeof setTimeout> | null = null;
  private saidTooFew: string | null = null;
  private saidSlow: string | null = null;
  private readonly reducedMotion: boolean;
  private readonly coarse: boolean;
  /** A key was pressed: this touch screen has a keyboard too, so hints name keys. */
  private keyboardSeen = false;
  /** The autopilot (key A or its wheel button): the demo strategy, made on first use. */
  autopilot: Autopilot | null = null;

  constructor(
    readonly el: Elements,
    private readonly opts: AppOptions,
  ) {
    const app = this;
    const ctx = el.canvas.getContext("2d", { alpha: false });
    if (!ctx) throw new Error("this browser cannot draw on a canvas");
    this.ctx = ctx;
    const mq = (q: string) => typeof matchMedia === "function" && matchMedia(q).matches;
    this.reducedMotion = mq("(prefers-reduced-motion: reduce)");
    this.coarse = mq("(pointer: coarse)");
    this.screen = new Screen(el.canvas);
    this.statusLine = new StatusLine(el.status);
    this.notices = new Notices(
      el.live,
      () => this.animTime,
      () => (this.dirty = true),
    );
    for (const text of opts.notices ?? []) this.notify(text);
    this.fixedSeed = opts.config?.seed ?? null;
    this.replays = new Replays({
      get game() {
        return app.game;
      },
      notify: (t) => this.notify(t),
    });
    this.options = new SettingsEditor(
      {
        storage: opts.storage,
        get hints() {
          return app.hints;
        },
        notify: (t) => this.notify(t),
        say: (t) => this.say(t),
        closeOverlay: () => (this.overlay = null),
        browserLocale: opts.browserLocale ?? "en",
      },
      opts.overrides ?? {},
    );
    this.game = this.firstGame();
    this.scores = new Scoreboard({
      get game() {
        return app.game;
      },
      get hints() {
        return app.hints;
      },
      notAPlayer: (score: number) => this.notAPlayer(score),
      storage: opts.storage,
      screen: this.screen,
      nameInput: el.nameInput,
      canvas: el.canvas,
      notify: (t) => this.notify(t),
      say: (t) => this.say(t),
      quiet: () => this.quietHeight(),
      focusNext: () => this.controls.focus("restart"),
      showTable: (shown) => (this.overlay = shown ? "table" : null),
    });
    this.scores.openTable(this.options.runSettings());
    this.verifier = new Verifier(
      {
        screen: this.screen,
        overlayZoom: () => this.overlayZoom(),
        say: (t) => this.say(t),
        notify: (t) => this.notify(t),
        redraw: () => (this.dirty = true),
        makeWorker: () => opts.verifyWorker?.() ?? null,
      },
      el.root,
    );
    this.controls.build(el.root);
    this.resize();
    this.input.wire();
  }

  /** The first game: the address's settings, or the saved ones if the physics refuses those. */
  private firstGame(): GameLike {
    const options = this.options;
    try {
      return this.makeGame(configFor(options.runSettings()));
    } catch (err) {
      if (!(err instanceof RangeError) || !Object.keys(options.overrides).length) throw err;
      const line = err instanceof ParameterError ? err.render(ADDRESS_NAMES) : err.message;
      this.notify(t("page.address_saved_settings", { problem: line }));
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
        won: () => this.won(),
        failed: (message) => this.workerFailed(message),
      });
    return this.pageGame(config);
  }

  private pageGame(config: GameConfig): Game {
    const game = new Game(this.opts.factory, config);
    game.onWin.push(() => this.won());
    return game;
  }

  /** A recording being watched (?replay=CODE), played again by each restart. */
  replaying: Recording | null = null;
  /** The class challenge played (class mode): its settings at every restart. */
  challengeSettings: ReplaySettings | null = null;

  /** Class mode: play this challenge (its settings and seed) from now on. */
  playChallenge(challenge: Challenge): void {
    this.challengeSettings = challenge.settings;
    this.fixedSeed = challenge.seed;
    this.restart();
    const s = challenge.settings;
    this.notify(t("page.class_challenge", { n: s.n_atoms, radius: s.radius, escape: s.escape }));
  }

  /** The win's notice when the autopilot or a replay won (never a player's score). */
  private notAPlayer(score: number): string | null {
    if (this.replaying) return t("page.replay_won", { n: score, claimed: this.replaying.score });
    if (this.challengeSettings) return t("page.class_won", { n: score });
    const pilot = this.autopilot;
    if (pilot?.flew)
      return t("page.autopilot_won", {
        name: t("autopilot.label", { name: pilot.name }),
        n: score,
      });
    return null;
  }

  /** Watch a replay code: its settings and seed, its heights frame by frame (page game). */
  async watch(code: string): Promise<void> {
    let rec: Recording;
    try {
      rec = await decode(code);
    } catch (err) {
      this.notify(t("page.address_bad_replay", { problem: (err as Error).message }));
      return;
    }
    this.replaying = rec;
    this.fixedSeed = rec.seed;
    this.restart();
    const won = rec.won ? "yes" : "no";
    this.notify(t("page.watching", { edition: rec.edition, won, n: rec.score }));
  }

  /** The replay's heights from the start of this game (a watched replay only). */
  private playBack(): void {
    const rec = this.replaying;
    if (!rec || !(this.game instanceof Game)) return;
    this.game.playback(heightsOf(rec.moves));
  }

  /** The seed of the next game. */
  freshSeed(): number {
    return this.fixedSeed ?? randomSeed();
  }

  /** A win: the scores (name or not), and the game's replay code. */
  private won(): void {
    this.scores.onWin();
    void this.replays.onWin().catch((err: unknown) => {
      console.warn(`evapcool: no replay code for this game (${(err as Error).message})`);
    });
  }

  /** The worker stopped: the same game's settings go on in the page's own loop. */
  private workerFailed(message: string): void {
    if (!(this.game instanceof RemoteGame)) return;
    console.warn(`evapcool: the physics worker failed (${message}); playing without it.`);
    const remote = this.game;
    remote.stop();
    this.opts.worker = null;
    this.game = this.pageGame(remote.config);
    this.loop.resetClock();
    this.dirty = true;
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

  // -- what the rooms share ---------------------------------------------------------------
  /** Hints in the words of the device: taps on a touch screen, keys once a key is pressed. */
  get hints(): Hints {
    return this.coarse && !this.keyboardSeen ? TOUCH_HINTS : KEY_HINTS;
  }

  /** A key was pressed (touch screens with a keyboard get key hints from now on). */
  keyPressed(): void {
    this.keyboardSeen = true;
  }

  get autopilotEngaged(): boolean {
    return this.autopilot?.engaged ?? false;
  }

  /** The player touched the trap: the autopilot lets go (and says so). */
  takeOver(): void {
    if (!this.autopilot?.engaged) return;
    this.autopilot.takeOver();
    this.notify(this.hints.youHaveTheTrap);
  }

  /** Key A or the wheel: the demo autopilot takes the trap, or hands it back. */
  private toggleAutopilot(): void {
    if (this.game.won) return;
    if (this.autopilot?.engaged) {
      this.takeOver();
      return;
    }
    this.autopilot ??= Autopilot.demo();
    this.autopilot.engage();
    this.autopilot.steer(this.game);
    this.notify(this.hints.autopilotPlays(this.autopilot.name));
  }

  get layout(): Layout {
    return this.screen.layout;
  }

  notify(text: string): void {
    this.notices.notify(text);
  }

  say(text: string): void {
    this.notices.say(text);
  }

  overlayZoom(): Zoom {
    return this.screen.overlayZoom();
  }

  // -- actions -------------------------------------------------------------------------------
  act(action: Action): void {
    const g = this.game;
    // Another panel over the settings: they close first, and say if changes were dropped.
    if (this.overlay === "settings" && ["help", "table", "clear", "escape"].includes(action))
      this.options.close(false);
    switch (action) {
      case "pause":
        g.togglePause();
        this.say(t(g.paused ? "page.paused" : "page.playing"));
        break;
      case "restart":
        this.restart();
        break;
      case "lower":
        this.takeOver();
        g.nudgeHeight(-HEIGHT_STEP);
        this.heightChanged();
        break;
      case "raise":
        this.takeOver();
        g.nudgeHeight(HEIGHT_STEP);
        this.heightChanged();
        break;
      case "step":
        this.autopilot?.steer(g);
        g.step();
        break;
      case "autopilot":
        this.toggleAutopilot();
        break;
      case "copycode":
        void this.replays.copy();
        break;
      case "verify":
        this.toggleOverlay("verify");
        break;
      case "faster":
        g.faster();
        this.say(t("page.speed_spoken", { speed: speedText(g.speed) }));
        break;
      case "slower":
        g.slower();
        this.say(t("page.speed_spoken", { speed: speedText(g.speed) }));
        break;
      case "energy":
        this.charts.showEnergy = !this.charts.showEnergy;
        this.resize();
        this.say(t(this.charts.showEnergy ? "page.energy_shown" : "page.energy_hidden"));
        break;
      case "path":
        this.charts.showPath = !this.charts.showPath;
        this.resize();
        this.say(t(this.charts.showPath ? "page.path_shown" : "page.path_hidden"));
        break;
      case "table":
        this.toggleOverlay("table");
        this.scores.confirmReset = false;
        break;
      case "clear":
        this.overlay = "table";
        this.scores.confirmReset = true;
        this.say(this.hints.confirmClearSpoken);
        break;
      case "next":
        if (this.scores.readyForNext) this.restart();
        break;
      case "settings":
        this.overlay = "settings";
        this.options.open();
        break;
      case "fullscreen":
        this.toggleFullscreen();
        break;
      case "help":
        this.toggleOverlay("help");
        break;
      case "escape":
        if (this.overlay !== null) this.overlay = null;
        else if (document.fullscreenElement) void document.exitFullscreen().catch(() => {});
        break;
    }
  }

  private toggleOverlay(name: Exclude<Overlay, null>): void {
    this.overlay = this.overlay === name ? null : name;
    const titles = {
      help: "help.title",
      table: "scores.title",
      settings: "settings.title",
      verify: "verify.title",
    };
    if (this.overlay === name) this.say(t("page.panel_shown", { panel: t(titles[name]) }));
  }

  /** New atoms with the current settings, trap at 400, paused; ends any name entry. */
  restart(): void {
    const s = this.options.runSettings();
    try {
      const forced = this.replaying?.settings ?? this.challengeSettings;
      const settings = forced ? configOf(forced, this.fixedSeed ?? 0) : configFor(s);
      this.game.restart({ ...this.game.config, ...settings, seed: this.freshSeed() });
    } catch (err) {
      this.notify(t("notice.settings_failed", { problem: (err as Error).message }));
      this.game.restart();
    }
    this.scores.newGame();
    this.autopilot?.newGame();
    this.autopilot?.steer(this.game);
    this.playBack();
    if (this.overlay === "table") this.overlay = null;
    this.charts.reset();
    this.scores.openTable(s);
    this.say(t("page.restarted", { n: this.game.config.nAtoms, height: 400 }));
  }

  heightChanged(): void {
    // Speak the height once the player stops moving it, not at every step.
    this.quietHeight();
    this.heightTimer = setTimeout(() => {
      const h = Math.round(this.game.trapHeight);
      if (h !== this.lastHeightSpoken) this.say(t("page.height_spoken", { h }));
      this.lastHeightSpoken = h;
    }, HEIGHT_SPEECH_MS);
  }

  /** Drop a trap height still waiting to be spoken. */
  private quietHeight(): void {
    if (this.heightTimer !== null) clearTimeout(this.heightTimer);
    this.heightTimer = null;
  }

  toggleFullscreen(): void {
    if (document.fullscreenElement) {
      void document.exitFullscreen().catch(() => {});
    } else if (document.documentElement.requestFullscreen) {
      document.documentElement.requestFullscreen().catch((err: unknown) => {
        this.notify(t("page.fullscreen_refused", { problem: (err as Error).message }));
      });
    } else {
      this.notify(t("notice.fullscreen_unavailable"));
    }
  }

  // -- layout ---------------------------------------------------------------------------------
  resize(): void {
    this.dirty = true;
    this.screen.fit(this.charts.shown);
    this.controls.place();
    this.scores.placeNameBox();
    this.verifier.place();
  }

  // -- the frame ------------------------------------------------------------------------------
  start(): void {
    this.loop.start();
  }

  stop(): void {
    this.loop.stop();
  }

  advance(dt: number): void {
    const g = this.game;
    this.autopilot?.steer(g); // the trap for this frame, from the gas as it is now
    g.update(dt);
    this.animTime += Math.min(dt, 0.25);
    this.pace.add(performance.now(), g.sim.time, g.speed, !g.paused, `${g.speed}|${g.generation}`);
    const note = this.slowNote();
    if (note !== this.saidSlow) {
      this.saidSlow = note;
      if (note) this.say(note);
    }
  }

  /** The slow-motion line while playing below real time, else null. */
  slowNote(): string | null {
    return this.game.paused ? null : this.pace.note();
  }

  /**
   * What the picture depends on besides input (every input event marks it dirty): while
   * this stays the same, a frame draws nothing (a paused applet costs no battery). ""
   * means animated: draw every frame.
   */
  pictureKey(): string {
    const g = this.game;
    const c = this.condensate.level;
    if ((g.won && !this.reducedMotion) || (c > 0 && c < 1)) return "";
    const l = this.layout;
    const cv = this.el.canvas;
    return [
      g.generation,
      g.sim.time,
      g.trapHeight,
      g.paused,
      g.speed,
      this.notices.visible.length,
      l.scale,
      l.offsetX,
      l.offsetY,
      l.width,
      l.height,
      cv.width,
      cv.height,
    ].join("|");
  }

  /** Advance n display frames of one physics frame x speed each, drawing each (tests). */
  async runFrames(n: number): Promise<void> {
    const g = this.game;
    for (let k = 0; k < n; k++) {
      this.autopilot?.steer(g);
      if (g instanceof RemoteGame) await g.runFrames(1);
      else (g as Game).runFrames(1);
      this.animTime += 1 / FPS;
      this.draw();
    }
  }

  /** n physics frames at once, not drawn between (benchmarks); the page's own game draws none. */
  physicsFrames(n: number): Promise<void> {
    const g = this.game;
    if (g instanceof RemoteGame) return g.runFrames(n);
    (g as Game).runFrames(n);
    return Promise.resolve();
  }

  /** Resolves once the worker (if any) has applied all input so far and posted the result. */
  settled(): Promise<void> {
    return this.game instanceof RemoteGame ? this.game.settled() : Promise.resolve();
  }

  draw(): void {
    const ctx = this.ctx;
    const l = this.layout;
    const g = this.game;
    const sim = g.sim;
    this.atoms = sim.trapped();
    this.charts.record(sim, this.atoms, g.generation);
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = "rgb(0,0,0)";
    ctx.fillRect(0, 0, this.el.canvas.width, this.el.canvas.height);
    const dpr = this.screen.dpr;
    const s = l.scale * dpr;
    ctx.setTransform(s, 0, 0, s, Math.round(l.offsetX * dpr), Math.round(l.offsetY * dpr));
    this.scene.deviceScale = s;
    this.drawScene(ctx);
    this.scene.drawFrame(ctx, sceneGame(g), l.sceneHeight, 16 / l.scale);
    this.controls.draw(ctx);
    this.readoutSize = l.readout ? drawReadout(ctx, l.readout, sim) : 0;
    this.drawMessages(ctx);
    this.verifier.show(this.overlay === "verify");
    this.drawOverlay(ctx);
    drawNotices(ctx, this.notices.visible);
    this.charts.draw(ctx, l);
    const slow = this.slowNote();
    if (slow)
      drawText(
        ctx,
        slow,
        20,
        SLOW_TEXT,
        PLAY_RECT.x + PLAY_RECT.w - 8,
        PLAY_RECT.y + 14,
        "midright",
      );
    if (this.statusLine.update(g)) this.dirty = true;
    const d = this.drawn;
    d.frame = this.loop.frames;
    d.trapHeight = g.trapHeight;
    d.paused = g.paused;
    d.speed = g.speed;
    d.energy = this.charts.showEnergy;
    d.overlay = this.overlay;
  }

  /** The atoms, and the condensate fading in over them. */
  private drawScene(ctx: CanvasRenderingContext2D): void {
    const g = this.game;
    const sim = g.sim;
    const fade = this.condensate.update(sim, this.atoms, g.generation, this.animTime);
    this.scene.draw(ctx, sceneGame(g), this.atoms, 1 - fade);
    if (fade <= 0) return;
    ctx.save();
    ctx.beginPath();
    ctx.rect(PLAY_RECT.x, PLAY_RECT.y, PLAY_RECT.w, PLAY_RECT.h);
    ctx.clip();
    let r = 0;
    for (let i = 0; i < this.atoms.count; i++) r += this.atoms.radius[i];
    r = this.atoms.count ? r / this.atoms.count : 1;
    const t = this.reducedMotion ? 0 : this.animTime;
    this.condensate.draw(ctx, sim, r, t, fade, this.reducedMotion);
    ctx.restore();
  }

  /** The score, the too-few message or the start hint, and the name box's frame. */
  private drawMessages(ctx: CanvasRenderingContext2D): void {
    const g = this.game;
    const tooFew = g.score === null ? g.tooFewAtoms(this.lightestMass()) : null;
    if (g.score !== null) this.scene.drawScore(ctx, g.score);
    else if (tooFew !== null) {
      this.scene.drawTooFew(ctx, t(tooFew), this.hints.tooFewLine);
      if (tooFew !== this.saidTooFew) this.say(this.hints.tooFewSpoken(tooFew));
    } else if (g.paused && g.sim.time === 0 && this.overlay === null) {
      this.scene.drawStartHint(ctx, this.coarse);
    }
    this.targets = [];
    this.targetsZoomed = false;
    this.saidTooFew = tooFew;
    if (g.won && this.replays.current && !this.scores.nameBoxOpen && this.overlay === null) {
      const h = this.coarse ? Math.max(34, MIN_TARGET_CSS / this.layout.scale) : 34;
      this.targets = drawMessageButtons(ctx, [[t("page.copy_code"), "copycode"]], h);
    }
    if (this.scores.nameBoxOpen)
      this.targets = drawNameFrame(
        ctx,
        t("win.top10"),
        this.scores.nameLength(),
        NAME_MAX,
        this.coarse,
        this.coarse ? Math.max(34, MIN_TARGET_CSS / this.layout.scale) : 34,
      );
  }

  /** Help, scores or settings over the play area (zoomed in the tall layout). */
  private drawOverlay(ctx: CanvasRenderingContext2D): void {
    if (this.overlay === "help") {
      // Over the whole screen: a projector's black bands hold larger text, a phone's rows
      // wrap at 16 CSS px or more.
      const box = this.screen.visibleBox(12);
      const help = drawHelp(ctx, helpRows(), this.fpsLines(), box, 16 / this.layout.scale);
      this.targets = help.targets;
      this.helpSize = help.size;
      return;
    }
    const zoom = this.overlayZoom();
    ctx.save();
    ctx.translate(zoom.x, zoom.y);
    ctx.scale(zoom.k, zoom.k);
    ctx.translate(-zoom.cx, -zoom.cy);
    if (this.overlay !== null) this.targetsZoomed = true;
    if (this.overlay === "table") {
      const table = drawTable(
        ctx,
        t("page.table_for", { run: describeRun(this.options.runSettings()) }),
        this.scores.table.entries,
        this.scores.storedRank,
        this.scores.footer(),
        this.scores.buttons(),
      );
      this.targets = table.targets;
      this.tableCells = table.cells;
    } else if (this.overlay === "verify") {
      const h = this.coarse ? Math.max(34, MIN_TARGET_CSS / this.layout.scale) : 34;
      const v = this.verifier;
      this.targets = drawVerify(ctx, PASTE_BOX, v.lines(), v.busy, h);
    } else if (this.overlay === "settings") {
      const o = this.options;
      this.targets = drawSettings(ctx, o.rows(), o.row, o.footer());
    }
    ctx.restore();
  }

  /** The display rate while playing (paused frames are not counted) and the game's pace. */
  private fpsLines(): string[] {
    const st = this.loop.playStats.summary();
    const atoms = t("status.atoms", { n: this.game.sim.nTrapped });
    if (st.frames < 2) return [t("page.rate_later", { atoms })];
    const fps = Math.round(st.fps);
    const ms = formatFixed(st.medianMs, 1);
    const pace = this.pace.pace;
    const paceLine =
      pace >= 0.98 ? t("page.real_time") : t("page.too_slow", { pace: formatFixed(pace, 2) });
    return [t("page.rate", { fps, ms, atoms }), paceLine];
  }

  /** Whether the game is playing (the loop counts only these frames for the display rate). */
  running(): boolean {
    return !this.game.paused && !this.game.won;
  }

  /** The lightest trapped atom's mass (the escape energy of the too-few rule). */
  private lightestMass(): number {
    const a = this.atoms;
    let m = Infinity;
    for (let i = 0; i < a.count; i++) m = Math.min(m, a.mass[i]);
    return Number.isFinite(m) ? m : 1;
  }
}

/** The scene reads only a game's sim and speed, which the worker's game has as the page's. */
function sceneGame(g: GameLike): Game {
  return g as Game;
}
