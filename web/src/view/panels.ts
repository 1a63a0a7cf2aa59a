/**
 * The charts beside the scene that show why evaporation cools (the desktop's panels):
 * `EnergyPanel`, a smoothed histogram of the trapped atoms' energies with the cut m g H
 * and the equilibrium law N P(E), P(E) ~ E^(3/2) exp(-E/kT), kT = 2/5 T (SPEC 4);
 * `PathPanel`, the run in the (N, T) plane on log-log axes with T = Tc(N) and the
 * condensate region shaded. Both record once per frame the physics advanced.
 * Python's twin: `src/evapcool/view/panels.py` (docs/twins.md).
 */
import { decimalMark, formatNumber, t } from "../i18n";
import type { AtomArrays, SimLike } from "../game/sim";
import { rect, type Rect } from "./geometry";
import { drawText, textWidth, fitSize } from "./text";

const BG = "rgb(244,243,238)";
const PLOT_BG = "rgb(255,255,255)";
const INK = "rgb(25,25,30)";
const BAR = "rgb(60,150,200)";
const CURVE = "rgb(20,20,20)";
const CUT = "rgb(205,25,25)";
const ESCAPE_TINT = "rgb(252,226,226)";
const CONDENSATE = "rgb(188,214,246)";
const TC_LINE = "rgb(25,60,150)";
const PATH = "rgb(215,95,10)";
export const KT_FRACTION = 0.4;
const GAMMA_5_2 = 0.75 * Math.sqrt(Math.PI);
/** The legends (the desktop's panels'), drawn in the header, never over the plot. */
const ENERGY_LEGEND: readonly LegendItem[] = [
  { swatch: "bar", color: BAR, text: "chart.legend.atoms" },
  { swatch: "line", color: CURVE, text: "chart.legend.equilibrium" },
  { swatch: "bar", color: CUT, text: "chart.legend.cut" },
];
const PATH_LEGEND: readonly LegendItem[] = [
  { swatch: "dot", color: PATH, text: "chart.legend.your_path" },
  { swatch: "line", color: TC_LINE, text: "chart.legend.tc_line" },
  { swatch: "bar", color: CONDENSATE, text: "chart.legend.condensate" },
];
/** The class's other paths under the student's own, after a class challenge (issue 36). */
const CLOUD = "rgba(70,80,110,0.35)";
const CLOUD_LEGEND: readonly LegendItem[] = [
  ...PATH_LEGEND,
  { swatch: "line", color: "rgb(150,155,170)", text: "page.class_debrief_cloud" },
];

const fontSize = (r: Rect) => Math.max(18, Math.min(30, Math.floor(r.h / 11)));

/** The plotting area inside a panel rectangle (room for title, header, ticks and labels). */
export function margins(r: Rect, top = Math.floor(1.5 * fontSize(r))): Rect {
  const fs = fontSize(r);
  const left = Math.floor(2.6 * fs);
  const right = Math.floor(0.8 * fs);
  const bottom = Math.floor(2.1 * fs);
  return rect(
    r.x + left,
    r.y + top,
    Math.max(10, r.w - left - right),
    Math.max(10, r.h - top - bottom),
  );
}

export function niceStep(span: number, target = 5): number {
  const raw = span / Math.max(1, target);
  const mag = Math.pow(10, Math.floor(Math.log10(raw)));
  for (const m of [1, 2, 2.5, 5, 10]) if (m * mag >= raw) return m * mag;
  return 10 * mag;
}

export function logTicks(lo: number, hi: number): number[] {
  const k0 = Math.floor(Math.log10(lo));
  const k1 = Math.ceil(Math.log10(hi));
  let ticks: number[] = [];
  for (const mantissas of [[1, 2, 5], [1, 3], [1]]) {
    ticks = [];
    for (let k = k0; k <= k1; k++) for (const m of mantissas) ticks.push(m * Math.pow(10, k));
    ticks = ticks.filter((t) => t >= lo && t <= hi);
    if (ticks.length <= 7) return ticks;
  }
  return ticks;
}

export function tickText(v: number): string {
  if (v >= 1000) return v.toFixed(0);
  return String(Number(v.toPrecision(3))).replace(".", decimalMark());
}

