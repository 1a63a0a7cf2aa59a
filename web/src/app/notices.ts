/**
 * Short messages shown for a few seconds at the bottom of the play area, what a screen
 * reader is told (a polite live region) and the canvas's text alternative (the status).
 * Python's twin: `src/evapcool/app/notices.py` (docs/twins.md).
 */
import { formatNumber, t } from "../i18n";
import type { GameLike } from "../runtime/remote";

/** How long a notice stays on screen, s of the applet's own clock. */
export const NOTICE_SECONDS = 8;
/** Notices at once (a damaged store can give several, each must be seen). */
export const NOTICE_MAX = 5;
/** Notices shown at once; the rest follow page by page, counted on the last line. */
const NOTICE_PAGE = NOTICE_MAX - 1;
/** Notices kept at most: beyond, the newest are counted on the last kept line instead
 * (each was spoken when it came), so the first is always shown. */
export const NOTICE_KEPT = 100;
/** The last line while more notices wait for their turn. */
export const moreNotices = (n: number): string => t("page.more_notices", { n });
/** The status line is rewritten at most this often, ms (screen readers read it on change). */
const STATUS_EVERY_MS = 500;

export class Notices {
  /** [text, shown from, shown until] (applet clock, s). */
  private list: Array<[string, number, number]> = [];
  /** The last kept line when full: it counts itself and `dropped` more. */
  private summary: [string, number, number] | null = null;
  /** Notices past NOTICE_KEPT not kept, counted on the summary line. */
  private dropped = 0;

  constructor(
    private readonly live: HTMLElement,
    /** The applet's clock, s. */
    private readonly clock: () => number,
    /** Called when the picture changes (a new notice must be drawn). */
    private readonly changed: () => void,
  ) {}

  /** Show text for NOTICE_SECONDS; when a page of notices is full, after the ones before it. */
  notify(text: string): void {
    this.changed();
    const now = this.clock();
    this.list = this.list.filter(([, , until]) => until > now);
    if (this.summary && !this.list.includes(this.summary)) [this.summary, this.dropped] = [null, 0];
    this.say(text);
    if (this.list.length >= NOTICE_KEPT) {
      // Full: the last kept line says how many more came (they were spoken).
      this.summary ??= this.list[this.list.length - 1];
      this.dropped += 1;
      this.summary[0] = moreNotices(this.dropped + 1);
      return;
    }
    const page = Math.floor(this.list.length / NOTICE_PAGE);
    const from = page === 0 ? now : Math.max(now, this.list[page * NOTICE_PAGE - 1][2]);
    this.list.push([text, from, from + NOTICE_SECONDS]);
  }

  /** Forget every notice (a replay presented on the projector shows none). */
  clear(): void {
    [this.list, this.summary, this.dropped] = [[], null, 0];
    this.changed();
  }

  /** The notices showing now, oldest first, and a line counting those still to come. */
  get visible(): string[] {
    const now = this.clock();
    const shown = this.list.filter(([, from, until]) => from <= now && until > now);
    const summary = this.summary && this.summary[1] > now ? this.dropped : 0;
    const waiting = this.list.filter(([, from]) => from > now).length + summary;
    const lines = shown.map(([text]) => text);
    return waiting > 0 ? [...lines, moreNotices(waiting)] : lines;
  }

  /** Tell a screen reader (politely: after what it is reading). */
  say(text: string): void {
    const live = this.live;
    // A changed text node is announced even when the words repeat.
    live.textContent = "";
    const node = document.createElement("p");
    node.textContent = text;
    live.append(node);
    while (live.childNodes.length > 1) live.firstChild?.remove();
  }
}

/** The canvas's text alternative: what is on screen, in words (updated when it changes). */
export class StatusLine {
  private last = "";
  private at = -Infinity;

  constructor(private readonly el: HTMLElement) {}

  /** Write the game's state; true if a change waits to be written (draw again). */
  update(g: GameLike): boolean {
    const sim = g.sim;
    const state = g.won
      ? t("page.status_condensed", { n: g.score ?? 0 })
      : t(g.allEscaped ? "lose.all_escaped" : g.paused ? "page.status_paused" : "status.playing");
    const text = t("page.status", {
      state,
      n: sim.nTrapped,
      h: Math.round(g.trapHeight),
      t: fmt(sim.temperature),
      tc: fmt(sim.criticalTemperature),
      below: sim.temperature < sim.criticalTemperature ? "yes" : "no",
    });
    if (text === this.last) return false;
    const now = performance.now();
    if (now - this.at < STATUS_EVERY_MS) return true;
    this.at = now;
    this.last = text;
    this.el.textContent = text;
    return false;
  }
}

function fmt(v: number): string {
  return Number.isFinite(v) ? formatNumber(Math.round(v * 10) / 10) : "-";
}
