/**
 * The applet in the page: one canvas drawn at the device's pixel ratio, transparent
 * buttons over the drawn controls (keyboard focus, screen readers, 44 px touch targets),
 * the key table, overlays, storage, the frame loop and a polite live region.
 */
import { FPS } from "../game/constants";
import { HighScoreTable, NAME_MAX, scoresKey } from "../game/highscores";
import { Game, HEIGHT_MAX, HEIGHT_MIN, type GameConfig, type SimFactory } from "../game/rules";
import {
  describe,
  FIELD_NAMES,
  sameSettings,
  settingsKey,
  step as stepSetting,
  tcExponent,
  type Settings,
} from "../game/settings";
import { loadSettings, saveSettings } from "../game/settingsStore";
import { emptyAtoms, type AtomArrays } from "../game/sim";
import type { KeyValue } from "../game/store";
import * as C from "../view/colors";
import { Condensate } from "../view/condensate";
import {
  atLeast,
  contains,
  layoutFor,
  MIN_TARGET_CSS,
  PLAY_RECT,
  type ControlName,
  type Layout,
  type Rect,
} from "../view/geometry";
import type { Look, SymbolName } from "../view/icons";
import {
  drawHelp,
  drawNameFrame,
  nameField,
  drawNotices,
  drawSettings,
  drawTable,
  type Target,
} from "../view/overlays";
import { EnergyPanel, PathPanel } from "../view/panels";
import { Scene } from "../view/scene";
import { drawText } from "../view/text";
import { drawControlButton, drawSlider, SliderModel } from "../view/widgets";
import { actionFor, helpRows, HEIGHT_STEP, type Action } from "./bindings";
import { FrameStats } from "./stats";

const NOTICE_SECONDS = 8;
/** Notices at once (a damaged store can give several, each must be seen). */
const NOTICE_MAX = 5;
const LABELS: Record<ControlName, string> = {
  pause: "Play",
  restart: "Restart: new atoms, trap at 400, paused",
  chart: "Energy chart on or off",
  help: "Help: every control",
  table: "High-score table",
  settings: "Settings",
  fullscreen: "Full screen on or off",
};

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
  /** Window size source and the clock (tests may replace them). */
  now?: () => number;
}

type Overlay = null | "help" | "table" | "settings";

export class App {
  readonly game: Game;
  readonly scene = new Scene();
  readonly condensate = new Condensate();
  readonly energy = new EnergyPanel();
  readonly path = new PathPanel();
  readonly stats = new FrameStats();
  readonly slider = new SliderModel(HEIGHT_MIN, HEIGHT_MAX, 400);
  layout!: Layout;
  overlay: Overlay = null;
  showEnergy = false;
  showPath = false;
  settings: Settings;
  settingsDraft: Settings;
  settingsRow = 0;
  overrides: Partial<Settings>;
  table!: HighScoreTable;
  nameBoxOpen = false;
  storedRank: number | null = null;
  readyForNext = false;
  confirmReset = false;
  animTime = 0;
  private notices: Array<[string, number]> = [];
  private targets: Target[] = [];
  private buttons = new Map<ControlName, HTMLButtonElement>();
  private sliderEl!: HTMLDivElement;
  private pressed: ControlName | null = null;
  private clickHandledAt = -Infinity;
  private sliding = false;
  private hot: ControlName | "slider" | null = null;
  private ctx: CanvasRenderingContext2D;
  private dpr = 1;
  private atoms: AtomArrays = emptyAtoms();
  private lastTime: number | null = null;
  private recordedTime = -1;
  private recordedGen = -1;
  private rafId = 0;
  private lastHeightSpoken = 400;
  private heightTimer: ReturnType<typeof setTimeout> | null = null;
  private pausedByHiding = false;
  private readonly reducedMotion: boolean;
  private readonly coarse: boolean;
  /** Set by any input: the next frame draws. */
  dirty = true;
  private lastPicture = "";
  private drawnAt = -1;
  /** Errors thrown while drawing a frame (kept, not rethrown, so one bad frame is not fatal). */
  errors: string[] = [];

  constructor(
    readonly el: Elements,
    private readonly opts: AppOptions,
  ) {
    const ctx = el.canvas.getContext("2d", { alpha: false });
    if (!ctx) throw new Error("this browser cannot draw on a canvas");
    this.ctx = ctx;
    const mq = (q: string) => typeof matchMedia === "function" && matchMedia(q).matches;
    this.reducedMotion = mq("(prefers-reduced-motion: reduce)");
    this.coarse = mq("(pointer: coarse)");
    for (const text of opts.notices ?? []) this.notify(text);
    const [saved, problems] = loadSettings(opts.storage);
    problems.forEach((t) => this.notify(t));
    this.settings = saved;
    this.settingsDraft = saved;
    this.overrides = opts.overrides ?? {};
    this.game = this.firstGame();
    this.game.onWin.push(() => this.onWin());
    this.openTable();
    this.buildControls();
    this.resize();
    this.wire();
  }

