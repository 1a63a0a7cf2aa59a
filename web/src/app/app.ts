/**
 * The applet in the page: the composition root of its rooms, each a file a reader can open
 * alone. The game's clock (play.ts), the panels over the play area (panels.ts), the win and
 * the name box (winscreen.ts, scoring.ts, replays.ts), class mode (classmode.ts), what each
 * action does (actions.ts), the frame's picture (picture.ts), the settings (options.ts),
 * the controls (controls.ts), input (input.ts), the screen's layout (layout.ts), the frame
 * loop (loop.ts), notices (notices.ts), the charts (charts.ts) and the verify panel
 * (verifier.ts). Each room declares the host it needs; this applet is that host, and no
 * room imports this file. Here: the wiring, and what a restart, a resize, a watched replay
 * and a class challenge change across rooms.
 */
import { t } from "../i18n";
import { decode } from "../game/replaycode";
import type { GameConfig, SimFactory } from "../game/rules";
import type { Settings } from "../game/settings";
import type { KeyValue } from "../game/store";
import { Condensate } from "../view/condensate";
import type { ControlName, Layout } from "../view/geometry";
import type { Target } from "../view/overlays";
import { Scene } from "../view/scene";
import { act, type ActionHost } from "./actions";
import type { Action } from "./bindings";
import { Charts } from "./charts";
import type { Challenge, ClassMode } from "./classmode";
import { Controls, type ControlsHost } from "./controls";
import { KEY_HINTS, TOUCH_HINTS, type Hints } from "./hints";
import { Input, type InputHost } from "./input";
import { Screen, type Zoom } from "./layout";
import { FrameLoop, type Animated } from "./loop";
import { Notices } from "./notices";
import { SettingsEditor } from "./options";
import { PanelKeys, type PanelKeysHost } from "./panelkeys";
import { Panels, type Overlay, type PanelRooms } from "./panels";
import { Picture, type DrawnControls, type PictureRooms } from "./picture";
import { Play, type PlayEvents } from "./play";
import type { GameLike } from "../runtime/remote";
import { Replays } from "./replays";
import { NO_SETUP, Setup, type SetupParams } from "./setup";
import { Teaching } from "./teaching";
import { Scoreboard } from "./scoring";
import { Verifier } from "./verifier";
import { WinScreen, type WinRooms } from "./winscreen";

export { pickTarget } from "./input";
export type { Overlay } from "./panels";
export type { DrawnControls } from "./picture";

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
  /** A teacher's link: start height, locks, hidden buttons, theme, sound (issue 48). */
  setup?: SetupParams;
  /** The page plays a class challenge (sound off unless chosen). */
  inClass?: boolean;
}

export class App
  implements
    Animated,
    ActionHost,
    ControlsHost,
    InputHost,
    PanelKeysHost,
    PlayEvents,
    PanelRooms,
    PictureRooms,
    WinRooms
{
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
  readonly teaching: Teaching;
  readonly controls: Controls;
  readonly input: Input;
  readonly panelKeys: PanelKeys;
  readonly loop = new FrameLoop(this);
  /** Class mode (the page served by `evapcool class`), or null. */
  classMode: ClassMode | null = null;
  /** Set by any input: the next frame draws. */
  dirty = true;
  readonly picture: Picture;
  /** A touch screen (its hints name taps; its buttons are 44 CSS px at least). */
  readonly coarse: boolean;
  readonly reducedMotion: boolean;
  /** A key was pressed: this touch screen has a keyboard too, so hints name keys. */
  private keyboardSeen = false;

  constructor(
    readonly el: Elements,
    opts: AppOptions,
  ) {
    const app = this;
    const setup = new Setup(opts.setup ?? NO_SETUP);
    this.picture = new Picture(this, el.status);
    const mq = (q: string) => typeof matchMedia === "function" && matchMedia(q).matches;
    this.reducedMotion = mq("(prefers-reduced-motion: reduce)");
    this.coarse = mq("(pointer: coarse)");
    this.screen = new Screen(el.canvas);
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
        fieldLocked: (field) => setup.fieldLocked(field),
        get soundByDefault() {
          return !opts.inClass && app.teaching.audible;
        },
        prefsChanged: (p) => this.teaching.prefsChanged(p),
      },
      opts.overrides ?? {},
    );
    const o = this.options;
    o.overrides = { ...setup.frozen(o.runSettings()), ...o.overrides };
    this.teaching = new Teaching(this, setup, opts.inClass ?? false);
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
      showTable: (shown) => {
        this.panels.open = shown ? "table" : null;
        this.panelKeys.stay(); // the restart button keeps the focus (issue 27.12)
      },
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
    this.panelKeys = new PanelKeys(this, el.root);
    this.controls.build(el.root);
    this.resize();
    this.input.wire();
    window.addEventListener("pointerdown", () => this.teaching.wake(), { capture: true });
    this.startTrap();
  }

  /** The link's start height for a game the player plays (not a replay's or a challenge's). */
  private startTrap(): void {
    const h = this.teaching.setup.params.trap;
    if (h !== null && !this.play.replaying && !this.play.challengeSettings)
      this.game.setTrapHeight(h);
  }

  // -- what the rooms share, and scripts and tests read (window.evapcool.app) -------------
  get game(): GameLike {
    return this.play.game;
  }

  get overlay(): Overlay {
    return this.panels.open;
  }

  get targets(): Target[] {
    return this.picture.targets;
  }

  get targetsZoomed(): boolean {
    return this.picture.targetsZoomed;
  }

  get readoutSize(): number {
    return this.picture.readoutSize;
  }

  get drawn(): DrawnControls {
    return this.picture.drawn;
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
    this.teaching.wake();
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

  hidden(name: ControlName): boolean {
    return this.teaching.setup.isHidden(name);
  }

  trapLocked(): boolean {
    return this.teaching.setup.locked.has("trap");
  }

  heightChanged(): void {
    this.play.heightChanged();
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
    const escape = t(s.escape === "knife" ? "settings.escape_knife" : "settings.escape_rim");
    this.notify(t("page.class_challenge", { n: s.n_atoms, radius: s.radius, escape }));
  }

  // -- actions -------------------------------------------------------------------------------
  act(action: Action): void {
    act(this, action);
  }

  /** New atoms with the current settings, trap at 400, paused; ends any name entry. */
  restart(): void {
    const s = this.options.runSettings();
    this.play.restart(s);
    this.startTrap();
    this.scores.newGame();
    if (this.panels.open === "table") this.panels.open = null;
    this.charts.reset();
    this.scores.openTable(s);
    const height = Math.round(this.game.trapHeight);
    this.say(t("page.restarted", { n: this.game.config.nAtoms, height }));
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

  /** Advance n display frames of one physics frame x speed each, drawing each (tests). */
  runFrames(n: number): Promise<void> {
    return this.play.runFrames(n, () => this.draw());
  }

  pictureKey(): string {
    return this.picture.key();
  }

  draw(): void {
    if (this.picture.draw()) this.dirty = true;
    this.panelKeys.sync();
    this.teaching.frame();
  }
}
