/**
 * The projector's podium and pages (issue 45): the top three of a closed round (names, or
 * "Student {rank}" in anonymous mode, and their atoms), and the board shown a page at a
 * time when it does not fit, every entry in turn. Text only; names go in with textContent.
 */
import { boardCells, shownName, type BoardEntry } from "./board";
import { fill, type Words } from "./common";

/** The podium's places: first, second, third (fewer with fewer entries). */
export function podiumOf(entries: readonly BoardEntry[]): BoardEntry[] {
  return entries.slice(0, 3);
}

/** Fill the podium list with the top three (their place, name or rank, atoms). */
export function drawPodium(list: HTMLElement, entries: readonly BoardEntry[], words: Words): void {
  list.replaceChildren();
  for (const e of podiumOf(entries)) {
    const li = document.createElement("li");
    li.className = "place-" + e.rank;
    li.dataset.entryRank = String(e.rank);
    const place = document.createElement("span");
    place.className = "place";
    place.textContent = String(e.rank);
    const name = document.createElement("span");
    name.className = "who";
    name.textContent = shownName(words, e.name, e.rank);
    const atoms = document.createElement("span");
    atoms.className = "atoms";
    atoms.textContent = fill(words["console.projector.atoms"], { n: e.score });
    li.append(place, name, atoms);
    list.append(li);
  }
}

/** The text under a paged board: "11–20 of 30" (1-based, inclusive). */
export function pageText(words: Words, first: number, last: number, n: number): string {
  return fill(words["console.projector.page"], { first, last, n });
}

/** The pages of `n` rows, `per` to a page: [first, end) of each. */
export function pages(n: number, per: number): [number, number][] {
  const size = Math.max(1, per);
  const out: [number, number][] = [];
  for (let i = 0; i < n; i += size) out.push([i, Math.min(n, i + size)]);
  return out.length ? out : [[0, 0]];
}

/**
 * The board's rows a page at a time: as many as fit its box, the next page every few
 * seconds, back to the first after the last (the room sees every entry).
 */
export class BoardPager {
  private page = 0;
  private rows: HTMLTableRowElement[] = [];
  private spans: [number, number][] = [[0, 0]];

  constructor(
    private readonly box: HTMLElement,
    private readonly table: HTMLTableElement,
    private readonly label: HTMLElement,
    private readonly words: Words,
  ) {}

  /** New rows (the header row first in the table): paged from the current page. */
  take(entries: readonly BoardEntry[], row: (cells: (string | number)[]) => HTMLTableRowElement) {
    this.rows = entries.map((e) => row(boardCells(e, this.words)));
    this.layout();
  }

  /** Count what fits, then show the current page (after a resize too). */
  layout(): void {
    for (const r of this.rows) r.hidden = false;
    const bottom = this.box.getBoundingClientRect().bottom;
    const fit = this.rows.filter((r) => r.getBoundingClientRect().bottom <= bottom + 0.5).length;
    this.spans = pages(this.rows.length, fit);
    if (this.page >= this.spans.length) this.page = 0;
    this.show();
  }

  /** The next page (the first after the last). */
  next(): void {
    this.page = (this.page + 1) % this.spans.length;
    this.show();
  }

  private show(): void {
    const [a, b] = this.spans[this.page];
    this.rows.forEach((r, i) => (r.hidden = i < a || i >= b));
    const paged = this.spans.length > 1;
    // Its line is kept when empty: the board's box must not change with the pages.
    this.label.style.visibility = paged ? "visible" : "hidden";
    this.label.textContent = paged ? pageText(this.words, a + 1, b, this.rows.length) : "";
    this.label.dataset.page = String(this.page);
    this.label.dataset.pages = String(this.spans.length);
  }
}