/** A panel's title at the top, centred, shrunk (to 12) to fit a long translation. */
function panelTitle(ctx: CanvasRenderingContext2D, r: Rect, title: string, size: number): void {
  const fitted = fitSize(ctx, title, size, r.w - 8, 12);
  drawText(ctx, title, fitted, INK, r.x + r.w / 2, r.y + 4, "midtop", true);
}

/** Energy 1/2 m v^2 + m g y of each atom in `a`, into `out`. */
export function energies(a: AtomArrays, g: number, out: Float64Array): Float64Array {
  for (let i = 0; i < a.count; i++) {
    const m = a.mass[i];
    out[i] = 0.5 * m * (a.vx[i] * a.vx[i] + a.vy[i] * a.vy[i]) + m * g * a.y[i];
  }
  return out;
}

/** A legend entry: a swatch ("bar", "line" or "dot") in a colour, and its words. */
export interface LegendItem {
  swatch: "bar" | "line" | "dot";
  color: string;
  text: string;
}

/** Where a panel put its plot and its words: every word lies outside the plot, where the
 * bars, curves and lines are drawn (clipped to it), so no line ever crosses a word. */
export interface PanelDrawn {
  plot: Rect;
  words: Rect[];
}

const SWATCH_W = 22;

/** The header under the title: the legend flowing in rows, then the live readout. */
function header(
  ctx: CanvasRenderingContext2D,
  r: Rect,
  items: readonly LegendItem[],
  readout: string,
  fs: number,
  small: number,
): { bottom: number; draw: () => Rect[] } {
  const pad = Math.floor(0.5 * fs);
  const line = Math.ceil(small * 0.6875 * 1.45);
  const gap = Math.floor(small * 0.9);
  const placed: Array<[LegendItem, number, number, number]> = [];
  let x = r.x + pad;
  let y = r.y + Math.floor(1.5 * fs);
  for (const item of items) {
    const w = SWATCH_W + 6 + textWidth(ctx, t(item.text), small);
    if (x > r.x + pad && x + w > r.x + r.w - pad) {
      x = r.x + pad;
      y += line;
    }
    placed.push([item, x, y, w]);
    x += w + gap;
  }
  const readoutY = y + line;
  return {
    bottom: readoutY + line + Math.floor(small * 0.3),
    draw: () => {
      const words: Rect[] = [];
      for (const [item, ix, iy, w] of placed) {
        const cy = iy + line / 2;
        ctx.fillStyle = item.color;
        if (item.swatch === "bar") ctx.fillRect(ix, iy + 3, SWATCH_W, line - 6);
        else if (item.swatch === "line") ctx.fillRect(ix, cy - 1.5, SWATCH_W, 3);
        else {
          ctx.beginPath();
          ctx.arc(ix + SWATCH_W / 2, cy, 6, 0, 2 * Math.PI);
          ctx.fill();
        }
        const tw = drawText(ctx, t(item.text), small, INK, ix + SWATCH_W + 6, cy, "midleft");
        words.push(rect(ix + SWATCH_W + 6, iy, Math.ceil(tw), line));
        void w;
      }
      if (readout) {
        const tw = drawText(ctx, readout, small, INK, r.x + pad, readoutY + line / 2, "midleft");
        words.push(rect(r.x + pad, readoutY, Math.ceil(tw), line));
      }
      return words;
    },
  };
}

function blank(ctx: CanvasRenderingContext2D, r: Rect, plot: Rect): void {
  ctx.fillStyle = BG;
  ctx.fillRect(r.x, r.y, r.w, r.h);
  ctx.fillStyle = PLOT_BG;
  ctx.fillRect(plot.x, plot.y, plot.w, plot.h);
}

/** The x axis's name, centred under the plot at the panel's bottom edge. */
function xLabel(ctx: CanvasRenderingContext2D, text: string, size: number, plot: Rect, r: Rect) {
  drawText(ctx, text, size, INK, plot.x + plot.w / 2, r.y + r.h - 2, "midbottom");
}

function yLabel(ctx: CanvasRenderingContext2D, text: string, size: number, x: number, cy: number) {
  ctx.save();
  ctx.translate(x, cy);
  ctx.rotate(-Math.PI / 2);
  drawText(ctx, text, size, INK, 0, 0, "midtop");
  ctx.restore();
}

