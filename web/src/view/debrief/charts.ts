/**
 * The debrief's two charts (issue 36), pure drawing from the debrief document: the class's
 * paths in the (N, T) plane on log-log axes with T = Tc(N), the condensate shaded below it,
 * one curve a student coloured by atoms kept, the won games' ends marked on the line, the
 * best game on top (a picked or the viewer's own game over all); and the trap height
 * against time of the same games.
 */
import { scaleRgb, scoreColor } from "./colors";
import { drawOrder, tcOf, type Debrief, type DebriefGame, type Tr } from "./model";
import { fitted, font, word, type DrawnWord } from "./text";

export interface Box {
  x: number;
  y: number;
  w: number;
  h: number;
}

export interface ChartOptions {
  tr: Tr;
  locale: string;
  /** A game drawn over all, thick with a dark edge (a picked archetype, or the viewer's). */
  highlight?: number | null;
  /** The viewer's own game: the others are drawn faint (the class's cloud). */
  focus?: number | null;
  /** The least size of the smallest words (ticks), px: a projector's, for the back row. */
  minSmall?: number;
}

/** What a chart drew: its plot, its words, the entries of its curves in drawing order. */
export interface ChartDrawn {
  plot: Box;
  words: DrawnWord[];
  curves: number[];
  /** Where each won game's end was marked (canvas px), by entry. */
  ends: Record<number, [number, number]>;
}

const BG = "rgb(250,249,245)";
const PLOT_BG = "rgb(255,255,255)";
const INK = "rgb(20,20,25)";
const CONDENSATE = "rgb(200,222,248)";
const TC_LINE = "rgb(25,60,150)";
const EDGE = "rgb(0,0,0)";
/** The smallest words drawn (a phone's chart); a projector's are far larger. */
export const MIN_TEXT = 14;

/** The titles' size: an 18th of the chart's height or a 24th of its width (ticks and
 * legends at three quarters of it: 25 px on a 1080-line projector's debrief). */
export function textSize(r: Box, minSmall = 0): number {
  const fromBox = Math.floor(Math.min(r.h / 18, r.w / 24));
  return Math.max(MIN_TEXT, fromBox, Math.ceil(minSmall / 0.75));
}

function logFrac(v: number, lo: number, hi: number): number {
  return (Math.log(v) - Math.log(lo)) / (Math.log(hi) - Math.log(lo));
}

/** The (N, T) ranges: around the games' paths (the line and the start in view), so the
 * class's strategies spread over the plot rather than crowd its corner. */
export function ranges(doc: Debrief): { n: [number, number]; t: [number, number] } {
  const law = doc.law;
  let [nLo, tLo, tHi] = [law.n0, law.t0, law.t0];
  for (const g of doc.games) {
    const p = g.path;
    if (!p) continue;
    for (let i = 0; i < p.n.length; i++) {
      nLo = Math.min(nLo, p.n[i]);
      tLo = Math.min(tLo, p.t[i]);
      tHi = Math.max(tHi, p.t[i]);
    }
  }
  nLo = Math.max(1, 0.8 * nLo);
  tLo = Math.min(tLo, tcOf(law, nLo));
  return { n: [nLo, 1.15 * Math.max(law.n0, 2)], t: [Math.max(0.8 * tLo, 1e-12), 1.25 * tHi] };
}

/** Ticks of a log axis, at most 6: the finest of 1-9, 1-2-5, 1-3 or 1 per decade that fits
 * (a class's N from 30 to 49 gets 30, 40, 50, not 50 alone). */
export function logTicks(lo: number, hi: number): number[] {
  const digits = [1, 2, 3, 4, 5, 6, 7, 8, 9];
  for (const mantissas of [digits, [1, 2, 5], [1, 3], [1]]) {
    const ticks: number[] = [];
    for (let k = Math.floor(Math.log10(lo)); k <= Math.ceil(Math.log10(hi)); k++)
      for (const m of mantissas) ticks.push(m * Math.pow(10, k));
    const inside = ticks.filter((t) => t >= lo && t <= hi);
    if (inside.length <= 6) return inside;
  }
  return [lo, hi];
}

function tickText(v: number, locale: string): string {
  return new Intl.NumberFormat(locale, { maximumSignificantDigits: 3 }).format(v);
}

