/**
 * The open panel by keyboard (issue 48), and the win screen's buttons: a transparent
 * element over each target drawn on the canvas (a settings row, a button, the help's close,
 * Copy replay code, Store and Skip) gives it a place in the Tab order, a role, its words in
 * the reader's language and a row's value; the focused target is ringed on the canvas
 * (Panels.focused). Focus enters a panel when it opens and goes back to what opened it when
 * it closes. Pointer events pass through to the canvas, whose taps pick the targets as before.
 */
import type { Target } from "../view/overlays";
import { setIfChanged, type Controls } from "./controls";
import { NO_ZOOM, type Input } from "./input";
import type { Screen } from "./layout";
import { SOUND_ROW, type SettingsEditor } from "./options";
import type { Overlay, Panels } from "./panels";

export interface PanelKeysHost {
  readonly screen: Screen;
  readonly panels: Panels;
  readonly options: SettingsEditor;
  readonly targets: Target[];
  readonly targetsZoomed: boolean;
  /** Does what a tap on a target does. */
  readonly input: Input;
  /** The scene's controls (where the focus may go back to). */
  readonly controls: Controls;
  redraw(): void;
}

export class PanelKeys {
  private readonly layer = document.createElement("div");
  private open: Overlay = null;
  /** What had the focus when the panel opened. */
  private back: Element | null = null;

  constructor(
    private readonly host: PanelKeysHost,
    root: HTMLElement,
  ) {
    const layer = this.layer;
    layer.addEventListener("focusin", (ev) => {
      const el = ev.target as HTMLElement;
      const action = el.dataset.action!;
      // Tab onto a row selects it: the arrows change the row that has the focus.
      if (action.startsWith("row:")) host.options.row = +action.slice(4);
      host.panels.focused = el.matches(":focus-visible") ? action : null;
      host.redraw();
    });
    layer.addEventListener("focusout", () => {
      host.panels.focused = null;
      host.redraw();
    });
    root.append(layer);
  }

  /** After each drawn frame: the elements follow the open panel's targets. */
  sync(): void {
    const { panels, options } = this.host;
    const layer = this.layer;
    const open = panels.open;
    // A panel's targets; with none open, the win screen's buttons (copy the code, the name
    // box's Store and Skip): every button drawn on the canvas has its place in the Tab order.
    const items = this.host.targets.filter((x) => x.label);
    const before = document.activeElement;
    const inside = !before || before === document.body || layer.contains(before);
    const els = [...layer.children] as HTMLElement[];
    const actions = items.map((x) => x.action);
    if (els.map((el) => el.dataset.action).join() !== actions.join())
      layer.replaceChildren(...actions.map((a) => this.make(a)));
    items.forEach((x, k) => this.update(layer.children[k] as HTMLElement, x));
    layer.hidden = items.length === 0;
    const now = document.activeElement as HTMLElement | null;
    const want = layer.querySelector<HTMLElement>(`[data-action="row:${options.row}"]`);
    const first = want ?? (layer.firstElementChild as HTMLElement | null);
    if (open !== this.open) {
      const was = this.open;
      // The verify panel's paste box takes the focus itself, and keeps it.
      if (!was) this.back = before instanceof HTMLTextAreaElement ? null : before;
      this.open = open;
      if (!inside && before !== this.back) return;
      if (open) first?.focus();
      else this.restore(was!);
    } else if (
      open &&
      inside &&
      (now === document.body || now?.dataset.action?.startsWith("row:"))
    ) {
      // The arrows moved the selected row (or the focused element went): the focus follows.
      if (now !== want) first?.focus();
    }
  }

  /** The game opened the panel itself (the table after a name): the focus stays put. */
  stay(): void {
    this.open = this.host.panels.open;
    this.back = document.activeElement;
  }

  /** Back to what had the focus when the panel opened (a key with the focus nowhere: nowhere). */
  private restore(was: Exclude<Overlay, null>): void {
    const back = this.back;
    if (!(back instanceof HTMLElement) || back === document.body) return;
    if (back.isConnected && !back.hidden) back.focus();
    else this.host.controls.focus(was === "verify" ? "table" : was);
  }

  private make(action: string): HTMLElement {
    const el = document.createElement("div");
    el.className = "hit pk";
    el.tabIndex = 0;
    el.dataset.action = action;
    const row = action.startsWith("row:");
    // A row's activation steps its value (a box turns over); a button does what a tap does.
    const activate = () => {
      this.host.input.target(row ? "inc" + action.slice(3) : action);
      this.host.redraw();
    };
    el.onclick = activate;
    el.onkeydown = (ev) => {
      // Enter on a row is left to the screen's keys: it saves, as the footer says.
      if (ev.key === " " || (ev.key === "Enter" && !row)) {
        ev.preventDefault();
        ev.stopPropagation();
        activate();
      }
    };
    return el;
  }

  /** Place the element over its target; its role, name and value as drawn. */
  private update(el: HTMLElement, x: Target): void {
    const { screen, targetsZoomed, options } = this.host;
    screen.placeZoomed(el, x.rect, targetsZoomed ? screen.overlayZoom() : NO_ZOOM);
    const box = x.action === `row:${SOUND_ROW}`;
    const value = x.value;
    setIfChanged(el, "role", value === undefined ? "button" : box ? "checkbox" : "spinbutton");
    setIfChanged(el, "aria-label", x.label!);
    if (box) setIfChanged(el, "aria-checked", String(options.soundDraftOn));
    else if (value !== undefined) setIfChanged(el, "aria-valuetext", value);
  }
}
