/**
 * The applet in the page: the composition root of its rooms, each a file a reader can open
 * alone. The game's clock (play.ts), the panels over the play area (panels.ts), the win and
 * the name box (winscreen.ts, scoring.ts, replays.ts), class mode (classmode.ts), the
 * settings (options.ts), the controls (controls.ts), input (input.ts), the screen's layout
 * (layout.ts), the frame loop (loop.ts), notices (notices.ts), the charts (charts.ts) and
 * the verify panel (verifier.ts). The rooms know one another only through the narrow hosts
 * they declare; none imports this file. Here: the wiring, the actions and the frame.
 */
import { t } from "../i18n";
import { decode } from "../game/replaycode";
import type { Game, GameConfig, SimFactory } from "../game/rules";
import type { Settings } from "../game/settings";
import { emptyAtoms, type AtomArrays } from "../game/sim";
import type { KeyValue } from "../game/store";
import { Condensate } from "../view/condensate";
import { PLAY_RECT, type Layout } from "../view/geometry";
import { drawNotices, type TableCell, type Target } from "../view/overlays";
import { drawReadout } from "../view/readout";
import { Scene, speedText } from "../view/scene";
import { drawText } from "../view/text";
import { HEIGHT_STEP, type Action } from "./bindings";
import { Charts } from "./charts";
import type { Challenge, ClassMode } from "./classmode";
import { Controls, type ControlsHost } from "./controls";
import { KEY_HINTS, TOUCH_HINTS, type Hints } from "./hints";
import { Input, type InputHost } from "./input";
import { Screen, type Zoom } from "./layout";
import { FrameLoop, type Animated } from "./loop";
import { Notices, StatusLine } from "./notices";
import { SettingsEditor } from "./options";
import { Panels, type Overlay, type PanelRooms } from "./panels";
import { Play, type PlayEvents } from "./play";
import type { GameLike } from "./remote";
import { Replays } from "./replays";
import { Scoreboard } from "./scoring";
import { Verifier } from "./verifier";
import { WinScreen, type WinRooms } from "./winscreen";

export { pickTarget } from "./input";
export type { Overlay } from "./panels";

/** The slow-motion line's colour: dark on the play area's grey. */
const SLOW_TEXT = "rgb(30,30,30)";

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
  /** Makes the verify panel's worker (absent or null: the panel replays codes in the page). */
  verifyWorker?: () => Worker | null;
  /** The language of the browser and the address (the language menu's "as the browser"). */
  browserLocale?: string;
}

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

export class App implements Animated, ControlsHost, InputHost, PlayEvents, PanelRooms, WinRooms {
  readonly scene = new Scene();
  readonly condensate = new Condensate();
  readonly charts = new Charts();
  readonly screen: Screen;
  readonly notices: Notices;
  readonly options: SettingsEditor;
  readonly play: Play;
  readonly panels: Panels;
  readonly scores: Scoreboard;
  readonly replays: Replays;
  readonly win: WinScreen;
  readonly verifier: Verifier;
  readonly controls: Controls;
  readonly input: Input;
  readonly loop = new FrameLoop(this);
  /** Class mode (the page served by `evapcool class`), or null. */
  classMode: ClassMode | null = null;
  /** Set by any input: the next frame draws. */
  dirty = true;
  /** The drawn tap targets (last frame), in the panel's own coordinates when zoomed. */
  targets: Target[] = [];
  /** Whether those targets were drawn zoomed with the panels (overlayZoom) or on the scene. */
  targetsZoomed = false;
  /** The tall readout's atom count size as last drawn (logical px; 0: none drawn). */
  readoutSize = 0;
  readonly drawn: DrawnControls = {
    frame: -1,
    trapHeight: 0,
    paused: true,
    speed: 1,
    energy: false,
    overlay: null,
  };
  /** A touch screen (its hints name taps; its buttons are 44 CSS px at least). */
  readonly coarse: boolean;
  private readonly reducedMotion: boolean;
  /** A key was pressed: this touch screen has a keyboard too, so hints name keys. */
  private keyboardSeen = false;
  private readonly ctx: CanvasRenderingContext2D;
  private atoms: AtomArrays = emptyAtoms();
  private readonly statusLine: StatusLine;

