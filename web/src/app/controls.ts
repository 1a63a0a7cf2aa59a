/**
 * The scene's own controls: play/pause, restart, the trap slider, the chart button and
 * the tools (help, scores, settings, full screen). Drawn on the canvas; transparent
 * elements over them give keyboard focus, screen-reader labels and 44 px touch targets.
 * Python's twin: `src/evapcool/app/controls.py` (docs/twins.md).
 */
import { HEIGHT_MAX, HEIGHT_MIN } from "../game/rules";
import { t } from "../i18n";
import * as C from "../view/colors";
import {
  atLeast,
  CONTROL_ORDER,
  MIN_TARGET_CSS,
  type ControlName,
  type Rect,
} from "../view/geometry";
import type { Look, SymbolName } from "../view/icons";
import { drawControlButton, drawSlider, SliderModel } from "../view/widgets";
import type { Action } from "./bindings";
import type { Screen } from "./layout";
import type { Overlay } from "./panels";
import type { GameLike } from "../runtime/remote";

/** What the controls move and show (the composition root wires them; app.ts). */
export interface ControlsHost {
  readonly screen: Screen;
  readonly game: GameLike;
  readonly autopilotEngaged: boolean;
  readonly overlay: Overlay;
  act(action: Action): void;
  /** Close the settings screen, keeping its changes (the gear pressed again). */
  saveSettings(): void;
  /** The player moved the trap: the autopilot lets go, the height is spoken. */
  takeOver(): void;
  heightChanged(): void;
  /** A link left the button out (issue 48). */
  hidden(name: ControlName): boolean;
  /** A link locked the trap: the slider is shown but does not move (said once per try). */
  trapLocked(): boolean;
}

/** Each button's spoken name: a message key (issue 23). */
const LABELS: Record<ControlName, string> = {
  pause: "control.play",
  restart: "status.restart",
  chart: "controls.energy_chart",
  help: "help.title",
  table: "control.table",
  settings: "settings.title",
  fullscreen: "controls.full_screen",
  step: "control.step",
  slower: "control.slower",
  faster: "control.faster",
  path: "control.path",
  autopilot: "control.autopilot",
};
/** A click this soon after a handled press and release is that press's own click, ms. */
const CLICK_AFTER_PRESS_MS = 600;

export class Controls {
  /** The knob rests at the game's trap height (read when drawn) unless a drag holds it. */
  readonly slider = new SliderModel(HEIGHT_MIN, HEIGHT_MAX, () => this.host.game.trapHeight);
  private buttons = new Map<ControlName, HTMLButtonElement>();
  private sliderEl!: HTMLDivElement;
  private layer!: HTMLDivElement;
  /** Knob minus pointer along the track when a drag grabbed the knob (no jump), logical px. */
  private grab = 0;
  /** The layout mode the elements' tab order was last put in. */
  private orderedFor = "";
  private pressed: ControlName | null = null;
  private clickHandledAt = -Infinity;
  sliding = false;
  private hot: ControlName | "slider" | null = null;

  constructor(private readonly host: ControlsHost) {}

  /** Transparent buttons over the drawn controls: focus, labels, touch targets. */
  build(root: HTMLElement): void {
    const layer = document.createElement("div");
    layer.className = "controls";
    root.append(layer);
    this.layer = layer;
    for (const name of CONTROL_ORDER) layer.append(this.button(name));
    layer.append(this.sliderElement());
  }

  focus(name: ControlName): void {
    this.buttons.get(name)?.focus({ preventScroll: true });
  }

  /** Tab order follows what is drawn: top to bottom, then left to right (issue 27.12). */
  private orderByPlace(): void {
    const l = this.host.screen.layout;
    if (this.orderedFor === l.mode) return;
    this.orderedFor = l.mode;
    const items: Array<[HTMLElement, Rect]> = [...this.buttons].map(([n, b]) => [b, l.buttons[n]]);
    const s = l.slider;
    // The slider as drawn with its knob (a lying track is only a few px high).
    items.push([this.sliderEl, atLeast(s, 2 * l.knobRadius)]);
    const focused = document.activeElement;
    for (const el of readingOrder(items, this.sliderEl, l.mode === "side")) this.layer.append(el);
    if (focused instanceof HTMLElement && this.layer.contains(focused))
      focused.focus({ preventScroll: true });
  }

