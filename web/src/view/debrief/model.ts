/**
 * The debrief's document (the server's /api/debrief, docs/class.md) and what the views
 * read from it: the critical line, each game's name (or its anonymous label), the order
 * the curves are drawn in, the archetypes and the best game's path in words.
 */
import type { GamePath } from "../../game/path";

/** Tc(N) = tc0 (N / n0)^exponent; t0: every game's starting temperature. */
export interface Law {
  n0: number;
  tc0: number;
  exponent: number;
  t0: number;
}

/** A game's path, sampled (game/path.ts, the server's game/path.py's twin). */
export type PathColumns = GamePath;

export interface DebriefGame {
  entry: number;
  /** null in anonymous mode. */
  name: string | null;
  rank: number;
  score: number;
  frames: number;
  won: boolean;
  /** null for a game kept before paths were. */
  path: PathColumns | null;
}

export const ARCHETYPES = ["best", "fastest", "most_lost", "never_won"] as const;
export type Archetype = (typeof ARCHETYPES)[number];
/** Each archetype's words (literal keys: the page's catalogs keep the keys its code names). */
export const ARCHETYPE_WORDS: Record<Archetype, string> = {
  best: "debrief.best",
  fastest: "debrief.fastest",
  most_lost: "debrief.most_lost",
  never_won: "debrief.never_won",
};

/** What the lecturer set the debrief to show. */
export interface Showing {
  anonymous: boolean;
  pick: number | null;
  pair: [number, number] | null;
}

export interface Debrief {
  challenge: number;
  anonymous: boolean;
  law: Law;
  max_score: number;
  lost: boolean;
  games: DebriefGame[];
  archetypes: Record<Archetype, number | null>;
  you: { entry: number; rank: number } | null;
  showing?: Showing;
}

/** Two games side by side: their paths at every frame, their replay codes. */
export interface PairDoc {
  challenge: number;
  games: Array<{
    entry: number;
    name: string | null;
    rank: number | null;
    path: PathColumns;
    /** The game's replay code (the projector plays both replays in step). */
    code?: string;
  }>;
}

/** A catalog text with its placeholders filled (the page's `t`, or the class pages' fill). */
export type Tr = (key: string, args?: Record<string, string | number>) => string;

/** The critical temperature with n atoms. */
export function tcOf(law: Law, n: number): number {
  return law.tc0 * Math.pow(n / law.n0, law.exponent);
}

/** A game's name, or "Student {rank}" in anonymous mode. */
export function nameOf(game: { name: string | null; rank?: number | null }, tr: Tr): string {
  return game.name ?? tr("debrief.anonymous_name", { n: game.rank ?? "" });
}

/** The games in drawing order: the last place first, the best last (on top), then the
 * one highlighted, if any, over all. */
export function drawOrder(doc: Debrief, highlight: number | null = null): DebriefGame[] {
  const drawn = doc.games.filter((g) => g.path && g.path.k.length > 0);
  drawn.sort((a, b) => b.rank - a.rank);
  const lit = drawn.findIndex((g) => g.entry === highlight);
  if (lit >= 0) drawn.push(...drawn.splice(lit, 1));
  return drawn;
}

/** The archetypes there are (in ARCHETYPES' order): kind, entry, its label. */
export function archetypeList(
  doc: Debrief,
  tr: Tr,
): Array<{ kind: Archetype; entry: number; label: string }> {
  const out = [];
  for (const kind of ARCHETYPES) {
    const entry = doc.archetypes[kind];
    if (entry !== null && entry !== undefined)
      out.push({ kind, entry, label: tr(ARCHETYPE_WORDS[kind]) });
  }
  return out;
}

/** A game of the document by entry. */
export function gameOf(doc: Debrief, entry: number | null): DebriefGame | undefined {
  return doc.games.find((g) => g.entry === entry);
}

/** A number for words: 3 significant digits at most, in the page's language. */
export function numberText(v: number, locale: string): string {
  const rounded = Number(v.toPrecision(3));
  return new Intl.NumberFormat(locale, { maximumSignificantDigits: 3 }).format(rounded);
}

/** The best game's path in words (the screen reader's description of the chart). */
export function describeBest(doc: Debrief, tr: Tr, locale: string): string {
  const best = gameOf(doc, doc.archetypes.best);
  const path = best?.path;
  if (!best || !path || path.k.length === 0) return tr("debrief.describe_none");
  const mid = path.k.findIndex((k) => k >= path.frames / 2);
  const at = mid < 0 ? path.k.length - 1 : mid;
  return tr("debrief.describe", {
    count: doc.games.length,
    name: nameOf(best, tr),
    n0: path.n[0],
    t0: numberText(path.t[0], locale),
    nmid: path.n[at],
    tmid: numberText(path.t[at], locale),
    frames: path.frames,
    score: path.score,
  });
}
