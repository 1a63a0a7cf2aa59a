/**
 * Two games side by side, in step (issue 36): one clock of whole frames for both, each game
 * shown at that frame (or at its last, once it has ended), with its atom count, its trap
 * height and a thermometer of T against Tc(N): why did the slower ramp keep more atoms?
 */
import {
  nameOf,
  numberText,
  tcOf,
  type Law,
  type PairDoc,
  type PathColumns,
  type Tr,
} from "./model";
import type { Box } from "./charts";
import { textSize } from "./charts";
import { fitted, word, type DrawnWord } from "./text";

/** Frames a second the pair plays at (the game's own pace). */
export const PAIR_FPS = 30;

/** The frame of a game shown at the shared frame k (a path with every frame). */
export function shownFrame(path: PathColumns, k: number): number {
  return Math.max(0, Math.min(k, path.frames));
}

/** The pair's shared clock: the frame at a time since it started, up to the longer end. */
export function frameAt(pair: PairDoc, elapsedMs: number, fps = PAIR_FPS): number {
  const last = Math.max(...pair.games.map((g) => g.path.frames));
  return Math.min(last, Math.max(0, Math.floor((elapsedMs / 1000) * fps)));
}

/** What a replay reported after being asked for a frame: the frame it shows, and whether
 * its game has ended (it holds its last frame); null: not ready (still loading). */
export type Shown = { frame: number; ended: boolean } | null;

/** The shared clock of replays played in step: the frame to ask for after the shared frame
 * k was asked for and each replay showed `shown`. It moves on one frame only once every
 * replay shows k or has ended before it (a lagging one holds the others), and stops once
 * all have ended. */
export function nextFrame(k: number, shown: Shown[]): number {
  if (shown.some((s) => s === null || (!s.ended && s.frame !== k))) return k;
  if (shown.every((s) => s!.ended)) return k;
  return k + 1;
}

/** Whether every replay has ended (each on its own last frame). */
export function allEnded(shown: Shown[]): boolean {
  return shown.length > 0 && shown.every((s) => s !== null && s.ended);
}

/** The state of a game at frame k: atoms, temperature, its Tc, trap height. */
export function stateAt(path: PathColumns, law: Law, k: number) {
  const i = Math.min(path.k.length - 1, Math.max(0, path.k.indexOf(shownFrame(path, k))));
  const n = path.n[i];
  return { k: path.k[i], n, t: path.t[i], tc: tcOf(law, n), h: path.h[i] };
}

export interface PairDrawn {
  words: DrawnWord[];
  /** The frame each game shows. */
  shown: number[];
}

const INK = "rgb(20,20,25)";
const HOT = "rgb(200,60,30)";
const COLD = "rgb(25,60,150)";

/** Both games at the shared frame k, each in half of r. */
export function drawPair(
  ctx: CanvasRenderingContext2D,
  r: Box,
  pair: PairDoc,
  law: Law,
  k: number,
  tr: Tr,
  locale: string,
  /** The least size of its words, px (a projector's: readable at the back). */
  minSmall = 0,
): PairDrawn {
  const words: DrawnWord[] = [];
  const shown: number[] = [];
  ctx.fillStyle = "rgb(250,249,245)";
  ctx.fillRect(r.x, r.y, r.w, r.h);
  const half = r.w / pair.games.length;
  pair.games.forEach((g, i) => {
    const box = { x: r.x + i * half, y: r.y, w: half, h: r.h };
    const s = stateAt(g.path, law, k);
    shown.push(s.k);
    one(ctx, box, words, nameOf(g, tr), s, law, tr, locale, minSmall);
  });
  ctx.fillStyle = INK;
  for (let i = 1; i < pair.games.length; i++) ctx.fillRect(r.x + i * half - 1, r.y, 2, r.h);
  return { words, shown };
}

function one(
  ctx: CanvasRenderingContext2D,
  r: Box,
  words: DrawnWord[],
  name: string,
  s: ReturnType<typeof stateAt>,
  law: Law,
  tr: Tr,
  locale: string,
  minSmall: number,
): void {
  const floor = Math.max(14, Math.ceil(minSmall));
  const fs = Math.max(textSize(r), Math.floor(r.h / 9), Math.ceil(floor / 0.8));
  const pad = fs / 2;
  const title = `${name} · ${tr("debrief.frame", { k: s.k })}`;
  const size = fitted(ctx, title, fs, r.w - 2 * pad, floor);
  word(ctx, words, title, size, INK, r.x + pad, r.y + fs * 0.8, "left");
  const readout = tr("chart.readout_path", {
    n: s.n,
    t: numberText(s.t, locale),
    tc: numberText(s.tc, locale),
  });
  const small = fitted(ctx, readout, Math.floor(0.8 * fs), r.w - 2 * pad - 2 * fs, floor);
  word(ctx, words, readout, small, INK, r.x + pad, r.y + 2.1 * fs, "left");
  const height = `${tr("debrief.axis_height")} = ${Math.round(s.h)}`;
  const hs = fitted(ctx, height, Math.floor(0.8 * fs), r.w - 2 * pad - 2 * fs, floor);
  word(ctx, words, height, hs, INK, r.x + pad, r.y + 3.2 * fs, "left");
  // The atoms, big: the score the class compares.
  word(ctx, words, String(s.n), Math.floor(2.2 * fs), INK, r.x + pad, r.y + r.h - 1.4 * fs, "left");
  thermometer(
    ctx,
    { x: r.x + r.w - 1.6 * fs, y: r.y + 1.6 * fs, w: fs, h: r.h - 2.2 * fs },
    s,
    law,
  );
}

/** A thermometer on a log scale from T0 x 1.2 down to the lowest Tc: the mercury at T, a
 * blue mark at Tc(N); the gas condenses when the mercury falls under the mark. */
function thermometer(
  ctx: CanvasRenderingContext2D,
  r: Box,
  s: { t: number; tc: number },
  law: Law,
): void {
  const hi = 1.2 * law.t0;
  const lo = 0.5 * Math.min(tcOf(law, 1), s.t);
  const y = (t: number) =>
    r.y + r.h - (r.h * (Math.log(Math.max(t, lo)) - Math.log(lo))) / (Math.log(hi) - Math.log(lo));
  ctx.fillStyle = "rgb(255,255,255)";
  ctx.fillRect(r.x, r.y, r.w, r.h);
  ctx.fillStyle = s.t < s.tc ? COLD : HOT;
  const top = Math.max(r.y, y(s.t));
  ctx.fillRect(r.x + 3, top, r.w - 6, r.y + r.h - top);
  ctx.fillStyle = COLD;
  ctx.fillRect(r.x - 0.3 * r.w, y(s.tc) - 3, 1.6 * r.w, 6);
  ctx.strokeStyle = INK;
  ctx.lineWidth = 2;
  ctx.strokeRect(r.x, r.y, r.w, r.h);
}
