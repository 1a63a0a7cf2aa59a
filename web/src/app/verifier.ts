/**
 * The verify panel (key V, or "Verify codes..." under the score table): a lecturer pastes
 * replay codes (the first MAX_CODES are checked); each is replayed with the game's own
 * rules in a worker of its own (physics.worker.ts; the page's own loop where none runs), and
 * the verified ones are ranked by score (ties: fewer frames first), each bad one listed with
 * the reason (damaged, edited, other version, does not replay to the claimed score).
 * Closing the panel stops the run.
 */
import { activeTranslator, onLocaleChange, t, type Translator } from "../i18n";
import { coreBytes } from "../game/engine";
import { DAMAGED, EDITED, OTHER_VERSION, WRONG_SCORE } from "../game/replay";
import type { Zoom } from "./layout";
import type { Screen } from "./layout";
import { PLAY_RECT, type Rect } from "../view/geometry";
import { decode } from "../game/replaycode";
import { refused, replayed, type Checked, type Decoded } from "../runtime/verify-check";
import type { FromWorker, ToWorker } from "../runtime/worker-protocol";

export type { Checked } from "../runtime/verify-check";

/** Codes checked in one run at most: a class's worth (more pasted are left, with a notice). */
export const MAX_CODES = 100;

export interface VerifierHost {
  readonly screen: Screen;
  overlayZoom(): Zoom;
  say(text: string): void;
  notify(text: string): void;
  redraw(): void;
  /** A new verify worker, or null where none can run (the codes are then checked here). */
  makeWorker(): Worker | null;
}

/** Where the codes are pasted, in the play area's coordinates (logical px). */
export const PASTE_BOX: Rect = {
  x: PLAY_RECT.x + 30,
  y: PLAY_RECT.y + 64,
  w: PLAY_RECT.w - 60,
  h: 130,
};

export class Verifier {
  results: Checked[] = [];
  busy = false;
  readonly area: HTMLTextAreaElement;
  /** Ends the run under way (its worker, or the page's loop), or null. */
  private stop: (() => void) | null = null;
  /** Counts runs and cancels: a run whose number has passed is dropped. */
  private runs = 0;

  constructor(
    private readonly host: VerifierHost,
    root: HTMLElement,
  ) {
    const area = document.createElement("textarea");
    area.id = "codes";
    area.hidden = true;
    area.spellcheck = false;
    const words = (tr: Translator) => {
      area.setAttribute("aria-label", tr.t("verify.label"));
      area.placeholder = tr.t("verify.placeholder");
      area.dir = tr.direction;
    };
    words(activeTranslator());
    onLocaleChange(words);
    area.addEventListener("keydown", (ev) => {
      if (ev.key === "Escape") (ev.target as HTMLElement).blur();
      ev.stopPropagation(); // typing here is not the game's keys
    });
    root.append(area);
    this.area = area;
  }

  /** Show or hide the paste box with the panel; place it where the panel draws it. */
  show(shown: boolean): void {
    const a = this.area;
    if (a.hidden === !shown) return;
    a.hidden = !shown;
    if (!shown) this.cancel();
    if (shown) {
      this.place();
      a.focus({ preventScroll: true });
    }
  }

  place(): void {
    if (this.area.hidden) return;
    const z = this.host.overlayZoom();
    this.host.screen.placeZoomed(this.area, PASTE_BOX, z);
    const scale = this.host.screen.layout.scale * z.k;
    this.area.style.fontSize = `${Math.max(16, 18 * scale)}px`;
  }

  /** Verify the codes pasted (spaces and lines between them), then rank them. */
  async run(): Promise<void> {
    if (this.busy) return;
    const codes = firstWords(this.area.value, MAX_CODES + 1);
    if (codes.length > MAX_CODES) {
      codes.length = MAX_CODES;
      this.host.notify(t("verify.capped", { n: MAX_CODES }));
    }
    this.busy = true;
    this.results = [];
    this.host.redraw();
    if (!(await this.checkAll(codes))) return; // the panel was closed
    this.results = ranked(this.results);
    this.busy = false;
    const good = this.results.filter((r) => r.verdict).length;
    this.host.say(t("verify.summary", { good, n: codes.length }));
    this.host.redraw();
  }

  /** Stop the run under way (the panel closed): its worker ends, its results are dropped. */
  cancel(): void {
    this.runs += 1;
    const stop = this.stop;
    this.stop = null;
    this.busy = false;
    this.results = [];
    stop?.();
  }