export class EnergyPanel {
  edges: Float64Array | null = null;
  private history: Float64Array[] = [];
  private gen = -1;
  nTrapped = 0;
  temperature = 0;
  cutEnergy = Infinity;
  yMax = 1;
  private buf = new Float64Array(0);

  constructor(readonly windowFrames = 30) {}

  /** The gas condensed: the chart holds the win's frame, as the path chart does (the
   * settling after it is the condensate's picture, not a temperature). */
  held = false;

  reset(): void {
    this.edges = null;
    this.history = [];
    this.gen = -1;
    this.yMax = 1;
    this.held = false;
  }

  private chooseBins(sim: SimLike, e: Float64Array, n: number, cut: number): Float64Array {
    let eMax = 1.8 * sim.initialTemperature;
    if (Number.isFinite(cut)) eMax = Math.max(eMax, cut);
    for (let i = 0; i < n; i++) eMax = Math.max(eMax, e[i]);
    eMax *= 1.1;
    if (!(Number.isFinite(eMax) && eMax > 0)) eMax = 1;
    const bins = Math.min(40, Math.max(12, Math.round(2 * Math.sqrt(Math.max(1, sim.nAtoms)))));
    return Float64Array.from({ length: bins + 1 }, (_, k) => (eMax * k) / bins);
  }

  /** Add this frame's histogram of the trapped atoms `atoms` of `sim`. */
  record(sim: SimLike, atoms: AtomArrays, generation: number): void {
    if (generation !== this.gen) {
      this.reset();
      this.gen = generation;
    }
    if (this.held) return;
    this.held = sim.won;
    if (this.buf.length < atoms.count) this.buf = new Float64Array(atoms.count);
    const e = energies(atoms, sim.gravity, this.buf);
    let m = 0;
    for (let i = 0; i < atoms.count; i++) m += atoms.mass[i];
    m = atoms.count ? m / atoms.count : 1;
    this.cutEnergy = m * sim.gravity * sim.trapHeight;
    if (!this.edges) this.edges = this.chooseBins(sim, e, atoms.count, this.cutEnergy);
    const nb = this.edges.length - 1;
    const eMax = this.edges[nb];
    const counts =
      this.history.length >= this.windowFrames ? this.history.shift()! : new Float64Array(nb);
    counts.fill(0);
    for (let i = 0; i < atoms.count; i++) {
      const v = e[i];
      if (v < 0 || v > eMax) continue;
      counts[Math.min(nb - 1, Math.floor((v / eMax) * nb))] += 1;
    }
    this.history.push(counts);
    this.nTrapped = sim.nTrapped;
    this.temperature = sim.temperature;
    const h = this.heights();
    let target = 1;
    for (const v of h) target = Math.max(target, v);
    for (const v of this.equilibriumCounts()) target = Math.max(target, v);
    target *= 1.15;
    this.yMax = target > this.yMax ? target : this.yMax + 0.03 * (target - this.yMax);
  }

  /** Bar heights: mean atoms per bin over the smoothing window. */
  heights(): Float64Array {
    const nb = this.edges ? this.edges.length - 1 : 0;
    const out = new Float64Array(nb);
    if (!this.history.length) return out;
    for (const c of this.history) for (let k = 0; k < nb; k++) out[k] += c[k];
    for (let k = 0; k < nb; k++) out[k] /= this.history.length;
    return out;
  }

  get kt(): number {
    return KT_FRACTION * this.temperature;
  }

  /** N P(E) in atoms per unit energy at the current temperature. */
  density(e: number): number {
    const kt = this.kt;
    if (kt <= 0 || this.nTrapped === 0) return 0;
    e = Math.max(0, e);
    return (this.nTrapped * Math.pow(e, 1.5) * Math.exp(-e / kt)) / (GAMMA_5_2 * Math.pow(kt, 2.5));
  }

  equilibriumCounts(): number[] {
    if (!this.edges) return [];
    const w = this.edges[1] - this.edges[0];
    const out: number[] = [];
    for (let k = 0; k + 1 < this.edges.length; k++) {
      out.push(this.density(0.5 * (this.edges[k] + this.edges[k + 1])) * w);
    }
    return out;
  }

