/**
 * A game's path in the (N, T) plane and its trap height, sampled from its replay (twin of
 * evapcool/game/path.py, issue 36): frame 0 and every `stride`-th whole frame, then the last
 * frame played, at most MAX_POINTS points, T to T_DIGITS significant digits. The class
 * server keeps each verified game's path so; a page computes the same points for its game,
 * in one call to the core's core_path (core/game.c) as Python's does (issue 47).
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
 * `frames` whole frames, when known), sampled in one call to the core (core_path). */
export function gamePath(rec: Recording, factory: SimFactory, frames?: number): GamePath {
  const all = framesOf(rec.moves);
  const total = frames === undefined ? all : Math.min(frames, all);
  const sim = startOf(rec, factory);
  const runs = rec.moves.map(([h, n]) => [clampHeight(h), n] as const);
  const t0 = sim.temperature;
  const h0 = runs.length ? runs[0][0] : clampHeight(sim.trapHeight);
  const played = sim.path(runs, total, strideOf(total), h0);
  const rows = played.rows;
  const score = sim.score;
  return {
    k: rows.map((r) => r[0]),
    n: rows.map((r) => r[1]),
    t: rows.map((r) => roundT(r[2])),
    h: rows.map((r) => r[3]),
    frames: played.frames,
    won: score !== null,
    score: score ?? 0,
    t0,
  };
}
