/**
 * A game's path in the (N, T) plane and its trap height, sampled from its replay (twin of
 * evapcool/game/path.py, issue 36): frame 0 and every `stride`-th whole frame, then the last
 * frame played, at most MAX_POINTS points, T to T_DIGITS significant digits. The class
 * server keeps each verified game's path so; a page computes the same points for its game.
 */
import { startOf, type Recording } from "./replay";
import { clampHeight, type SimFactory } from "./rules";
import { framesOf } from "./moves";

export const MAX_POINTS = 240;
export const T_DIGITS = 5;

/** Sampled frames k, atoms n, temperature t, height h held during frame k (the first move's
 * at k = 0); frames played, won, score; t0 the start's temperature. */
export interface GamePath {
  k: number[];
  n: number[];
  t: number[];
  h: number[];
  frames: number;
  won: boolean;
  score: number;
  t0: number;
}

export function strideOf(frames: number): number {
  return Math.max(1, Math.ceil(frames / (MAX_POINTS - 1)));
}

/** T to T_DIGITS significant digits (the decimal nearest, as the server's). */
export function roundT(t: number): number {
  return Number(t.toExponential(T_DIGITS - 1));
}

/** The path of a recording's game, replayed up to the win or the end of its moves (or
 * `frames` whole frames, when known). */
export function gamePath(rec: Recording, factory: SimFactory, frames?: number): GamePath {
  const all = framesOf(rec.moves);
  const total = frames === undefined ? all : Math.min(frames, all);
  const stride = strideOf(total);
  const sim = startOf(rec, factory);
  const out: GamePath = { k: [], n: [], t: [], h: [], frames: 0, won: false, score: 0, t0: 0 };
  const keep = (k: number, h: number) => {
    const n = sim.nTrapped;
    const t = sim.temperature;
    if (!(n > 0 && Number.isFinite(t) && t > 0)) return;
    out.k.push(k);
    out.n.push(n);
    out.t.push(roundT(t));
    out.h.push(h);
  };
  out.t0 = sim.temperature;
  keep(0, clampHeight(rec.moves.length ? rec.moves[0][0] : sim.trapHeight));
  let k = 0;
  for (const [height, run] of rec.moves) {
    const h = clampHeight(height);
    for (let i = 0; i < run && k < total && sim.score === null; i++) {
      sim.frame(h);
      k += 1;
      if (k % stride === 0 || k === total || sim.score !== null) keep(k, h);
    }
  }
  out.frames = k;
  out.won = sim.score !== null;
  out.score = sim.score ?? 0;
  return out;
}