/** Title, legend row and the plot's box inside a chart's rectangle. */
function frame(
  ctx: CanvasRenderingContext2D,
  r: Box,
  title: string,
  words: DrawnWord[],
  fs: number,
  bottom: number,
): Box {
  ctx.fillStyle = BG;
  ctx.fillRect(r.x, r.y, r.w, r.h);
  const size = fitted(ctx, title, fs, r.w - fs, MIN_TEXT);
  word(ctx, words, title, size, INK, r.x + r.w / 2, r.y + fs * 0.7, "center");
  const left = Math.floor(2.8 * fs);
  const top = Math.ceil(bottom - r.y + 0.4 * fs);
  const plot = { x: r.x + left, y: r.y + top, w: r.w - left - fs, h: r.h - top - 2.3 * fs };
  ctx.fillStyle = PLOT_BG;
  ctx.fillRect(plot.x, plot.y, plot.w, plot.h);
  return plot;
}

function axisNames(
  ctx: CanvasRenderingContext2D,
  words: DrawnWord[],
  r: Box,
  plot: Box,
  x: string,
  y: string,
  fs: number,
): void {
  const small = Math.floor(0.8 * fs);
  const xs = fitted(ctx, x, small, plot.w, MIN_TEXT);
  word(ctx, words, x, xs, INK, plot.x + plot.w / 2, r.y + r.h - 0.55 * fs, "center");
  // Turned a quarter in the left margin, from the plot's top to the chart's foot (nothing
  // else is drawn in that strip: the ticks' words end right of it).
  const span = r.y + r.h - 4 - plot.y;
  const middle = plot.y + span / 2;
  ctx.save();
  ctx.translate(r.x + 0.5 * fs, middle);
  ctx.rotate(-Math.PI / 2);
  const ys = fitted(ctx, y, small, span, MIN_TEXT);
  const drawn: DrawnWord[] = [];
  word(ctx, drawn, y, ys, INK, 0, 0, "center");
  ctx.restore();
  // Its box is the word's, upright.
  for (const d of drawn) words.push({ ...d, x: r.x, y: middle - d.w / 2, w: d.h, h: d.w });
}

/** A curve through points, with a dark edge if `edge`. */
function stroke(
  ctx: CanvasRenderingContext2D,
  pts: Array<[number, number]>,
  color: string,
  width: number,
  edge: boolean,
): void {
  const line = (c: string, w: number) => {
    ctx.strokeStyle = c;
    ctx.lineWidth = w;
    ctx.beginPath();
    pts.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    ctx.stroke();
  };
  ctx.lineJoin = "round";
  ctx.lineCap = "round";
  if (edge) line(EDGE, width + 4);
  line(color, width);
}

function dot(ctx: CanvasRenderingContext2D, x: number, y: number, r: number, fill: string): void {
  ctx.fillStyle = EDGE;
  ctx.beginPath();
  ctx.arc(x, y, r + 2, 0, 2 * Math.PI);
  ctx.fill();
  ctx.fillStyle = fill;
  ctx.beginPath();
  ctx.arc(x, y, r, 0, 2 * Math.PI);
  ctx.fill();
}

function curveStyle(g: DebriefGame, doc: Debrief, o: ChartOptions, lw: number) {
  const lit = g.entry === o.highlight || g.entry === o.focus;
  const best = g.entry === doc.archetypes.best;
  const faint = o.focus !== null && o.focus !== undefined && !lit;
  return {
    color: scoreColor(g.score, doc.max_score),
    width: lit ? 2.2 * lw : best ? 1.6 * lw : lw,
    edge: lit || (best && !faint),
    alpha: faint ? 0.35 : 1,
  };
}

/** A legend item: a swatch (the colour scale, a line, a band, a dot) and its words. */
type Item = { text: string; kind: "scale" | "line" | "bar" | "dot" };

/** The legend under the title, its items flowing in rows at one readable size; returns the
 * y under its last row. Drawn only if `draw` (measured first, to place the plot). */
function legendFlow(
  ctx: CanvasRenderingContext2D,
  words: DrawnWord[],
  r: Box,
  fs: number,
  items: Item[],
  o: ChartOptions,
  max: number,
  draw: boolean,
): number {
  const small = Math.floor(0.8 * fs);
  const swatch = (k: Item["kind"]) => (k === "scale" ? 5 * fs : 1.1 * fs);
  const maxText = tickText(max, o.locale);
  ctx.font = font(small);
  const width = (it: Item) =>
    swatch(it.kind) +
    0.3 * fs +
    ctx.measureText(it.text).width +
    (it.kind === "scale" ? ctx.measureText(`0 ${maxText}`).width + 0.6 * fs : 0);
  const row = 1.25 * fs;
  let [x, y] = [r.x + fs / 2, r.y + 2.05 * fs];
  for (const it of items) {
    const w = width(it);
    if (x > r.x + fs / 2 && x + w > r.x + r.w - fs / 2) [x, y] = [r.x + fs / 2, y + row];
    if (draw) drawItem(ctx, words, it, x, y, fs, small, maxText);
    x += w + 0.7 * fs;
  }
  return y + 0.75 * fs;
}