  constructor(
    readonly el: Elements,
    opts: AppOptions,
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
    const notify = (text: string) => this.notify(text);
    const say = (text: string) => this.say(text);
    this.notices = new Notices(
      el.live,
      () => this.play?.animTime ?? 0, // notices come before the game does
      () => (this.dirty = true),
    );
    for (const text of opts.notices ?? []) notify(text);
    this.options = new SettingsEditor(
      {
        storage: opts.storage,
        get hints() {
          return app.hints;
        },
        notify,
        say,
        closeOverlay: () => (this.panels.open = null),
        browserLocale: opts.browserLocale ?? "en",
      },
      opts.overrides ?? {},
    );
    this.play = new Play(this, opts, this.options);
    this.replays = new Replays({
      get game() {
        return app.game;
      },
      notify,
    });
    this.scores = new Scoreboard({
      get game() {
        return app.game;
      },
      get hints() {
        return app.hints;
      },
      notAPlayer: (score: number) => this.play.notAPlayer(score),
      storage: opts.storage,
      screen: this.screen,
      nameInput: el.nameInput,
      canvas: el.canvas,
      notify,
      say,
      quiet: () => this.play.quietHeight(),
      focusNext: () => this.controls.focus("restart"),
      showTable: (shown) => (this.panels.open = shown ? "table" : null),
    });
    this.scores.openTable(this.options.runSettings());
    this.win = new WinScreen(this);
    this.verifier = new Verifier(
      {
        screen: this.screen,
        overlayZoom: () => this.overlayZoom(),
        say,
        notify,
        redraw: () => (this.dirty = true),
        makeWorker: () => opts.verifyWorker?.() ?? null,
      },
      el.root,
    );
    this.panels = new Panels(this);
    // The rooms see this applet only as their hosts (the interfaces they declare).
    this.controls = new Controls(this);
    this.input = new Input(this);
    this.controls.build(el.root);
    this.resize();
    this.input.wire();
  }

  // -- what the rooms share, and scripts and tests read (window.evapcool.app) -------------
  get game(): GameLike {
    return this.play.game;
  }

  get fixedSeed(): number | null {
    return this.play.fixedSeed;
  }

  get animTime(): number {
    return this.play.animTime;
  }

  set animTime(s: number) {
    this.play.animTime = s;
  }

  get overlay(): Overlay {
    return this.panels.open;
  }

  get helpSize(): number {
    return this.panels.helpSize;
  }

  get tableCells(): TableCell[] {
    return this.panels.tableCells;
  }

  get layout(): Layout {
    return this.screen.layout;
  }

  /** Hints in the words of the device: taps on a touch screen, keys once a key is pressed. */
  get hints(): Hints {
    return this.coarse && !this.keyboardSeen ? TOUCH_HINTS : KEY_HINTS;
  }

  get canvas(): HTMLCanvasElement {
    return this.el.canvas;
  }

  get nameInput(): HTMLInputElement {
    return this.el.nameInput;
  }

  get autopilotEngaged(): boolean {
    return this.play.autopilotEngaged;
  }

  /** The game was won: the win screen takes it from here. */
  won(): void {
    this.win.won();
  }

  /** The game left the worker for the page's own loop: the frame clock starts again. */
  moved(): void {
    this.loop.resetClock();
    this.dirty = true;
  }

  redraw(): void {
    this.dirty = true;
  }

  /** A key was pressed (touch screens with a keyboard get key hints from now on). */
  keyPressed(): void {
    this.keyboardSeen = true;
  }

  resetClock(): void {
    this.loop.resetClock();
  }

  saveSettings(): void {
    this.options.close(true);
  }

  takeOver(): void {
    this.play.takeOver();
  }

  heightChanged(): void {
    this.play.heightChanged();
  }