  private button(name: ControlName): HTMLButtonElement {
    const b = document.createElement("button");
    b.type = "button";
    b.className = "hit";
    b.dataset.control = name;
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
      if (performance.now() - this.clickHandledAt > CLICK_AFTER_PRESS_MS) this.press(name);
      this.clickHandledAt = -Infinity;
    });
    this.buttons.set(name, b);
    return b;
  }

  private sliderElement(): HTMLDivElement {
    const s = document.createElement("div");
    s.className = "hit slider";
    s.tabIndex = 0;
    s.setAttribute("role", "slider");
    s.setAttribute("aria-valuemin", String(HEIGHT_MIN));
    s.setAttribute("aria-valuemax", String(HEIGHT_MAX));
    s.setAttribute("aria-orientation", "horizontal"); // set per layout in place()
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
        if (this.host.trapLocked()) return;
        const g = this.host.game;
        const h = { Home: HEIGHT_MIN, End: HEIGHT_MAX, PageUp: g.trapHeight + 50 }[k as "Home"];
        this.host.takeOver();
        g.setTrapHeight(h ?? g.trapHeight - 50);
        this.host.heightChanged();
      }
    });
    this.sliderEl = s;
    return s;
  }

  private press(name: ControlName): void {
    const host = this.host;
    switch (name) {
      case "chart":
        host.act("energy");
        break;
      case "settings":
        // The gear closes the screen as it opened it: keeping the changes, and saying so.
        if (host.overlay === "settings") host.saveSettings();
        else host.act("settings");
        break;
      default:
        host.act(name);
    }
  }

  private slideStart(ev: PointerEvent): void {
    if (this.host.game.won) return;
    if (this.host.trapLocked()) {
      this.host.act("lower"); // refused, and said so
      return;
    }
    ev.preventDefault();
    this.sliding = true;
    this.sliderEl.setPointerCapture?.(ev.pointerId);
    this.sliderEl.focus({ preventScroll: true });
    this.host.takeOver();
    // A press on or near the knob takes hold of it where it is; elsewhere the knob jumps there.
    const l = this.host.screen.layout;
    const along = this.along(ev);
    const knob = this.slider.knobAt(l.slider);
    const reach = Math.max(l.knobRadius, MIN_TARGET_CSS / 2 / l.scale);
    this.grab = Math.abs(knob - along) <= reach ? knob - along : 0;
    this.slideMove(ev);
  }

  /** The pointer's logical position along the slider's track. */
  private along(ev: PointerEvent): number {
    const [x, y] = this.host.screen.toLogical(ev.clientX, ev.clientY);
    return SliderModel.upright(this.host.screen.layout.slider) ? y : x;
  }

  private slideMove(ev: PointerEvent): void {
    if (!this.sliding) return;
    const value = this.slider.valueAt(this.along(ev) + this.grab, this.host.screen.layout.slider);
    this.host.game.setTrapHeight(value);
    this.slider.hold(value);
    this.host.heightChanged();
  }

  private slideEnd(ev: PointerEvent): void {
    if (!this.sliding) return;
    this.slideMove(ev);
    this.sliding = false;
    this.slider.release();
    this.sliderEl.releasePointerCapture?.(ev.pointerId);
  }

  /** Put the elements over the controls as the layout draws them. */
  place(): void {
    const screen = this.host.screen;
    const l = screen.layout;
    const min = MIN_TARGET_CSS / l.scale;
    for (const [name, b] of this.buttons) {
      screen.place(b, atLeast(l.buttons[name], min));
      b.hidden = this.host.hidden(name);
    }
    const s = l.slider;
    const r = l.knobRadius;
    const upright = SliderModel.upright(s);
    const box = upright
      ? { x: s.x + s.w / 2 - r, y: s.y - r, w: 2 * r, h: s.h + 2 * r }
      : { x: s.x - r, y: s.y + s.h / 2 - r, w: s.w + 2 * r, h: 2 * r };
    const hit = atLeast(box, min);
    // Its focus ring must not cut the label under a lying slider: grow upward, not down.
    if (!upright) hit.y = Math.min(hit.y, s.y + s.h + r + 4 - 7 / l.scale - hit.h);
    screen.place(this.sliderEl, hit);
    this.sliderEl.setAttribute("aria-orientation", upright ? "vertical" : "horizontal");
    this.orderByPlace();
  }

  /** Draw the strip, buttons and slider, and keep the elements' states in step. */
  draw(ctx: CanvasRenderingContext2D): void {
    const l = this.host.screen.layout;
    const g = this.host.game;
    if (l.strip) {
      ctx.fillStyle = C.BORDER;
      ctx.fillRect(l.strip.x, l.strip.y, l.strip.w, l.strip.h);
      ctx.fillStyle = C.STRIP_LINE;
      // A line where the strip meets the scene: above it (tall), at its left (wide, side).
      if (l.mode === "tall") ctx.fillRect(l.strip.x, l.strip.y, l.strip.w, 2);
      else ctx.fillRect(l.strip.x, l.strip.y, 2, l.strip.h);
    }
    const flying = this.host.autopilotEngaged;
    for (const name of CONTROL_ORDER) {
      if (this.host.hidden(name)) continue;
      const symbol: SymbolName = name === "pause" ? (g.paused ? "play" : "pause") : name;
      const down = this.pressed === name || (name === "autopilot" && flying);
      const look: Look = down ? "down" : this.hot === name ? "hover" : "idle";
      drawControlButton(ctx, l.buttons[name], symbol, look);
    }
    this.buttons.get("autopilot")?.setAttribute("aria-pressed", String(flying));
    // At least 16 CSS px on any screen (issue 27.6).
    const labelSize = Math.max(l.mode === "tall" ? 40 : 24, 16 / l.scale);
    const hot = this.sliding || this.hot === "slider";
    const sliderLabel = t("controls.trap_height");
    drawSlider(ctx, l.slider, this.slider, l.knobRadius, sliderLabel, hot, !g.won, labelSize);
    for (const [name, b] of this.buttons) {
      const key = name === "pause" && !g.paused ? "control.pause" : LABELS[name];
      setIfChanged(b, "aria-label", t(key, { height: 400 }));
    }
    this.buttons.get("pause")?.setAttribute("aria-pressed", String(!g.paused));
    setIfChanged(this.sliderEl, "aria-label", sliderLabel);
    const h = Math.round(g.trapHeight);
    setIfChanged(this.sliderEl, "aria-valuenow", String(h));
    setIfChanged(this.sliderEl, "aria-valuetext", t("control.height_value", { h }));
    this.sliderEl.setAttribute("aria-disabled", String(g.won || this.host.trapLocked()));
  }
}

