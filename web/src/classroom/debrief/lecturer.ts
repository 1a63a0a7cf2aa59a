/**
 * The lecturer's debrief controls: look at the debrief early (while the challenge is open,
 * on this page only), hide the names, pick an archetype (its button names the student it
 * will project: its curve highlighted and its replay on the projector), set two entries
 * side by side (pickers listing names and atoms).
 */
import { classBase } from "../common";
import { archetypeList, gameOf, nameOf, type Debrief, type Tr } from "../../view/debrief/model";
import { DebriefView } from "../../view/debrief/view";

function made<K extends keyof HTMLElementTagNameMap>(
  tag: K,
  parent: HTMLElement,
  id = "",
): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  if (id) e.id = id;
  parent.append(e);
  return e;
}

export class LecturerDebrief {
  readonly box: HTMLElement;
  readonly early: HTMLElement;
  readonly picks: HTMLElement;
  readonly anonymous: HTMLInputElement;
  readonly pairA: HTMLSelectElement;
  readonly pairB: HTMLSelectElement;
  readonly pair: HTMLElement;
  readonly view: DebriefView;
  doc: Debrief | null = null;

  constructor(
    parent: HTMLElement,
    private readonly tr: Tr,
    locale: string,
    private readonly headers: Record<string, string>,
    /** POST to the server (the page says any refusal and refreshes). */
    private readonly post: (path: string, body: unknown) => Promise<unknown>,
    /** Where the charts go (after the controls when not given). */
    viewParent: HTMLElement | null = null,
  ) {
    this.box = made("section", parent, "debrief-controls");
    const head = made("h2", this.box);
    head.textContent = tr("console.lecturer.debrief_head");
    const show = made("button", this.box, "debrief-show");
    show.type = "button";
    show.textContent = tr("debrief.show");
    show.onclick = () => void this.refresh();
    const label = made("label", this.box);
    this.anonymous = document.createElement("input");
    this.anonymous.type = "checkbox";
    this.anonymous.id = "debrief-anonymous";
    label.append(this.anonymous, " ", tr("debrief.anonymous"));
    this.anonymous.onchange = () =>
      void this.post("/api/debrief", { anonymous: this.anonymous.checked });
    this.early = made("p", this.box, "debrief-early");
    this.picks = made("p", this.box, "debrief-picks");
    const pair = made("p", this.box, "debrief-pair-pick");
    pair.hidden = true; // until the debrief has two games to set side by side
    this.pair = pair;
    const labelA = made("label", pair);
    labelA.append(tr("console.lecturer.pair_left"), " ");
    this.pairA = made("select", labelA, "debrief-pair-a");
    const labelB = made("label", pair);
    labelB.append(tr("console.lecturer.pair_right"), " ");
    this.pairB = made("select", labelB, "debrief-pair-b");
    const go = made("button", pair, "debrief-pair-go");
    go.type = "button";
    go.textContent = tr("debrief.pair");
    go.onclick = () =>
      void this.post("/api/debrief", {
        pair: [Number(this.pairA.value), Number(this.pairB.value)],
      });
    const charts = made("section", viewParent ?? this.box, "debrief-view");
    this.view = new DebriefView(charts, { tr, locale });
  }

  /** The debrief as the lecturer sees it (names always; early while the challenge is open). */
  async refresh(): Promise<void> {
    const res = await fetch(classBase() + "/api/debrief", {
      headers: this.headers,
      cache: "no-store",
    });
    if (!res.ok) return;
    const doc = (await res.json()) as Debrief;
    this.doc = doc;
    const open = await this.isOpen();
    this.early.textContent = open ? this.tr("debrief.early") : "";
    this.anonymous.checked = doc.showing?.anonymous ?? false;
    this.picks.replaceChildren();
    for (const a of archetypeList(doc, this.tr)) {
      const b = made("button", this.picks);
      const game = gameOf(doc, a.entry);
      b.type = "button";
      b.dataset.kind = a.kind;
      b.dataset.entry = String(a.entry);
      b.textContent = this.tr("console.lecturer.pick_named", {
        kind: a.label,
        name: game ? nameOf(game, this.tr) : "?",
        score: game ? game.score : "",
      });
      if (doc.showing?.pick === a.entry) b.className = "on";
      b.onclick = () => void this.post("/api/debrief", { pick: a.entry });
    }
    for (const select of [this.pairA, this.pairB]) {
      const was = select.value;
      select.replaceChildren();
      for (const g of doc.games) {
        const o = made("option", select);
        o.value = String(g.entry);
        o.textContent = this.tr("console.lecturer.pair_option", {
          rank: g.rank,
          name: nameOf(g, this.tr),
          score: g.score,
        });
      }
      if (was) select.value = was;
    }
    this.pair.hidden = doc.games.length < 2;
    if (!this.pairB.value || this.pairB.value === this.pairA.value)
      this.pairB.selectedIndex = Math.min(1, doc.games.length - 1);
    this.view.show(doc, doc.showing?.pick ?? null);
  }

  private async isOpen(): Promise<boolean> {
    const res = await fetch(classBase() + "/api/leaderboard", { cache: "no-store" });
    return res.ok && Boolean(((await res.json()) as { open: boolean }).open);
  }
}