  /** Each code's outcome into results as it comes; false if cancelled first. */
  private async checkAll(texts: string[]): Promise<boolean> {
    const run = ++this.runs;
    const codes: Decoded[] = [];
    for (const text of texts) {
      const decoded = await decode(text).then(
        (recording) => ({ code: text, recording }),
        (err: unknown) => refused(text, err),
      );
      if (run !== this.runs) return false; // closed while decoding
      codes.push(decoded);
    }
    if (codes.length === 0) return true;
    return new Promise((resolve) => {
      const worker = this.startWorker();
      if (worker === null) void this.checkHere(codes, resolve);
      else this.checkIn(worker, codes, resolve);
    });
  }

  /** The codes replayed in the worker, each outcome posted back as it comes. */
  private checkIn(worker: Worker, codes: Decoded[], resolve: (done: boolean) => void): void {
    const end = () => {
      worker.onmessage = worker.onerror = null;
      worker.terminate();
    };
    this.stop = () => {
      end();
      resolve(false);
    };
    // The worker broke: the codes it had not answered are checked here.
    const failed = (message: string) => {
      end();
      console.warn(`evapcool: the verify worker failed (${message}); checking here.`);
      void this.checkHere(codes.slice(this.results.length), resolve);
    };
    worker.onmessage = (ev: MessageEvent<FromWorker>) => {
      const msg = ev.data;
      if (msg.type === "failed") failed(msg.message);
      if (msg.type !== "verified") return; // its hello
      this.results.push(msg.checked);
      this.host.redraw();
      if (this.results.length < codes.length) return;
      end();
      this.stop = null;
      resolve(true);
    };
    worker.onerror = (ev) => {
      ev.preventDefault();
      failed(ev.message);
    };
    worker.postMessage({ type: "verify", core: coreBytes(), codes } satisfies ToWorker);
  }

  private startWorker(): Worker | null {
    try {
      return this.host.makeWorker();
    } catch (err) {
      console.warn(`evapcool: no verify worker here (${(err as Error).message}).`);
      return null;
    }
  }

  /** The page's own loop: one code at a time, the page drawn between. */
  private async checkHere(codes: Decoded[], resolve: (done: boolean) => void): Promise<void> {
    let cancelled = false;
    this.stop = () => {
      cancelled = true;
      resolve(false);
    };
    for (const code of codes) {
      this.results.push(replayed(code));
      this.host.redraw();
      await new Promise((next) => setTimeout(next, 0)); // let the page draw
      if (cancelled) return;
    }
    this.stop = null;
    resolve(true);
  }

  /** The lines the panel shows: ranked verified codes, then the rejected ones. */
  lines(): string[] {
    if (this.busy) return [t("verify.replaying", { n: this.results.length + 1 })];
    let rank = 0;
    return this.results.map((r) => {
      const short = r.code.length > 18 ? `${r.code.slice(0, 14)}...` : r.code;
      if (!r.verdict) {
        const key = Object.hasOwn(REASON_KEYS, r.reason) ? REASON_KEYS[r.reason] : null;
        return t("verify.rejected", { reason: key ? t(key) : r.reason, code: short });
      }
      rank += 1;
      const v = r.verdict;
      const args = { rank, n: v.score, frames: v.frames, edition: r.edition, code: short };
      return t("verify.verified", args);
    });
  }
}

/** The refusals' words (protocol names shared with the class server) by message key. */
const REASON_KEYS: Record<string, string> = {
  [DAMAGED]: "reason.damaged",
  [EDITED]: "reason.edited",
  [OTHER_VERSION]: "reason.other_version",
  [WRONG_SCORE]: "reason.wrong_score",
};

/** Verified first, by score (higher first), then frames (fewer first); rejected last. */
function ranked(results: Checked[]): Checked[] {
  const good = results.filter((r) => r.verdict);
  const bad = results.filter((r) => !r.verdict);
  good.sort((a, b) => b.verdict!.score - a.verdict!.score || a.verdict!.frames - b.verdict!.frames);
  return [...good, ...bad];
}

/** The first n words of text (codes are separated by spaces and lines), without splitting
 * all of a huge paste. */
function firstWords(text: string, n: number): string[] {
  const out: string[] = [];
  for (const m of text.matchAll(/\S+/g)) {
    out.push(m[0]);
    if (out.length >= n) break;
  }
  return out;
}
