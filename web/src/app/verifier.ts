/**
 * The verify panel (key V, or "Verify codes..." under the score table): a lecturer pastes
 * any number of replay codes; each is replayed in the page with the game's own rules and
 * the verified ones are ranked by score (ties: fewer frames first), each bad one listed
 * with the reason (damaged, edited, other version, does not replay to the claimed score).
 */
import { activeTranslator, onLocaleChange, t, type Translator } from "../i18n";
import { makeSimulation } from "../game/engine";
import {
  DAMAGED,
  EDITED,
  OTHER_VERSION,
  ReplayError,
  verify,
  WRONG_SCORE,
  type Verdict,
} from "../game/replay";
import { decode } from "../game/replaycode";
import type { Zoom } from "./layout";
import type { Screen } from "./layout";
import { PLAY_RECT, type Rect } from "../view/geometry";

/** One pasted code's outcome. */
export interface Checked {
  code: string;
  verdict: Verdict | null;
  edition: string;
  reason: string;
}

export interface VerifierHost {
  readonly screen: Screen;
  overlayZoom(): Zoom;
  say(text: string): void;
  redraw(): void;
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
    if (shown) {
      this.place();
      a.focus({ preventScroll: true });
    }
  }

  place(): void {
    if (this.area.hidden) return;
    const z = this.host.overlayZoom();
    const r = PASTE_BOX;
    this.host.screen.place(this.area, {
      x: z.x + (r.x - z.cx) * z.k,
      y: z.y + (r.y - z.cy) * z.k,
      w: r.w * z.k,
      h: r.h * z.k,
    });
    const scale = this.host.screen.layout.scale * z.k;
    this.area.style.fontSize = `${Math.max(16, 18 * scale)}px`;
  }

  /** Verify every code pasted (one per line, blank lines and spaces ignored), then rank. */
  async run(): Promise<void> {
    if (this.busy) return;
    const codes = this.area.value.split(/\s+/).filter((c) => c.length > 0);
    this.busy = true;
    this.results = [];
    this.host.redraw();
    for (const code of codes) {
      this.results.push(await check(code));
      this.host.redraw();
      await new Promise((resolve) => setTimeout(resolve, 0)); // let the page draw
    }
    this.results = ranked(this.results);
    this.busy = false;
    const good = this.results.filter((r) => r.verdict).length;
    this.host.say(t("verify.summary", { good, n: codes.length }));
    this.host.redraw();
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

async function check(code: string): Promise<Checked> {
  try {
    const rec = await decode(code);
    return { code, verdict: verify(rec, makeSimulation), edition: rec.edition, reason: "" };
  } catch (err) {
    const reason = err instanceof ReplayError ? err.reason : (err as Error).message;
    return { code, verdict: null, edition: "", reason };
  }
}

/** Verified first, by score (higher first), then frames (fewer first); rejected last. */
function ranked(results: Checked[]): Checked[] {
  const good = results.filter((r) => r.verdict);
  const bad = results.filter((r) => !r.verdict);
  good.sort((a, b) => b.verdict!.score - a.verdict!.score || a.verdict!.frames - b.verdict!.frames);
  return [...good, ...bad];
}