  /** Where the last draw put the plot and the words. */
  drawn: PanelDrawn | null = null;

  draw(ctx: CanvasRenderingContext2D, r: Rect): void {
    const fs = fontSize(r);
    const small = Math.floor(fs * 0.85);
    const readout = this.edges
      ? t("chart.readout_energy", {
          n: formatNumber(this.nTrapped),
          t: tickText(this.temperature),
        })
      : "";
    const head = header(ctx, r, ENERGY_LEGEND, readout, fs, small);
    const plot = margins(r, head.bottom - r.y);
    ctx.save();
    ctx.beginPath();
    ctx.rect(r.x, r.y, r.w, r.h);
    ctx.clip();
    blank(ctx, r, plot);
    panelTitle(ctx, r, t("chart.energies"), fs);
    const words = head.draw();
    xLabel(ctx, t("chart.axis.energy"), small, plot, r);
    yLabel(ctx, t("chart.axis.per_bin"), small, r.x + 4, plot.y + plot.h / 2);
    if (!this.edges) {
      drawText(
        ctx,
        t("chart.no_data"),
        small,
        INK,
        plot.x + plot.w / 2,
        plot.y + plot.h / 2,
        "center",
      );
    } else {
      const eMax = this.edges[this.edges.length - 1];
      const ex = (e: number) => plot.x + (plot.w * e) / eMax;
      const cy = (c: number) => plot.y + plot.h - (plot.h * c) / this.yMax;
      ctx.save();
      ctx.beginPath();
      ctx.rect(plot.x + 2, plot.y + 2, plot.w - 4, plot.h - 4);
      ctx.clip();
      const cx = Number.isFinite(this.cutEnergy) ? Math.round(ex(this.cutEnergy)) : plot.x + plot.w;
      ctx.fillStyle = ESCAPE_TINT;
      ctx.fillRect(cx, plot.y, plot.x + plot.w - cx, plot.h);
      ctx.fillStyle = BAR;
      const h = this.heights();
      h.forEach((v, i) => {
        if (v <= 0) return;
        const x0 = Math.round(ex(this.edges![i]));
        const x1 = Math.round(ex(this.edges![i + 1]));
        const top = Math.round(cy(v));
        ctx.fillRect(x0 + 1, top, Math.max(1, x1 - x0 - 2), plot.y + plot.h - top);
      });
      if (this.nTrapped && this.kt > 0) {
        const w = this.edges[1] - this.edges[0];
        ctx.strokeStyle = CURVE;
        ctx.lineWidth = 3;
        ctx.beginPath();
        for (let k = 0; k < 120; k++) {
          const e = (eMax * k) / 119;
          const x = ex(e);
          const y = cy(this.density(e) * w);
          if (k === 0) ctx.moveTo(x, y);
          else ctx.lineTo(x, y);
        }
        ctx.stroke();
      }
      ctx.fillStyle = CUT;
      ctx.fillRect(cx - 1, plot.y, 3, plot.h);
      ctx.restore();
      ctx.fillStyle = INK;
      const step = niceStep(eMax);
      for (let v = 0; v <= eMax * (1 + 1e-9); v += step) {
        const x = Math.round(ex(v));
        ctx.fillRect(x - 1, plot.y + plot.h, 2, 5);
        drawText(ctx, tickText(v), small, INK, x, plot.y + plot.h + 6, "midtop");
      }
      const ystep = niceStep(this.yMax, 4);
      for (let v = 0; v < this.yMax; v += ystep) {
        const y = Math.round(cy(v));
        ctx.fillStyle = INK;
        ctx.fillRect(plot.x - 5, y - 1, 5, 2);
        drawText(ctx, tickText(v), small, INK, plot.x - 6, y, "midright");
      }
      if (cx > plot.x + plot.w) {
        // The cut lies beyond the energies shown: a red arrowhead at the plot's right edge.
        const ax = plot.x + plot.w - 3;
        ctx.fillStyle = CUT;
        ctx.beginPath();
        ctx.moveTo(ax, plot.y + 14);
        ctx.lineTo(ax - 12, plot.y + 6);
        ctx.lineTo(ax - 12, plot.y + 22);
        ctx.closePath();
        ctx.fill();
      }
    }
    this.drawn = { plot, words };
    ctx.strokeStyle = INK;
    ctx.lineWidth = 2;
    ctx.strokeRect(plot.x, plot.y, plot.w, plot.h);
    ctx.restore();
  }
}