function drawItem(
  ctx: CanvasRenderingContext2D,
  words: DrawnWord[],
  it: Item,
  x: number,
  y: number,
  fs: number,
  small: number,
  maxText: string,
): void {
  if (it.kind === "scale") {
    x += word(ctx, words, it.text, small, INK, x, y, "left") + 0.3 * fs;
    x += word(ctx, words, "0", small, INK, x, y, "left") + 0.15 * fs;
    const barW = 5 * fs;
    for (let i = 0; i < barW; i++) {
      const [r, g, b] = scaleRgb(i / barW);
      ctx.fillStyle = `rgb(${r},${g},${b})`;
      ctx.fillRect(x + i, y - 0.3 * fs, 1.5, 0.6 * fs);
    }
    word(ctx, words, maxText, small, INK, x + barW + 0.15 * fs, y, "left");
    return;
  }
  const sw = 1.1 * fs;
  if (it.kind === "line")
    stroke(
      ctx,
      [
        [x, y],
        [x + sw, y],
      ],
      TC_LINE,
      Math.max(3, fs / 8),
      false,
    );
  else if (it.kind === "bar") {
    ctx.fillStyle = CONDENSATE;
    ctx.fillRect(x, y - 0.35 * fs, sw, 0.7 * fs);
  } else dot(ctx, x + sw / 2, y, Math.max(2, fs / 12) * 1.6, scoreColor(1, 1));
  word(ctx, words, it.text, small, INK, x + sw + 0.3 * fs, y, "left");
}

function pathItems(o: ChartOptions): Item[] {
  return [
    { text: o.tr("debrief.scale"), kind: "scale" },
    { text: o.tr("chart.legend.tc_line"), kind: "line" },
    { text: o.tr("chart.legend.condensate"), kind: "bar" },
    { text: o.tr("debrief.legend_end"), kind: "dot" },
  ];
}

/** Both charts' plots start under the paths chart's legend (the two read side by side). */
function legendBottom(
  ctx: CanvasRenderingContext2D,
  r: Box,
  fs: number,
  o: ChartOptions,
  max: number,
) {
  return legendFlow(ctx, [], r, fs, pathItems(o), o, max, false);
}

/** The class's paths in the (N, T) plane. */
export function drawPaths(
  ctx: CanvasRenderingContext2D,
  r: Box,
  doc: Debrief,
  o: ChartOptions,
): ChartDrawn {
  const fs = textSize(r, o.minSmall);
  const words: DrawnWord[] = [];
  ctx.save();
  ctx.beginPath();
  ctx.rect(r.x, r.y, r.w, r.h);
  ctx.clip();
  const bottom = legendBottom(ctx, r, fs, o, doc.max_score);
  const plot = frame(ctx, r, o.tr("debrief.paths"), words, fs, bottom);
  const range = ranges(doc);
  const px = (n: number, t: number): [number, number] => [
    plot.x + plot.w * logFrac(n, ...range.n),
    plot.y + plot.h - plot.h * logFrac(t, ...range.t),
  ];
  legendFlow(ctx, words, r, fs, pathItems(o), o, doc.max_score, true);
  ctx.save();
  ctx.beginPath();
  ctx.rect(plot.x, plot.y, plot.w, plot.h);
  ctx.clip();
  const [a, b] = [
    px(range.n[0], tcOf(doc.law, range.n[0])),
    px(range.n[1], tcOf(doc.law, range.n[1])),
  ];
  ctx.fillStyle = CONDENSATE;
  ctx.beginPath();
  ctx.moveTo(...a);
  ctx.lineTo(...b);
  ctx.lineTo(b[0], plot.y + plot.h);
  ctx.lineTo(a[0], plot.y + plot.h);
  ctx.closePath();
  ctx.fill();
  stroke(ctx, [a, b], TC_LINE, Math.max(3, fs / 8), false);
  const order = drawOrder(doc, o.focus ?? o.highlight ?? null);
  const lw = Math.max(2, fs / 12);
  const ends: Record<number, [number, number]> = {};
  for (const g of order) {
    const p = g.path!;
    const s = curveStyle(g, doc, o, lw);
    ctx.globalAlpha = s.alpha;
    stroke(
      ctx,
      p.n.map((n, i) => px(n, p.t[i])),
      s.color,
      s.width,
      s.edge,
    );
    if (g.won) {
      const end = px(p.n[p.n.length - 1], p.t[p.t.length - 1]);
      ends[g.entry] = end;
      dot(ctx, end[0], end[1], s.edge ? lw * 2.2 : lw * 1.6, s.color);
    }
  }
  ctx.globalAlpha = 1;
  ctx.restore();
  ticks(ctx, words, plot, fs, o.locale, range, px);
  axisNames(ctx, words, r, plot, o.tr("chart.axis.atoms"), o.tr("chart.axis.temperature"), fs);
  ctx.strokeStyle = INK;
  ctx.lineWidth = 2;
  ctx.strokeRect(plot.x, plot.y, plot.w, plot.h);
  ctx.restore();
  return { plot, words, curves: order.map((g) => g.entry), ends };
}

