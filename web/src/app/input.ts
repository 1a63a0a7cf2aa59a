/**
 * The page's input: the key table applied in the applet's modes (a question pending, the
 * name box, the settings screen, play), taps on the drawn panels, and the window's events
 * (resize, pixel ratio, another tab's scores, hiding, full screen).
 * Python's twin: `src/evapcool/app/input.py` (docs/twins.md).
 */
import { cutName, NAME_CODE_POINTS } from "../game/highscores";
import { atLeast, contains, MIN_TARGET_CSS } from "../view/geometry";
import type { Target } from "../view/overlays";
import { actionFor, type Action } from "./bindings";
import type { Hints } from "./hints";
import type { Screen } from "./layout";
import type { SettingsEditor } from "./options";
import type { Panels } from "./panels";
import type { GameLike } from "../runtime/remote";
import type { Scoreboard } from "./scoring";
import type { Verifier } from "./verifier";

/** What input reaches (the composition root wires it; app.ts). */
export interface InputHost {
  readonly screen: Screen;
  readonly canvas: HTMLCanvasElement;
  readonly nameInput: HTMLInputElement;
  readonly game: GameLike;
  readonly hints: Hints;
  readonly scores: Scoreboard;
  readonly options: SettingsEditor;
  readonly panels: Panels;
  readonly verifier: Verifier;
  /** The drawn tap targets of the last frame, and whether they were drawn zoomed. */
  readonly targets: Target[];
  readonly targetsZoomed: boolean;
  act(action: Action): void;
  restart(): void;
  resize(): void;
  /** Something changed: the next frame draws. */
  redraw(): void;
  /** A key was pressed (touch screens with a keyboard get key hints from then on). */
  keyPressed(): void;
  say(text: string): void;
  /** The frame clock starts again (the page was hidden). */
  resetClock(): void;
}

/** Targets drawn on the scene itself (the name box's buttons) are not zoomed. */
export const NO_ZOOM = { k: 1, cx: 0, cy: 0, x: 0, y: 0 };

export class Input {
  private pausedByHiding = false;

  constructor(private readonly host: InputHost) {}

  /** A key press (KeyboardEvent.key); true if the applet used it. */
  key(rawKey: string): boolean {
    const app = this.host;
    const scores = app.scores;
    const key = rawKey.toLowerCase();
    if (scores.confirmReset) {
      if (key === "y") scores.clearTable(true);
      else if (key === "n" || key === "escape") scores.clearTable(false);
      return true; // nothing else happens until the question is answered
    }
    if (scores.nameBoxOpen) return false; // the input field has the keyboard
    if (app.panels.open === "settings") {
      app.options.key(key);
      return key !== "tab"; // Tab moves between the screen's rows and buttons (panelkeys.ts)
    }
    const action = actionFor(rawKey);
    if (!action) return false;
    app.act(action);
    return true;
  }

  wire(): void {
    const app = this.host;
    for (const type of ["keydown", "keyup", "pointerdown", "pointermove", "pointerup", "input"]) {
      window.addEventListener(type, () => app.redraw(), { capture: true, passive: true });
    }
    window.addEventListener("resize", () => app.resize());
    // Another tab stored a score: show the table as it is now.
    window.addEventListener("storage", (ev) => {
      if (ev.key !== null && ev.key !== app.scores.table.key) return;
      app.scores.reload();
      app.redraw();
    });
    window.visualViewport?.addEventListener("resize", () => app.resize());
    this.watchRatio();
    this.wireKeys();
    app.canvas.addEventListener("pointerdown", (ev) => this.tap(ev));
    document.addEventListener("visibilitychange", () => this.visibility());
    document.addEventListener("fullscreenchange", () => app.resize());
  }

  /** A window moved to a screen of another pixel ratio: redraw sharp for that one. */
  private watchRatio(): void {
    if (typeof matchMedia !== "function") return;
    matchMedia(`(resolution: ${window.devicePixelRatio}dppx)`).addEventListener(
      "change",
      () => {
        this.host.resize();
        this.watchRatio();
      },
      { once: true },
    );
  }

