/**
 * The debrief on a page (projector, lecturer, student): its heading, the picked game's
 * line, the two charts side by side, the best path in words for a screen reader, and two
 * games played side by side in step. Names reach the page only with textContent.
 */
import { drawHeights, drawPaths, type ChartDrawn } from "./charts";
import { describeBest, gameOf, nameOf, type Debrief, type PairDoc, type Tr } from "./model";
import { drawPair, frameAt, type PairDrawn } from "./pair";

export interface DebriefOptions {
  tr: Tr;
  locale: string;
  /** The page's own clock (tests give theirs). */
  now?: () => number;
  /** The least size of the charts' smallest words, px (a projector's: the back row's). */
  minSmall?: () => number;
  /** The pair's shared frame at each tick (the projector's: its replays' clock), else
   * the page's clock at the game's pace. */
  pairFrame?: (pair: PairDoc, elapsedMs: number) => number;
}

function element<K extends keyof HTMLElementTagNameMap>(
  tag: K,
  id: string,
  parent: HTMLElement,
): HTMLElementTagNameMap[K] {
  const made = document.createElement(tag);
  made.id = id;
  parent.append(made);
  return made;
}

/** A canvas sized to its box in CSS px, drawn in CSS px (sharp on any pixel ratio). */
function sized(canvas: HTMLCanvasElement): [CanvasRenderingContext2D, number, number] {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, canvas.clientWidth);
  const h = Math.max(1, canvas.clientHeight);
  if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
    canvas.width = Math.round(w * dpr);
    canvas.height = Math.round(h * dpr);
  }
  const ctx = canvas.getContext("2d")!;
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  return [ctx, w, h];
}

/** The smallest word's size and the words outside the canvas, kept on it (the tests:
 * readable at the back of a lecture hall, nothing cut off). */
function measured(canvas: HTMLCanvasElement, drawn: ChartDrawn, w: number, h: number): void {
  const sizes = drawn.words.map((x) => x.size);
  canvas.dataset.minText = String(Math.min(...sizes));
  const out = drawn.words.filter(
    (x) => x.x < -1 || x.y < -1 || x.x + x.w > w + 1 || x.y + x.h > h + 1,
  );
  canvas.dataset.outside = out.map((x) => x.text).join("|");
}

export class DebriefView {
  readonly root: HTMLElement;
  readonly heading: HTMLElement;
  readonly picked: HTMLElement;
  readonly paths: HTMLCanvasElement;
  readonly heights: HTMLCanvasElement;
  readonly described: HTMLElement;
  readonly pairCanvas: HTMLCanvasElement;
  doc: Debrief | null = null;
  highlight: number | null = null;
  focus: number | null = null;
  drawn: { paths: ChartDrawn; heights: ChartDrawn } | null = null;
  pairDrawn: PairDrawn | null = null;
  private pairDoc: PairDoc | null = null;
  private pairStart = 0;
  private pairTimer = 0;

  constructor(
    parent: HTMLElement,
    private readonly o: DebriefOptions,
  ) {
    this.root = element("section", "debrief", parent);
    this.root.hidden = true;
    this.heading = element("h2", "debrief-title", this.root);
    this.heading.textContent = o.tr("debrief.title");
    this.picked = element("p", "debrief-pick", this.root);
    const charts = element("div", "debrief-charts", this.root);
    this.paths = element("canvas", "debrief-paths", charts);
    this.heights = element("canvas", "debrief-heights", charts);
    for (const c of [this.paths, this.heights]) c.setAttribute("role", "img");
    this.described = element("p", "debrief-describe", this.root);
    this.paths.setAttribute("aria-describedby", "debrief-describe");
    this.pairCanvas = element("canvas", "debrief-pair", this.root);
    this.pairCanvas.setAttribute("role", "img");
    this.pairCanvas.hidden = true;
    // A page's layout may change the charts' size (a replay beside them): drawn anew.
    if (typeof ResizeObserver !== "undefined") {
      const watch = new ResizeObserver(() => this.draw());
      watch.observe(this.paths);
      watch.observe(this.heights);
    }
  }