/** Screen readers re-read a changed label: set it only when the words change. */
export function setIfChanged(el: HTMLElement, name: string, value: string): void {
  if (el.getAttribute(name) !== value) el.setAttribute(name, value);
}

/**
 * Elements in reading order of their drawn boxes: rows top to bottom (a box whose centre
 * lies within a row's height joins it), left to right in a row; `first` (the upright slider,
 * standing left of everything in the side layout) before all when `firstLeads`.
 */
function readingOrder(
  items: Array<[HTMLElement, Rect]>,
  first: HTMLElement,
  firstLeads: boolean,
): HTMLElement[] {
  const rest = firstLeads ? items.filter(([el]) => el !== first) : items;
  const byCentre = [...rest].sort(([, a], [, b]) => a.y + a.h / 2 - (b.y + b.h / 2));
  const rows: Array<Array<[HTMLElement, Rect]>> = [];
  let bottom = -Infinity;
  for (const item of byCentre) {
    const [, r] = item;
    if (r.y + r.h / 2 > bottom || !rows.length) {
      rows.push([item]);
      bottom = r.y + r.h;
    } else {
      rows[rows.length - 1].push(item);
    }
  }
  const order = rows.flatMap((row) => row.sort(([, a], [, b]) => a.x - b.x).map(([el]) => el));
  return firstLeads ? [first, ...order] : order;
}