  fpsLines(): string[] {
    return this.panels.rateLines();
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

  ready(): Promise<void> {
    return this.play.ready();
  }

  settled(): Promise<void> {
    return this.play.settled();
  }

  // -- what comes from outside: a replay to watch, a class challenge ------------------------
  /** Watch a replay code: its settings and seed, its heights frame by frame (page game). */
  async watch(code: string): Promise<void> {
    try {
      this.play.watch(await decode(code));
    } catch (err) {
      this.notify(t("page.address_bad_replay", { problem: (err as Error).message }));
      return;
    }
    this.restart();
    const rec = this.play.replaying!;
    const won = rec.won ? "yes" : "no";
    this.notify(t("page.watching", { edition: rec.edition, won, n: rec.score }));
  }

  /** Class mode: play this challenge (its settings and seed) from now on. */
  playChallenge(challenge: Challenge): void {
    this.play.playChallenge(challenge);
    this.restart();
    const s = challenge.settings;
    this.notify(t("page.class_challenge", { n: s.n_atoms, radius: s.radius, escape: s.escape }));
  }

  // -- actions -------------------------------------------------------------------------------
  act(action: Action): void {
    const g = this.game;
    const panels = this.panels;
    // Another panel over the settings: they close first, and say if changes were dropped.
    if (panels.open === "settings" && ["help", "table", "clear", "escape"].includes(action))
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
      case "raise":
        this.play.takeOver();
        g.nudgeHeight(action === "lower" ? -HEIGHT_STEP : HEIGHT_STEP);
        this.play.heightChanged();
        break;
      case "step":
        this.play.autopilot?.steer(g);
        g.step();
        break;
      case "autopilot":
        this.play.toggleAutopilot();
        break;
      case "copycode":
        void this.replays.copy();
        break;
      case "faster":
      case "slower":
        if (action === "faster") g.faster();
        else g.slower();
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
        panels.toggle("table");
        this.scores.confirmReset = false;
        break;
      case "clear":
        panels.open = "table";
        this.scores.confirmReset = true;
        this.say(this.hints.confirmClearSpoken);
        break;
      case "next":
        if (this.scores.readyForNext) this.restart();
        break;
      case "settings":
        panels.open = "settings";
        this.options.open();
        break;
      case "fullscreen":
        this.toggleFullscreen();
        break;
      case "help":
      case "verify":
        panels.toggle(action);
        break;
      case "escape":
        if (panels.open !== null) panels.open = null;
        else if (document.fullscreenElement) void document.exitFullscreen().catch(() => {});
        break;
    }
  }

  /** New atoms with the current settings, trap at 400, paused; ends any name entry. */
  restart(): void {
    const s = this.options.runSettings();
    this.play.restart(s);
    this.scores.newGame();
    if (this.panels.open === "table") this.panels.open = null;
    this.charts.reset();
    this.scores.openTable(s);
    this.say(t("page.restarted", { n: this.game.config.nAtoms, height: 400 }));
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

  resize(): void {
    this.dirty = true;
    this.screen.fit(this.charts.shown);
    this.controls.place();
    this.scores.placeNameBox();
    this.verifier.place();
  }

  // -- the frame (the loop's Animated) ---------------------------------------------------------
  start(): void {
    this.loop.start();
  }

  stop(): void {
    this.loop.stop();
  }

  advance(dt: number): void {
    this.play.advance(dt);
  }

  running(): boolean {
    return this.play.running();
  }

  /** The slow-motion line while playing below real time, else null. */
  slowNote(): string | null {
    return this.play.slowNote();
  }

  /** Advance n display frames of one physics frame x speed each, drawing each (tests). */
  runFrames(n: number): Promise<void> {
    return this.play.runFrames(n, () => this.draw());
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
    this.targets = this.win.draw(ctx, this.atoms, this.panels.open !== null);
    this.targetsZoomed = false;
    this.verifier.show(this.panels.open === "verify");
    const panel = this.panels.draw(ctx);
    if (panel) [this.targets, this.targetsZoomed] = [panel.targets, panel.zoomed];
    drawNotices(ctx, this.notices.visible);
    this.charts.draw(ctx, l);
    const slow = this.slowNote();
    if (slow) {
      const [x, y] = [PLAY_RECT.x + PLAY_RECT.w - 8, PLAY_RECT.y + 14];
      drawText(ctx, slow, 20, SLOW_TEXT, x, y, "midright");
    }
    if (this.statusLine.update(g)) this.dirty = true;
    const d = this.drawn;
    d.frame = this.loop.frames;
    d.trapHeight = g.trapHeight;
    d.paused = g.paused;
    d.speed = g.speed;
    d.energy = this.charts.showEnergy;
    d.overlay = this.panels.open;
  }

  /** The atoms, and the condensate fading in over them. */
  private drawScene(ctx: CanvasRenderingContext2D): void {
    const g = this.game;
    const sim = g.sim;
    const fade = this.condensate.update(sim, this.atoms, g.generation, this.play.animTime);
    this.scene.draw(ctx, sceneGame(g), this.atoms, 1 - fade);
    if (fade <= 0) return;
    ctx.save();
    ctx.beginPath();
    ctx.rect(PLAY_RECT.x, PLAY_RECT.y, PLAY_RECT.w, PLAY_RECT.h);
    ctx.clip();
    let r = 0;
    for (let i = 0; i < this.atoms.count; i++) r += this.atoms.radius[i];
    r = this.atoms.count ? r / this.atoms.count : 1;
    const t = this.reducedMotion ? 0 : this.play.animTime;
    this.condensate.draw(ctx, sim, r, t, fade, this.reducedMotion);
    ctx.restore();
  }
}

/** The scene reads only a game's sim and speed, which the worker's game has as the page's. */
function sceneGame(g: GameLike): Game {
  return g as Game;
}
