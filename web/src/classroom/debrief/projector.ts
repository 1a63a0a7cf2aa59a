/**
 * The debrief on the projector: shown once the challenge is closed (never while it is
 * open: the lecturer's early look stays on the lecturer's page), redrawn when the lecturer
 * picks a game (highlighted, its name unless anonymous; its replay plays in the replay
 * box) and playing two games' replays side by side, in step, when the lecturer sets a pair.
 */
import { classBase } from "../common";
import {
  nameOf,
  type Debrief,
  type PairDoc,
  type Showing,
  type Tr,
} from "../../view/debrief/model";
import { frameAt } from "../../view/debrief/pair";
import { DebriefView } from "../../view/debrief/view";
import { PairReplays } from "./replays";

/** What the projector reads of a leaderboard message for the debrief. */
export interface BoardForDebrief {
  challenge?: number | null;
  open: boolean;
  entries: unknown[];
  debrief?: Showing;
}

export class ProjectorDebrief {
  readonly view: DebriefView;
  readonly replays: PairReplays;
  private readonly tr: Tr;
  private docKey = "";
  private pairKey = "";
  doc: Debrief | null = null;
  pair: PairDoc | null = null;
  /** performance.now() when the last debrief document was asked for, and first drawn. */
  asked = 0;
  firstDrawn = 0;

  constructor(
    parent: HTMLElement,
    tr: Tr,
    locale: string,
    /** The projector's own query (its key), for the API's addresses. */
    private readonly query: string,
  ) {
    // Ticks and legends at least 24 px on a 1080-line projector (in proportion on others).
    const minSmall = () => Math.round((24 * window.innerHeight) / 1080);
    // Two games' numbers follow their replays' shared clock (the page's, without them).
    const pairFrame = (pair: PairDoc, ms: number) => this.replays.step() ?? frameAt(pair, ms);
    this.view = new DebriefView(parent, { tr, locale, minSmall, pairFrame });
    this.tr = tr;
    this.replays = new PairReplays(this.view.pairCanvas, tr, locale);
    window.addEventListener("resize", () => this.view.draw());
  }

  /** Follow a leaderboard message; true while the debrief is shown. */
  take(board: BoardForDebrief): boolean {
    const shown = board.challenge !== null && board.challenge !== undefined && !board.open;
    document.body.classList.toggle("debriefing", shown);
    if (!shown) {
      [this.docKey, this.pairKey, this.doc, this.pair] = ["", "", null, null];
      this.view.hide();
      this.replays.set(null);
      return false;
    }
    const s = board.debrief ?? { anonymous: false, pick: null, pair: null };
    const key = `${board.challenge}:${s.anonymous}:${board.entries.length}`;
    if (key !== this.docKey) {
      this.docKey = key;
      void this.load(s);
    } else if (this.doc && s.pick !== this.view.highlight) {
      this.view.show(this.doc, s.pick);
      this.headPair();
    }
    const pairKey = s.pair ? `${key}:${s.pair.join(",")}` : "";
    if (pairKey !== this.pairKey) {
      this.pairKey = pairKey;
      void this.loadPair(pairKey);
    }
    return true;
  }

  private async load(s: Showing): Promise<void> {
    const key = this.docKey;
    this.asked = performance.now();
    const res = await fetch(classBase() + "/api/debrief" + this.query, { cache: "no-store" });
    if (!res.ok || key !== this.docKey) return;
    this.doc = (await res.json()) as Debrief;
    this.view.show(this.doc, this.doc.showing?.pick ?? s.pick);
    this.headPair();
    if (!this.firstDrawn) this.firstDrawn = performance.now();
  }

  private async loadPair(key: string): Promise<void> {
    if (!key) {
      this.pair = null;
      this.replays.set(null);
      this.view.setPair(null);
      return this.headPair();
    }
    const res = await fetch(classBase() + "/api/debrief/pair" + this.query, { cache: "no-store" });
    if (!res.ok || key !== this.pairKey) return;
    const pair = (await res.json()) as PairDoc;
    this.pair = pair;
    this.replays.set(pair);
    this.view.setPair(pair);
    this.headPair();
  }

  /** With a pair shown, the line over the charts names the two games played (not the
   * game picked before): the heading true to what is shown. */
  private headPair(): void {
    if (!this.pair || !this.doc) return;
    const names = this.pair.games.map((g) => nameOf(g, this.tr)).join(" · ");
    this.view.picked.textContent = this.tr("debrief.side_by_side") + ": " + names;
  }
}