function ticks(
  ctx: CanvasRenderingContext2D,
  words: DrawnWord[],
  plot: Box,
  fs: number,
  locale: string,
  range: { n: [number, number]; t: [number, number] },
  px: (n: number, t: number) => [number, number],
): void {
  const small = Math.floor(0.75 * fs);
  ctx.fillStyle = INK;
  for (const v of logTicks(...range.n)) {
    const x = Math.round(px(v, range.t[0])[0]);
    ctx.fillRect(x - 1, plot.y + plot.h, 2, 6);
    word(ctx, words, tickText(v, locale), small, INK, x, plot.y + plot.h + 0.75 * fs, "center");
  }
  for (const v of logTicks(...range.t)) {
    const y = Math.round(px(range.n[0], v)[1]);
    ctx.fillRect(plot.x - 6, y - 1, 6, 2);
    word(ctx, words, tickText(v, locale), small, INK, plot.x - 8, y, "right");
  }
}

/** The trap height against time of the same games. */
export function drawHeights(
  ctx: CanvasRenderingContext2D,
  r: Box,
  doc: Debrief,
  o: ChartOptions,
): ChartDrawn {
  const fs = textSize(r, o.minSmall);
  const words: DrawnWord[] = [];
  ctx.save();
  ctx.beginPath();
  ctx.rect(r.x, r.y, r.w, r.h);
  ctx.clip();
  const bottom = legendBottom(ctx, r, fs, o, doc.max_score);
  const plot = frame(ctx, r, o.tr("debrief.heights"), words, fs, bottom);
  legendFlow(ctx, words, r, fs, pathItems(o).slice(0, 1), o, doc.max_score, true);
  const order = drawOrder(doc, o.focus ?? o.highlight ?? null);
  let kMax = 1;
  let hMax = 100;
  for (const g of order) {
    kMax = Math.max(kMax, g.path!.frames);
    for (const h of g.path!.h) hMax = Math.max(hMax, h);
  }
  hMax = Math.ceil((hMax * 1.05) / 50) * 50;
  const px = (k: number, h: number): [number, number] => [
    plot.x + (plot.w * k) / kMax,
    plot.y + plot.h - (plot.h * h) / hMax,
  ];
  ctx.save();
  ctx.beginPath();
  ctx.rect(plot.x, plot.y, plot.w, plot.h);
  ctx.clip();
  const lw = Math.max(2, fs / 12);
  for (const g of order) {
    const p = g.path!;
    const s = curveStyle(g, doc, o, lw);
    ctx.globalAlpha = s.alpha;
    stroke(
      ctx,
      p.k.map((k, i) => px(k, p.h[i])),
      s.color,
      s.width,
      s.edge,
    );
  }
  ctx.globalAlpha = 1;
  ctx.restore();
  const small = Math.floor(0.75 * fs);
  ctx.fillStyle = INK;
  for (const v of evenTicks(kMax)) {
    const x = Math.round(px(v, 0)[0]);
    ctx.fillRect(x - 1, plot.y + plot.h, 2, 6);
    word(ctx, words, tickText(v, o.locale), small, INK, x, plot.y + plot.h + 0.75 * fs, "center");
  }
  for (const v of evenTicks(hMax)) {
    const y = Math.round(px(0, v)[1]);
    ctx.fillRect(plot.x - 6, y - 1, 6, 2);
    word(ctx, words, tickText(v, o.locale), small, INK, plot.x - 8, y, "right");
  }
  const [xName, yName] = [o.tr("debrief.axis_time"), o.tr("debrief.axis_height")];
  axisNames(ctx, words, r, plot, xName, yName, fs);
  ctx.strokeStyle = INK;
  ctx.lineWidth = 2;
  ctx.strokeRect(plot.x, plot.y, plot.w, plot.h);
  ctx.restore();
  return { plot, words, curves: order.map((g) => g.entry), ends: {} };
}

/** 0 and round steps up to `hi` (at most 5 of them). */
export function evenTicks(hi: number): number[] {
  const raw = hi / 4;
  const mag = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw) ?? 10 * mag;
  const out: number[] = [];
  for (let v = 0; v <= hi * (1 + 1e-9); v += step) out.push(Number(v.toPrecision(6)));
  return out;
}