  /** The first game: the address's settings, or the saved ones if the physics refuses those. */
  private firstGame(): Game {
    const config = this.opts.config ?? {};
    try {
      return new Game(this.opts.factory, { ...config, ...this.configFor(this.runSettings()) });
    } catch (err) {
      if (!(err instanceof RangeError) || !Object.keys(this.overrides).length) throw err;
      this.notify(`Address: ${err.message}; playing the saved settings.`);
      this.overrides = {};
      return new Game(this.opts.factory, { ...config, ...this.configFor(this.runSettings()) });
    }
  }

  // -- settings and the table ------------------------------------------------------------
  runSettings(): Settings {
    return { ...this.settings, ...this.overrides };
  }

  private configFor(s: Settings): Partial<GameConfig> {
    return { nAtoms: s.nAtoms, radius: s.radius, tcExponent: tcExponent(s), escape: s.escape };
  }

  private openTable(): void {
    const key = scoresKey(settingsKey(this.runSettings()));
    if (this.table?.key === key) return;
    this.table = new HighScoreTable(this.opts.storage, key);
    this.table.takeNotices().forEach((t) => this.notify(t));
  }

  // -- notices and the live region ---------------------------------------------------------
  notify(text: string): void {
    this.dirty = true;
    this.notices.push([text, this.animTime + NOTICE_SECONDS]);
    this.notices.splice(0, Math.max(0, this.notices.length - NOTICE_MAX));
    this.say(text);
  }

  get visibleNotices(): string[] {
    return this.notices.filter(([, until]) => until > this.animTime).map(([t]) => t);
  }

  /** Tell a screen reader (politely: after what it is reading). */
  say(text: string): void {
    const live = this.el.live;
    // A changed text node is announced even when the words repeat.
    live.textContent = "";
    const node = document.createElement("p");
    node.textContent = text;
    live.append(node);
    while (live.childNodes.length > 1) live.firstChild?.remove();
  }

