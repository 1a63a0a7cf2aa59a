/**
 * The scene's own controls: play/pause, restart, the trap slider, the chart button and
 * the tools (help, scores, settings, full screen). Drawn on the canvas; transparent
 * elements over them give keyboard focus, screen-reader labels and 44 px touch targets.
 */
import { HEIGHT_MAX, HEIGHT_MIN } from "../game/rules";
import * as C from "../view/colors";
import { atLeast, MIN_TARGET_CSS, type ControlName } from "../view/geometry";
import type { Look, SymbolName } from "../view/icons";
import { drawControlButton, drawSlider, SliderModel } from "../view/widgets";
import type { App } from "./app";

const LABELS: Record<ControlName, string> = {
  pause: "Play",
  restart: "Restart: new atoms, trap at 400, paused",
  chart: "Energy chart on or off",
  help: "Help: every control",
  table: "High-score table",
  settings: "Settings",
  fullscreen: "Full screen on or off",
};
const SLIDER_LABEL = "Trap height";
/** A click this soon after a handled press and release is that press's own click, ms. */
const CLICK_AFTER_PRESS_MS = 600;

export class Controls {
  /** The knob rests at the game's trap height (read when drawn) unless a drag holds it. */
  readonly slider = new SliderModel(HEIGHT_MIN, HEIGHT_MAX, () => this.app.game.trapHeight);
  private buttons = new Map<ControlName, HTMLButtonElement>();
  private sliderEl!: HTMLDivElement;
  private pressed: ControlName | null = null;
  private clickHandledAt = -Infinity;
  sliding = false;
  private hot: ControlName | "slider" | null = null;

  constructor(private readonly app: App) {}

  /** Transparent buttons over the drawn controls: focus, labels, touch targets. */
  build(root: HTMLElement): void {
    const layer = document.createElement("div");
    layer.className = "controls";
    root.append(layer);
    const make = (name: ControlName) => layer.append(this.button(name));
    (["pause", "restart"] as ControlName[]).forEach(make);
    // The slider comes after the two buttons in the tab order, as on screen.
    layer.append(this.sliderElement());
    (["chart", "help", "table", "settings", "fullscreen"] as ControlName[]).forEach(make);
  }

  private button(name: ControlName): HTMLButtonElement {
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
    s.setAttribute("aria-label", SLIDER_LABEL);
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
        const g = this.app.game;
        const h = { Home: HEIGHT_MIN, End: HEIGHT_MAX, PageUp: g.trapHeight + 50 }[k as "Home"];
        g.setTrapHeight(h ?? g.trapHeight - 50);
        this.app.heightChanged();
      }
    });
    this.sliderEl = s;
    return s;
  }

  private press(name: ControlName): void {
    const app = this.app;
    switch (name) {
      case "chart":
        app.act("energy");
        break;
      case "settings":
        if (app.overlay === "settings") app.options.close(false);
        else app.act("settings");
        break;
      default:
        app.act(name);
    }
  }

  private slideStart(ev: PointerEvent): void {
    if (this.app.game.won) return;
    ev.preventDefault();
    this.sliding = true;
    this.sliderEl.setPointerCapture?.(ev.pointerId);
    this.sliderEl.focus({ preventScroll: true });
    this.slideMove(ev);
  }

  private slideMove(ev: PointerEvent): void {
    if (!this.sliding) return;
    const [x] = this.app.screen.toLogical(ev.clientX, ev.clientY);
    const value = this.slider.valueAt(x, this.app.screen.layout.slider);
    this.app.game.setTrapHeight(value);
    this.slider.hold(value);
    this.app.heightChanged();
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
    const screen = this.app.screen;
    const l = screen.layout;
    const min = MIN_TARGET_CSS / l.scale;
    for (const [name, b] of this.buttons) screen.place(b, atLeast(l.buttons[name], min));
    const s = l.slider;
    const r = l.knobRadius;
    screen.place(
      this.sliderEl,
      atLeast({ x: s.x - r, y: s.y + s.h / 2 - r, w: s.w + 2 * r, h: 2 * r }, min),
    );
  }

  /** Draw the strip, buttons and slider, and keep the elements' states in step. */
  draw(ctx: CanvasRenderingContext2D): void {
    const l = this.app.screen.layout;
    const g = this.app.game;
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
    const labelSize = l.mode === "tall" ? 40 : 24;
    const hot = this.sliding || this.hot === "slider";
    drawSlider(ctx, l.slider, this.slider, l.knobRadius, SLIDER_LABEL, hot, !g.won, labelSize);
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
}