  private wireKeys(): void {
    const app = this.host;
    const nameInput = app.nameInput;
    window.addEventListener("keydown", (ev) => {
      if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
      app.keyPressed();
      const target = ev.target as HTMLElement | null;
      if (target === nameInput) return;
      // Enter on a focused button presses that button (its own click); on the settings
      // screen Enter saves wherever the focus is, as its footer says (issue 27.1).
      const onButton = target instanceof HTMLButtonElement;
      if (
        ev.key === "Enter" &&
        onButton &&
        !app.scores.readyForNext &&
        app.panels.open !== "settings"
      )
        return;
      if (this.key(ev.key)) ev.preventDefault();
    });
    // The table keeps whole characters (cutName); this bounds typing in UTF-16 units.
    nameInput.maxLength = NAME_CODE_POINTS * 2;
    nameInput.addEventListener("keydown", (ev) => {
      if (ev.isComposing) return;
      if (ev.key === "Enter") {
        ev.preventDefault();
        app.scores.storeName(nameInput.value);
      } else if (ev.key === "Escape") {
        ev.preventDefault();
        app.scores.skipName();
      }
      ev.stopPropagation();
    });
    nameInput.addEventListener("input", () => {
      const cut = cutName(nameInput.value);
      if (cut !== nameInput.value) nameInput.value = cut;
    });
  }

  /** Hidden: pause (and say so on return); the clock restarts either way. */
  private visibility(): void {
    const app = this.host;
    if (document.hidden && !app.game.paused) {
      app.game.paused = true;
      this.pausedByHiding = true;
    } else if (!document.hidden && this.pausedByHiding) {
      this.pausedByHiding = false;
      app.say(app.hints.hiddenPause);
    }
    app.resetClock();
  }

  /** A tap or click on the canvas: the drawn targets first, then closing the help. */
  private tap(ev: PointerEvent): void {
    const app = this.host;
    const [lx, ly] = app.screen.toLogical(ev.clientX, ev.clientY);
    const z = app.targetsZoomed ? app.screen.overlayZoom() : NO_ZOOM;
    const [x, y] = [z.cx + (lx - z.x) / z.k, z.cy + (ly - z.y) / z.k];
    const hit = pickTarget(app.targets, x, y, MIN_TARGET_CSS / (app.screen.layout.scale * z.k));
    if (hit) {
      ev.preventDefault();
      this.target(hit.action);
    } else if (app.panels.open === "help") {
      app.panels.open = null;
    }
  }

  /** A drawn panel's target ("name" or "name:row") was tapped (or its element pressed). */
  target(action: string): void {
    const app = this.host;
    const [name, arg] = action.split(":");
    const row = Number(arg);
    switch (name) {
      case "close":
        app.panels.open = null;
        break;
      case "dec":
      case "inc":
        app.options.change(row, name === "inc" ? 1 : -1);
        break;
      case "row":
        app.options.select(row);
        break;
      case "save":
        app.options.close(true);
        break;
      case "cancel":
        app.options.close(false);
        break;
      case "copylink":
      case "saverun":
        app.act(name);
        break;
      case "clear":
        app.act("clear");
        break;
      case "yes":
        app.scores.clearTable(true);
        break;
      case "no":
        app.scores.clearTable(false);
        break;
      case "next":
        app.restart();
        break;
      case "copycode":
        app.act("copycode");
        break;
      case "verifycodes":
        app.act("verify");
        break;
      case "verifyrun":
        void app.verifier.run();
        break;
      case "store":
        app.scores.storeName(app.nameInput.value);
        break;
      case "skip":
        app.scores.skipName();
        break;
      case "tableclose":
        app.panels.open = null;
        app.scores.confirmReset = false;
        break;
    }
  }
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