  // -- actions -------------------------------------------------------------------------------
  act(action: Action): void {
    const g = this.game;
    switch (action) {
      case "pause":
        g.togglePause();
        this.say(g.paused ? "Paused" : "Playing");
        break;
      case "restart":
        this.restart();
        break;
      case "lower":
        g.nudgeHeight(-HEIGHT_STEP);
        this.heightChanged();
        break;
      case "raise":
        g.nudgeHeight(HEIGHT_STEP);
        this.heightChanged();
        break;
      case "step":
        g.step();
        break;
      case "faster":
        g.faster();
        this.say(`Speed ${speedText(g.speed)}`);
        break;
      case "slower":
        g.slower();
        this.say(`Speed ${speedText(g.speed)}`);
        break;
      case "energy":
        this.showEnergy = !this.showEnergy;
        this.resize();
        this.say(`Energy chart ${this.showEnergy ? "shown" : "hidden"}`);
        break;
      case "path":
        this.showPath = !this.showPath;
        this.resize();
        this.say(`Path chart ${this.showPath ? "shown" : "hidden"}`);
        break;
      case "table":
        this.toggleOverlay("table");
        this.confirmReset = false;
        break;
      case "clear":
        this.overlay = "table";
        this.confirmReset = true;
        this.say("Clear all scores? Y: yes, N or Escape: no");
        break;
      case "next":
        if (this.readyForNext) this.restart();
        break;
      case "settings":
        this.overlay = "settings";
        this.settingsDraft = this.settings;
        this.settingsRow = 0;
        this.sayRow();
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
    const titles = { help: "Help", table: "High scores", settings: "Settings" };
    if (this.overlay === name) this.say(`${titles[name]} shown`);
  }

  /** New atoms with the current settings, trap at 400, paused; ends any name entry. */
  restart(): void {
    const s = this.runSettings();
    try {
      this.game.restart({ ...this.game.config, ...this.configFor(s) });
    } catch (err) {
      this.notify(
        `Those settings do not work (${(err as Error).message}); kept the previous ones.`,
      );
      this.game.restart();
    }
    this.closeNameBox();
    this.readyForNext = false;
    this.storedRank = null;
    this.confirmReset = false;
    if (this.overlay === "table") this.overlay = null;
    this.energy.reset();
    this.path.reset();
    this.openTable();
    this.slider.setValue(this.game.trapHeight);
    this.say(`Restarted: ${this.game.sim.nAtoms} atoms, trap height 400, paused`);
  }

  private heightChanged(): void {
    // Speak the height once the player stops moving it, not at every step.
    if (this.heightTimer !== null) clearTimeout(this.heightTimer);
    this.heightTimer = setTimeout(() => {
      const h = Math.round(this.game.trapHeight);
      if (h !== this.lastHeightSpoken) this.say(`Trap height ${h}`);
      this.lastHeightSpoken = h;
    }, 400);
  }

  toggleFullscreen(): void {
    if (document.fullscreenElement) {
      void document.exitFullscreen().catch(() => {});
    } else if (document.documentElement.requestFullscreen) {
      document.documentElement.requestFullscreen().catch((err: unknown) => {
        this.notify(`Full screen is not available here (${(err as Error).message}).`);
      });
    } else {
      this.notify("Full screen is not available in this browser.");
    }
  }

  // -- the win and the name box --------------------------------------------------------------
  private onWin(): void {
    const g = this.game;
    const score = g.score ?? 0;
    const seconds = g.wonAt ?? 0;
    // The win is what matters now: a trap height still waiting to be spoken is dropped.
    if (this.heightTimer !== null) clearTimeout(this.heightTimer);
    this.heightTimer = null;
    this.say(`Temperature below Tc: ${score} atoms, score ${score}`);
    if (this.table.qualifies(score, seconds)) {
      this.overlay = null; // the name box must be seen
      this.openNameBox();
    } else {
      this.notify(`Score ${score} is not in the top 10 this time. Enter: next player.`);
      this.readyForNext = true;
    }
  }

  private openNameBox(): void {
    this.nameBoxOpen = true;
    const input = this.el.nameInput;
    input.value = "";
    input.hidden = false;
    this.placeNameBox();
    input.focus({ preventScroll: true });
  }

  private closeNameBox(): void {
    if (!this.nameBoxOpen) return;
    this.nameBoxOpen = false;
    const input = this.el.nameInput;
    const hadFocus = document.activeElement === input;
    input.hidden = true;
    if (hadFocus) this.el.canvas.focus({ preventScroll: true });
  }

  storeName(name: string): void {
    const g = this.game;
    this.closeNameBox();
    this.storedRank = this.table.add(name, g.score ?? 0, g.wonAt ?? 0);
    this.table.takeNotices().forEach((t) => this.notify(t));
    this.overlay = "table";
    this.readyForNext = true;
    if (this.storedRank !== null)
      this.say(`Stored at place ${this.storedRank}. Enter: next player`);
  }

  skipName(): void {
    this.closeNameBox();
    this.notify("Score not stored. Enter: next player.");
    this.readyForNext = true;
  }

  private clearTable(yes: boolean): void {
    this.confirmReset = false;
    if (!yes) return;
    this.storedRank = null;
    if (this.table.reset()) this.notify("The high-score table was cleared.");
    this.table.takeNotices().forEach((t) => this.notify(t));
  }

  // -- settings screen --------------------------------------------------------------------------
  private settingsKey(key: string): void {
    const n = FIELD_NAMES.length;
    if (key === "arrowup") this.settingsRow = (this.settingsRow + n - 1) % n;
    else if (key === "arrowdown") this.settingsRow = (this.settingsRow + 1) % n;
    else if (key === "arrowleft" || key === "arrowright") {
      this.changeSetting(this.settingsRow, key === "arrowright" ? 1 : -1);
      return;
    } else if (key === "enter" || key === "o") {
      this.closeSettings(true);
      return;
    } else if (key === "escape") {
      this.closeSettings(false);
      return;
    } else return;
    this.sayRow();
  }

  private changeSetting(row: number, d: number): void {
    this.settingsRow = row;
    this.settingsDraft = stepSetting(this.settingsDraft, FIELD_NAMES[row], d);
    this.sayRow();
  }

  private sayRow(): void {
    const [label, value] = describe(this.settingsDraft)[this.settingsRow];
    this.say(`${label} ${value}`);
  }

  private closeSettings(save: boolean): void {
    this.overlay = null;
    const draft = this.settingsDraft;
    if (!save || sameSettings(draft, this.settings)) return;
    const base = this.settings;
    this.overrides = {}; // a choice made here beats the address for the rest of the visit
    // What was stored: this draft's changes over another tab's choices made meanwhile.
    const { saved, notices: problems } = saveSettings(this.opts.storage, draft, base);
    this.settings = saved;
    problems.forEach((t) => this.notify(t));
    if (!problems.length) this.notify("Settings saved. Press R (restart) to play with them.");
  }

  // -- input ------------------------------------------------------------------------------------
  /** A key press (KeyboardEvent.key); true if the applet used it. */
  key(rawKey: string): boolean {
    const key = rawKey.toLowerCase();
    if (this.confirmReset) {
      if (key === "y") this.clearTable(true);
      else if (key === "n" || key === "escape") this.clearTable(false);
      return true; // nothing else happens until the question is answered
    }
    if (this.nameBoxOpen) return false; // the input field has the keyboard
    if (this.overlay === "settings") {
      this.settingsKey(key);
      return true;
    }
    const action = actionFor(rawKey);
    if (!action) return false;
    this.act(action);
    return true;
  }

  private wire(): void {
    const { canvas, nameInput } = this.el;
    for (const type of ["keydown", "keyup", "pointerdown", "pointermove", "pointerup", "input"]) {
      window.addEventListener(type, () => (this.dirty = true), { capture: true, passive: true });
    }
    window.addEventListener("resize", () => this.resize());
    // Another tab stored a score: show the table as it is now.
    window.addEventListener("storage", (ev) => {
      if (ev.key !== null && ev.key !== this.table.key) return;
      this.table.load();
      this.table.takeNotices().forEach((t) => this.notify(t));
      this.dirty = true;
    });
    window.visualViewport?.addEventListener("resize", () => this.resize());
    // A window moved to a screen of another pixel ratio: redraw sharp for that one.
    const watchRatio = () => {
      if (typeof matchMedia !== "function") return;
      matchMedia(`(resolution: ${window.devicePixelRatio}dppx)`).addEventListener(
        "change",
        () => {
          this.resize();
          watchRatio();
        },
        { once: true },
      );
    };
    watchRatio();
    window.addEventListener("keydown", (ev) => {
      if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
      const target = ev.target as HTMLElement | null;
      if (target === nameInput) return;
      // Enter on a focused button presses that button (its own click).
      if (ev.key === "Enter" && target instanceof HTMLButtonElement && !this.readyForNext) return;
      if (this.key(ev.key)) ev.preventDefault();
    });
    nameInput.maxLength = NAME_MAX * 2; // code points are cut by the table; this bounds typing
    nameInput.addEventListener("keydown", (ev) => {
      if (ev.isComposing) return;
      if (ev.key === "Enter") {
        ev.preventDefault();
        this.storeName(nameInput.value);
      } else if (ev.key === "Escape") {
        ev.preventDefault();
        this.skipName();
      }
      ev.stopPropagation();
    });
    nameInput.addEventListener("input", () => {
      const chars = Array.from(nameInput.value);
      if (chars.length > NAME_MAX) nameInput.value = chars.slice(0, NAME_MAX).join("");
    });
    canvas.addEventListener("pointerdown", (ev) => this.tap(ev));
    document.addEventListener("visibilitychange", () => {
      if (document.hidden && !this.game.paused) {
        this.game.paused = true;
        this.pausedByHiding = true;
      } else if (!document.hidden && this.pausedByHiding) {
        this.pausedByHiding = false;
        this.say("Paused while the page was hidden. Space or play: go on.");
      }
      this.lastTime = null;
    });
    document.addEventListener("fullscreenchange", () => this.resize());
  }

  /** A tap or click on the canvas: overlay targets first, then closing the help. */
  private tap(ev: PointerEvent): void {
    const [lx, ly] = this.toLogical(ev.clientX, ev.clientY);
    const z = this.overlayZoom();
    const [x, y] = [z.cx + (lx - z.x) / z.k, z.cy + (ly - z.y) / z.k];
    const hit = pickTarget(this.targets, x, y, MIN_TARGET_CSS / (this.layout.scale * z.k));
    if (hit) {
      ev.preventDefault();
      this.target(hit.action);
    } else if (this.overlay === "help") {
      this.overlay = null;
    }
  }

  private target(action: string): void {
    const [name, arg] = action.split(":");
    const row = Number(arg);
    switch (name) {
      case "close":
        this.overlay = null;
        break;
      case "dec":
      case "inc":
        this.changeSetting(row, name === "inc" ? 1 : -1);
        break;
      case "row":
        this.settingsRow = row;
        this.sayRow();
        break;
      case "save":
        this.closeSettings(true);
        break;
      case "cancel":
        this.closeSettings(false);
        break;
      case "clear":
        this.act("clear");
        break;
      case "yes":
        this.clearTable(true);
        break;
      case "no":
        this.clearTable(false);
        break;
      case "next":
        this.restart();
        break;
      case "tableclose":
        this.overlay = null;
        this.confirmReset = false;
        break;
    }
  }

  toLogical(clientX: number, clientY: number): [number, number] {
    const r = this.el.canvas.getBoundingClientRect();
    const l = this.layout;
    return [(clientX - r.left - l.offsetX) / l.scale, (clientY - r.top - l.offsetY) / l.scale];
  }

  /** Transparent buttons over the drawn controls: focus, labels, touch targets. */
  private buildControls(): void {
    const names: ControlName[] = ["pause", "restart"];
    const layer = document.createElement("div");
    layer.className = "controls";
    this.el.root.append(layer);
    const make = (name: ControlName) => {
      const b = document.createElement("button");
      b.type = "button";
      b.className = "hit";
      b.dataset.control = name;
      b.setAttribute("aria-label", LABELS[name]);
      b.addEventListener("pointerdown", () => (this.pressed = name));
      b.addEventListener("pointerleave", () => {
        if (this.pressed === name) this.pressed = null;
        if (this.hot === name) this.hot = null;
      });
      b.addEventListener("pointerenter", (ev) => {
        if (ev.pointerType === "mouse") this.hot = name;
      });
      // A press and release on the button acts at once (no wait for a synthesized click,
      // which touch screens may delay or drop); the click that follows is then ignored.
      b.addEventListener("pointerup", (ev) => {
        const r = b.getBoundingClientRect();
        const inside =
          ev.clientX >= r.left &&
          ev.clientX <= r.right &&
          ev.clientY >= r.top &&
          ev.clientY <= r.bottom;
        if (this.pressed === name && inside) {
          this.clickHandledAt = performance.now();
          this.press(name);
        }
        this.pressed = null;
      });
      b.addEventListener("pointercancel", () => (this.pressed = null));
      b.addEventListener("click", () => {
        if (performance.now() - this.clickHandledAt > 600) this.press(name); // keyboard
        this.clickHandledAt = -Infinity;
      });
      this.buttons.set(name, b);
      layer.append(b);
    };
    names.forEach(make);
    // The slider comes after the two buttons in the tab order, as on screen.
    const s = document.createElement("div");
    s.className = "hit slider";
    s.tabIndex = 0;
    s.setAttribute("role", "slider");
    s.setAttribute("aria-label", "Trap height");
    s.setAttribute("aria-valuemin", String(HEIGHT_MIN));
    s.setAttribute("aria-valuemax", String(HEIGHT_MAX));
    s.setAttribute("aria-orientation", "horizontal");
    s.addEventListener("pointerdown", (ev) => this.slideStart(ev));
    s.addEventListener("pointermove", (ev) => this.slideMove(ev));
    s.addEventListener("pointerup", (ev) => this.slideEnd(ev));
    s.addEventListener("pointercancel", (ev) => this.slideEnd(ev));
    s.addEventListener("pointerenter", (ev) => {
      if (ev.pointerType === "mouse") this.hot = "slider";
    });
    s.addEventListener("pointerleave", () => {
      if (this.hot === "slider") this.hot = null;
    });
    s.addEventListener("keydown", (ev) => {
      const k = ev.key;
      if (k === "Home" || k === "End" || k === "PageUp" || k === "PageDown") {
        ev.preventDefault();
        const g = this.game;
        const h = { Home: HEIGHT_MIN, End: HEIGHT_MAX, PageUp: g.trapHeight + 50 }[k as "Home"];
        g.setTrapHeight(h ?? g.trapHeight - 50);
        this.heightChanged();
      }
    });
    this.sliderEl = s;
    layer.append(s);
    (["chart", "help", "table", "settings", "fullscreen"] as ControlName[]).forEach(make);
  }

  private press(name: ControlName): void {
    switch (name) {
      case "pause":
        this.act("pause");
        break;
      case "restart":
        this.act("restart");
        break;
      case "chart":
        this.act("energy");
        break;
      case "help":
        this.act("help");
        break;
      case "table":
        this.act("table");
        break;
      case "settings":
        if (this.overlay === "settings") this.closeSettings(false);
        else this.act("settings");
        break;
      case "fullscreen":
        this.act("fullscreen");
        break;
    }
  }

  private slideStart(ev: PointerEvent): void {
    if (this.game.won) return;
    ev.preventDefault();
    this.sliding = true;
    this.sliderEl.setPointerCapture?.(ev.pointerId);
    this.sliderEl.focus({ preventScroll: true });
    this.slideMove(ev);
  }

  private slideMove(ev: PointerEvent): void {
    if (!this.sliding) return;
    const [x] = this.toLogical(ev.clientX, ev.clientY);
    this.game.setTrapHeight(this.slider.valueAt(x, this.layout.slider));
    this.slider.setValue(this.slider.valueAt(x, this.layout.slider));
    this.heightChanged();
  }

  private slideEnd(ev: PointerEvent): void {
    if (!this.sliding) return;
    this.slideMove(ev);
    this.sliding = false;
    this.sliderEl.releasePointerCapture?.(ev.pointerId);
  }

  // -- layout -------------------------------------------------------------------------------
  resize(): void {
    this.dirty = true;
    const vw = Math.max(1, window.innerWidth);
    const vh = Math.max(1, window.innerHeight);
    this.layout = layoutFor(vw, vh, { energy: this.showEnergy, path: this.showPath });
    this.dpr = Math.max(1, window.devicePixelRatio || 1);
    const c = this.el.canvas;
    c.style.width = `${vw}px`;
    c.style.height = `${vh}px`;
    const w = Math.round(vw * this.dpr);
    const h = Math.round(vh * this.dpr);
    if (c.width !== w || c.height !== h) {
      c.width = w;
      c.height = h;
    }
    this.placeControls();
    this.placeNameBox();
  }

  /** Logical rect -> CSS box of an element over the canvas. */
  private place(el: HTMLElement, r: Rect): void {
    const l = this.layout;
    el.style.left = `${l.offsetX + r.x * l.scale}px`;
    el.style.top = `${l.offsetY + r.y * l.scale}px`;
    el.style.width = `${r.w * l.scale}px`;
    el.style.height = `${r.h * l.scale}px`;
  }

  private placeControls(): void {
    const l = this.layout;
    const min = MIN_TARGET_CSS / l.scale;
    for (const [name, b] of this.buttons) this.place(b, atLeast(l.buttons[name], min));
    const s = l.slider;
    const r = l.knobRadius;
    this.place(
      this.sliderEl,
      atLeast({ x: s.x - r, y: s.y + s.h / 2 - r, w: s.w + 2 * r, h: 2 * r }, min),
    );
  }

  private placeNameBox(): void {
    if (!this.nameBoxOpen || !this.layout) return;
    const field = nameField();
    const input = this.el.nameInput;
    this.place(input, field);
    input.style.fontSize = `${32 * 0.6875 * this.layout.scale}px`;
  }

  // -- the frame ------------------------------------------------------------------------------
  start(): void {
    const loop = (now: number) => {
      this.rafId = requestAnimationFrame(loop);
      this.frame(now);
    };
    this.rafId = requestAnimationFrame(loop);
  }

  stop(): void {
    cancelAnimationFrame(this.rafId);
  }

  /** One display frame at time `now` (ms): physics to now, then drawing. */
  frame(now: number): void {
    const t0 = performance.now();
    const dt = this.lastTime === null ? 0 : Math.max(0, (now - this.lastTime) / 1000);
    this.lastTime = now;
    try {
      this.game.update(dt);
      this.animTime += Math.min(dt, 0.25);
      const key = this.pictureKey();
      if (!this.dirty && key !== "" && key === this.lastPicture) return; // nothing changed
      this.lastPicture = key;
      this.dirty = false;
      this.drawnAt = now;
      this.draw();
    } catch (err) {
      // Keep the page alive; the message is kept for the console and the tests.
      const text = `${(err as Error).name}: ${(err as Error).message}`;
      if (this.errors.length < 20) this.errors.push(text);
      if (this.errors.length === 1) console.error(err);
    }
    if (this.drawnAt === now) this.stats.add(now, performance.now() - t0);
  }

  /**
   * What the picture depends on besides input (every input event marks it dirty): while
   * this stays the same, a frame draws nothing (a paused applet costs no battery). ""
   * means animated: draw every frame.
   */
  private pictureKey(): string {
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
      this.visibleNotices.length,
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
  runFrames(n: number): void {
    for (let k = 0; k < n; k++) {
      this.game.runFrames(1);
      this.animTime += 1 / FPS;
      this.draw();
    }
  }

  private record(): void {
    const sim = this.game.sim;
    const gen = this.game.generation;
    if (gen === this.recordedGen && sim.time === this.recordedTime) return;
    this.recordedGen = gen;
    this.recordedTime = sim.time;
    this.energy.record(sim, this.atoms, gen);
    this.path.record(sim, gen);
  }

  draw(): void {
    const ctx = this.ctx;
    const l = this.layout;
    const g = this.game;
    const sim = g.sim;
    this.atoms = sim.trapped();
    this.record();
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = "rgb(0,0,0)";
    ctx.fillRect(0, 0, this.el.canvas.width, this.el.canvas.height);
    const s = l.scale * this.dpr;
    ctx.setTransform(
      s,
      0,
      0,
      s,
      Math.round(l.offsetX * this.dpr),
      Math.round(l.offsetY * this.dpr),
    );
    this.scene.deviceScale = s;
    const fade = this.condensate.update(sim, this.atoms, g.generation, this.animTime);
    this.scene.draw(ctx, g, this.atoms, 1 - fade);
    if (fade > 0) {
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
    this.scene.drawFrame(ctx, g, l.sceneHeight);
    this.drawControls(ctx);
    const tooFew = g.score === null ? g.tooFewAtoms(this.lightestMass()) : null;
    if (g.score !== null) this.scene.drawScore(ctx, g.score);
    else if (tooFew !== null) {
      this.scene.drawTooFew(ctx, tooFew);
      if (tooFew !== this.saidTooFew)
        this.say(`Too few atoms left. ${tooFew} Press R to try again.`);
    } else if (g.paused && sim.time === 0 && this.overlay === null) {
      this.scene.drawStartHint(ctx, this.coarse);
    }
    this.targets = [];
    this.saidTooFew = tooFew;
    if (this.nameBoxOpen) {
      const length = Array.from(this.el.nameInput.value).length;
      drawNameFrame(ctx, "Top 10! Type your name:", length, NAME_MAX);
    }
    const zoom = this.overlayZoom();
    ctx.save();
    ctx.translate(zoom.x, zoom.y);
    ctx.scale(zoom.k, zoom.k);
    ctx.translate(-zoom.cx, -zoom.cy);
    if (this.overlay === "help") {
      this.targets = drawHelp(ctx, helpRows(), this.fpsLine());
    } else if (this.overlay === "table") {
      this.targets = drawTable(
        ctx,
        `for ${describeRun(this.runSettings())}`,
        this.table.entries,
        this.storedRank,
        this.tableFooter(),
        this.tableButtons(),
      );
    } else if (this.overlay === "settings") {
      this.targets = drawSettings(
        ctx,
        describe(this.settingsDraft),
        this.settingsRow,
        this.settingsFooter(),
      );
    }
    ctx.restore();
    drawNotices(ctx, this.visibleNotices);
    if (l.charts.energy) this.energy.draw(ctx, l.charts.energy);
    if (l.charts.path) this.path.draw(ctx, l.charts.path);
    this.updateStatus();
  }

  private drawControls(ctx: CanvasRenderingContext2D): void {
    const l = this.layout;
    const g = this.game;
    if (l.strip) {
      ctx.fillStyle = C.BORDER;
      ctx.fillRect(l.strip.x, l.strip.y, l.strip.w, l.strip.h);
      ctx.fillStyle = "rgb(60,60,60)";
      ctx.fillRect(l.strip.x, l.strip.y, l.strip.w, 2);
    }
    const symbols: Record<ControlName, SymbolName> = {
      pause: g.paused ? "play" : "pause",
      restart: "restart",
      chart: "chart",
      help: "help",
      table: "table",
      settings: "settings",
      fullscreen: "fullscreen",
    };
    for (const name of Object.keys(symbols) as ControlName[]) {
      const look: Look = this.pressed === name ? "down" : this.hot === name ? "hover" : "idle";
      drawControlButton(ctx, l.buttons[name], symbols[name], look);
    }
    if (!this.sliding) this.slider.setValue(g.trapHeight);
    const labelSize = l.mode === "tall" ? 40 : 24;
    const hot = this.sliding || this.hot === "slider";
    drawSlider(ctx, l.slider, this.slider, l.knobRadius, "Trap height", hot, !g.won, labelSize);
    const pauseBtn = this.buttons.get("pause");
    pauseBtn?.setAttribute("aria-label", g.paused ? "Play" : "Pause");
    pauseBtn?.setAttribute("aria-pressed", String(!g.paused));
    const h = Math.round(g.trapHeight);
    if (this.sliderEl.getAttribute("aria-valuenow") !== String(h)) {
      this.sliderEl.setAttribute("aria-valuenow", String(h));
      this.sliderEl.setAttribute("aria-valuetext", `${h} px`);
    }
    this.sliderEl.setAttribute("aria-disabled", String(g.won));
  }

  /**
   * Panels over the play area (help, scores, settings) drawn larger in the tall layout,
   * centred on the whole scene and strip, so their text stays readable on a phone: the
   * point (cx, cy) of the play area goes to (x, y), scaled by k.
   */
  overlayZoom(): { k: number; cx: number; cy: number; x: number; y: number } {
    const cx = PLAY_RECT.x + PLAY_RECT.w / 2;
    const cy = PLAY_RECT.y + PLAY_RECT.h / 2;
    const l = this.layout;
    if (l.mode !== "tall" || !l.strip) return { k: 1, cx, cy, x: cx, y: cy };
    const bottom = l.strip.y + l.strip.h;
    const k = Math.min((l.width - 16) / (PLAY_RECT.w - 24), (bottom - 8) / PLAY_RECT.h);
    return { k, cx, cy, x: l.width / 2, y: bottom / 2 };
  }

  private tableFooter(): string[] {
    if (this.confirmReset) return ["Clear all scores?  Y: yes   N or Esc: no"];
    if (this.readyForNext) return ["Enter: next player"];
    return ["T: close   Delete or X: clear the table"];
  }

  private tableButtons(): Array<[string, string]> {
    if (this.confirmReset)
      return [
        ["Yes, clear", "yes"],
        ["No", "no"],
      ];
    if (this.readyForNext)
      return [
        ["Next player", "next"],
        ["Close", "tableclose"],
      ];
    return [
      ["Close", "tableclose"],
      ["Clear...", "clear"],
    ];
  }

  private settingsFooter(): string[] {
    const lines = ["Up/Down choose, Left/Right change", "Enter or O: save   Esc: cancel"];
    const names = Object.keys(this.overrides);
    if (names.length)
      lines.push(`This visit uses the address's ${names.join(", ")} until you save here.`);
    return lines;
  }

  private fpsLine(): string {
    const st = this.stats.summary();
    const fps = st.fps > 0 ? st.fps.toFixed(0) : "-";
    return `${fps} fps   frame ${st.medianMs.toFixed(2)} ms   ${this.game.sim.nTrapped} atoms`;
  }

  private lastStatus = "";
  private saidTooFew: string | null = null;

  /** The lightest trapped atom's mass (the escape energy of the too-few rule). */
  private lightestMass(): number {
    const a = this.atoms;
    let m = Infinity;
    for (let i = 0; i < a.count; i++) m = Math.min(m, a.mass[i]);
    return Number.isFinite(m) ? m : 1;
  }
  private statusAt = -Infinity;

  /** The canvas's text alternative: what is on screen, in words (updated when it changes). */
  private updateStatus(): void {
    const g = this.game;
    const sim = g.sim;
    const state = g.won
      ? `Condensed. Score ${g.score}.`
      : g.allEscaped
        ? "All the atoms escaped."
        : g.paused
          ? "Paused."
          : "Playing.";
    const text =
      `${state} ${sim.nTrapped} atoms in the cup, trap height ${Math.round(g.trapHeight)} px, ` +
      `temperature ${fmt(sim.temperature)}, critical temperature ${fmt(sim.criticalTemperature)} ` +
      `(${sim.temperature < sim.criticalTemperature ? "below" : "above"} Tc).`;
    if (text === this.lastStatus) return;
    // At most twice a second; until then keep drawing so the last change is written.
    const now = performance.now();
    if (now - this.statusAt >= 500) {
      this.statusAt = now;
      this.lastStatus = text;
      this.el.status.textContent = text;
    } else {
      this.dirty = true;
    }
  }
}

function fmt(v: number): string {
  return Number.isFinite(v) ? v.toFixed(1) : "-";
}

export function speedText(s: number): string {
  return s >= 1 ? `${s}x` : `1/${1 / s}x`;
}

function describeRun(s: Settings): string {
  const law = s.tcLaw === "seed" ? "Tc ~ N^(2/3)" : "Tc ~ N^(2/5)";
  return `${s.nAtoms} atoms of radius ${s.radius}, ${law}, ${s.escape === "rim" ? "rim" : "knife"}`;
}

/**
 * The target under a tap: one drawn under the point first (the first listed wins), else
 * the nearest whose area grown to `min` logical px (44 CSS px) holds the point, so small
 * targets on a phone can still be hit with a finger.
 */
export function pickTarget(targets: Target[], x: number, y: number, min: number): Target | null {
  const exact = targets.find((t) => contains(t.rect, x, y));
  if (exact) return exact;
  let best: Target | null = null;
  let bestD = Infinity;
  for (const t of targets) {
    if (!contains(atLeast(t.rect, min), x, y)) continue;
    const cx = Math.max(t.rect.x, Math.min(x, t.rect.x + t.rect.w));
    const cy = Math.max(t.rect.y, Math.min(y, t.rect.y + t.rect.h));
    const d = Math.hypot(x - cx, y - cy);
    if (d < bestD) [best, bestD] = [t, d];
  }
  return best;
}