export class PathPanel {
  private gen = -1;
  private done = false;
  n: number[] = [];
  t: number[] = [];
  /** The physics time (frames) of each point: the class debrief's paths sample whole ones. */
  time: number[] = [];
  n0 = 1;
  t0 = 1;
  tc0 = 0.75;
  exponent = 2 / 3;
  nRange: [number, number] = [1, 1.25];
  tRange: [number, number] = [0.1, 1.6];
  /** Other games' paths drawn faint under this one (the class's, after a challenge). */
  cloud: Array<{ n: number[]; t: number[] }> = [];

  /** Show a finished game's path over the class's (its law: Tc0, N0, p, T0). */
  showClass(
    law: { n0: number; tc0: number; exponent: number; t0: number },
    own: { n: number[]; t: number[] },
    cloud: Array<{ n: number[]; t: number[] }>,
  ): void {
    this.reset();
    this.done = true;
    [this.n0, this.t0, this.tc0, this.exponent] = [law.n0, law.t0, law.tc0, law.exponent];
    [this.n, this.t, this.cloud] = [own.n, own.t, cloud];
    // Around the paths (the class's strategies spread over the plot, not in its corner).
    let [nLo, tLo, tHi] = [this.n0, this.t0, this.t0];
    for (const p of [own, ...cloud])
      p.n.forEach((n, k) => {
        [nLo, tLo, tHi] = [Math.min(nLo, n), Math.min(tLo, p.t[k]), Math.max(tHi, p.t[k])];
      });
    nLo = Math.max(1, 0.8 * nLo);
    this.nRange = [nLo, 1.15 * Math.max(this.n0, 2)];
    this.tRange = [Math.max(0.8 * Math.min(tLo, this.tc(nLo)), 1e-12), 1.25 * tHi];
  }

  reset(): void {
    this.gen = -1;
    this.n = [];
    this.t = [];
    this.time = [];
    this.done = false;
  }

  private adopt(sim: SimLike, generation: number): void {
    this.reset();
    this.gen = generation;
    this.n0 = sim.nAtoms;
    this.t0 = sim.initialTemperature;
    this.exponent = sim.tcExponent;
    const n = sim.nTrapped;
    this.tc0 =
      n > 0 ? sim.criticalTemperature / Math.pow(n / this.n0, this.exponent) : 0.75 * this.t0;
    this.nRange = [1, 1.25 * Math.max(this.n0, 2)];
    const tLo = 0.5 * Math.min(this.tc(1), this.t0);
    this.tRange = [Math.max(tLo, 1e-12), Math.max(1.6 * this.t0, 2 * tLo)];
  }

  tc(n: number): number {
    return this.tc0 * Math.pow(n / this.n0, this.exponent);
  }

  /** Add the current (N, T); nothing for an empty cup or after the win. */
  record(sim: SimLike, generation: number): boolean {
    if (generation !== this.gen) this.adopt(sim, generation);
    if (this.done) return false;
    const n = sim.nTrapped;
    const t = sim.temperature;
    if (n <= 0 || !(t > 0 && Number.isFinite(t))) return false;
    this.n.push(n);
    this.t.push(t);
    this.time.push(sim.time);
    if (sim.won) this.done = true;
    return true;
  }

  private frac(v: number, [lo, hi]: [number, number]): number {
    return (Math.log(v) - Math.log(lo)) / (Math.log(hi) - Math.log(lo));
  }

  toPixel(n: number, t: number, plot: Rect): [number, number] {
    return [
      plot.x + plot.w * this.frac(n, this.nRange),
      plot.y + plot.h - plot.h * this.frac(t, this.tRange),
    ];
  }

  /** Where the last draw put the plot and the words. */
  drawn: PanelDrawn | null = null;