  /** Show a debrief (highlight: a picked game; focus: the viewer's own, others faint). */
  show(doc: Debrief, highlight: number | null = null, focus: number | null = null): void {
    [this.doc, this.highlight, this.focus] = [doc, highlight, focus];
    this.root.hidden = false;
    const game = gameOf(doc, highlight);
    this.picked.textContent = game
      ? this.o.tr("debrief.picked", {
          name: nameOf(game, this.o.tr),
          score: game.score,
          frames: game.frames,
        })
      : "";
    this.described.textContent = describeBest(doc, this.o.tr, this.o.locale);
    this.paths.setAttribute("aria-label", this.o.tr("debrief.paths"));
    this.heights.setAttribute("aria-label", this.o.tr("debrief.heights"));
    this.draw();
  }

  hide(): void {
    this.root.hidden = true;
    delete this.root.dataset.drawnAt;
    this.setPair(null);
  }

  /** Redraw at the canvases' current sizes (after a resize too). */
  draw(): void {
    const doc = this.doc;
    if (!doc || this.root.hidden) return;
    const shown = (c: HTMLCanvasElement) => c.clientWidth > 0 && c.clientHeight > 0;
    const opts = {
      minSmall: this.o.minSmall?.() ?? 0,
      tr: this.o.tr,
      locale: this.o.locale,
      highlight: this.highlight,
      focus: this.focus,
    };
    const [pc, pw, ph] = sized(this.paths);
    const paths = drawPaths(pc, { x: 0, y: 0, w: pw, h: ph }, doc, opts);
    this.paths.dataset.curves = paths.curves.join(",");
    measured(this.paths, paths, pw, ph);
    let heights = this.drawn?.heights ?? null;
    if (shown(this.heights)) {
      // Not drawn while hidden (a phone's narrow screen, a replay beside the paths).
      const [hc, hw, hh] = sized(this.heights);
      heights = drawHeights(hc, { x: 0, y: 0, w: hw, h: hh }, doc, opts);
      measured(this.heights, heights, hw, hh);
    }
    this.drawn = { paths, heights: heights ?? paths };
    this.root.dataset.drawn = String((Number(this.root.dataset.drawn) || 0) + 1);
    // When it was drawn, on the machine's clock (the benchmark's close-to-draw time).
    this.root.dataset.drawnAt ??= String(Math.round(performance.timeOrigin + performance.now()));
  }

  /** Play two games side by side in step (null: stop). */
  setPair(pair: PairDoc | null): void {
    window.clearInterval(this.pairTimer);
    this.pairDoc = pair;
    this.pairCanvas.hidden = pair === null;
    this.root.classList.toggle("pairing", pair !== null);
    if (!pair) return;
    this.pairCanvas.setAttribute("aria-label", this.o.tr("debrief.side_by_side"));
    this.pairStart = this.now();
    this.tick();
    this.pairTimer = window.setInterval(() => this.tick(), 1000 / 30);
  }

  private now(): number {
    return this.o.now ? this.o.now() : performance.now();
  }

  private tick(): void {
    const pair = this.pairDoc;
    if (!pair || !this.doc) return;
    const k = (this.o.pairFrame ?? frameAt)(pair, this.now() - this.pairStart);
    const [ctx, w, h] = sized(this.pairCanvas);
    this.pairDrawn = drawPair(
      ctx,
      { x: 0, y: 0, w, h },
      pair,
      this.doc.law,
      k,
      this.o.tr,
      this.o.locale,
      this.o.minSmall?.() ?? 0,
    );
    this.pairCanvas.dataset.minText = String(Math.min(...this.pairDrawn.words.map((x) => x.size)));
    this.pairCanvas.dataset.frames = this.pairDrawn.shown.join(",");
    this.pairCanvas.dataset.frame = String(k);
    const last = Math.max(...pair.games.map((g) => g.path.frames));
    if (k >= last) window.clearInterval(this.pairTimer);
  }
}