  draw(ctx: CanvasRenderingContext2D, r: Rect): void {
    const fs = fontSize(r);
    const small = Math.floor(fs * 0.85);
    let readout = "";
    if (this.n.length) {
      const n = this.n[this.n.length - 1];
      const temperature = this.t[this.t.length - 1];
      readout = t("chart.readout_path", {
        n: formatNumber(n),
        t: tickText(temperature),
        tc: tickText(this.tc(n)),
      });
    }
    const legend = this.cloud.length ? CLOUD_LEGEND : PATH_LEGEND;
    const head = header(ctx, r, legend, readout, fs, small);
    const plot = margins(r, head.bottom - r.y);
    ctx.save();
    ctx.beginPath();
    ctx.rect(r.x, r.y, r.w, r.h);
    ctx.clip();
    blank(ctx, r, plot);
    // The condensate: below T = Tc(N), a straight line on log-log axes.
    const [xa, ya] = this.toPixel(this.nRange[0], this.tc(this.nRange[0]), plot);
    const [xb, yb] = this.toPixel(this.nRange[1], this.tc(this.nRange[1]), plot);
    ctx.save();
    ctx.beginPath();
    ctx.rect(plot.x, plot.y, plot.w, plot.h);
    ctx.clip();
    ctx.fillStyle = CONDENSATE;
    ctx.beginPath();
    ctx.moveTo(xa, ya);
    ctx.lineTo(xb, yb);
    ctx.lineTo(xb, plot.y + plot.h + 10);
    ctx.lineTo(xa, plot.y + plot.h + 10);
    ctx.closePath();
    ctx.fill();
    ctx.strokeStyle = TC_LINE;
    ctx.lineWidth = 3;
    ctx.beginPath();
    ctx.moveTo(xa, ya);
    ctx.lineTo(xb, yb);
    ctx.stroke();
    ctx.strokeStyle = CLOUD;
    ctx.lineWidth = 2;
    for (const c of this.cloud) {
      ctx.beginPath();
      c.n.forEach((n, k) => {
        const [x, y] = this.toPixel(n, c.t[k], plot);
        if (k) ctx.lineTo(x, y);
        else ctx.moveTo(x, y);
      });
      ctx.stroke();
    }
    // The path and its markers, then the current point.
    if (this.n.length) {
      ctx.strokeStyle = PATH;
      ctx.fillStyle = PATH;
      ctx.lineWidth = 3;
      ctx.beginPath();
      const thin = Math.max(1, Math.floor(this.n.length / 200));
      const pts: Array<[number, number]> = this.n.map((n, k) => this.toPixel(n, this.t[k], plot));
      pts.forEach(([x, y], k) => (k ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
      ctx.stroke();
      for (let k = 0; k < pts.length; k += thin) {
        ctx.beginPath();
        ctx.arc(pts[k][0], pts[k][1], 3, 0, 2 * Math.PI);
        ctx.fill();
      }
      const [x, y] = pts[pts.length - 1];
      ctx.fillStyle = INK;
      ctx.beginPath();
      ctx.arc(x, y, 8, 0, 2 * Math.PI);
      ctx.fill();
      ctx.fillStyle = PATH;
      ctx.beginPath();
      ctx.arc(x, y, 6, 0, 2 * Math.PI);
      ctx.fill();
    }
    ctx.restore();
    panelTitle(ctx, r, t("chart.path"), fs);
    this.drawn = { plot, words: head.draw() };
    ctx.fillStyle = INK;
    for (const v of logTicks(...this.nRange)) {
      const x = Math.round(this.toPixel(v, this.tRange[0], plot)[0]);
      ctx.fillRect(x - 1, plot.y + plot.h, 2, 5);
      drawText(ctx, tickText(v), small, INK, x, plot.y + plot.h + 6, "midtop");
    }
    for (const v of logTicks(...this.tRange)) {
      const y = Math.round(this.toPixel(this.nRange[0], v, plot)[1]);
      ctx.fillStyle = INK;
      ctx.fillRect(plot.x - 5, y - 1, 5, 2);
      drawText(ctx, tickText(v), small, INK, plot.x - 6, y, "midright");
    }
    xLabel(ctx, t("chart.axis.atoms"), small, plot, r);
    yLabel(ctx, t("chart.axis.temperature"), small, r.x + 2, plot.y + plot.h / 2);
    ctx.strokeStyle = INK;
    ctx.lineWidth = 2;
    ctx.strokeRect(plot.x, plot.y, plot.w, plot.h);
    ctx.restore();
  }
}
