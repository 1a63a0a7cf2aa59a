/**
 * The challenge and its leaderboard as the projector and the lecturer's page say them:
 * pure text and row data (tested without a browser), and the one DOM helper that puts a
 * row's cells in with textContent.
 */
import { fill, type Words } from "./common";

/** A challenge's settings as the server sends them (docs/class.md). */
export interface ChallengeSettings {
  n_atoms: number;
  radius: number;
  escape: string;
  tc_exponent: number;
}

/** What every page shows of a challenge (the server's challenge_info). */
export interface ChallengeInfo {
  id: number;
  seed: number;
  settings: ChallengeSettings;
  attempts: number | null;
  open: boolean;
  /** Seconds left in its window when the server answered, or null for no window. */
  closes_in: number | null;
}

/** One row of the public leaderboard (name null in the debrief's anonymous mode). */
export interface BoardEntry {
  rank: number;
  name: string | null;
  score: number;
  frames: number;
  edition: string;
}

/** The moves of the replay on the projector, as the server summarises them. */
export interface ReplaySummary {
  frames: number;
  runs: number;
  score: number;
  first: string;
  last: string;
}

/** The replay on the projector (its code only while a reader may see it; name null in
 * the debrief's anonymous mode). */
export interface Replay {
  entry: number;
  name: string | null;
  code?: string;
  summary: ReplaySummary;
}

/** The leaderboard document of the event stream. */
export interface Board {
  challenge?: number | null;
  open: boolean;
  info: ChallengeInfo | null;
  entries: BoardEntry[];
  /** How many students played (one row each). */
  players?: number;
  rejected: number;
  replay: Replay | null;
  /** What the lecturer set the debrief to show (issue 36). */
  debrief?: { anonymous: boolean; pick: number | null; pair: [number, number] | null };
}

/** The two cooling laws the lecturer's form offers, by the exponent's JSON text. */
const LAWS: Readonly<Record<string, string>> = { "0.6666666666666666": "2/3", "0.4": "2/5" };

/** A challenge's settings in one line (atoms, radius, escape, seed, law, attempts). */
export function settingsText(words: Words, c: ChallengeInfo): string {
  const s = c.settings;
  const escape = words[s.escape] || s.escape;
  let text = fill(words.settings, { n: s.n_atoms, radius: s.radius, escape, seed: c.seed });
  const law = LAWS[String(s.tc_exponent)] ?? Number(s.tc_exponent).toFixed(3);
  text += " · " + words.tc_law + " " + law;
  if (c.attempts) text += " · " + fill(words.per_student, { n: c.attempts });
  return text;
}

/** Seconds as m:ss, rounded up, never below 0:00. */
export function clock(seconds: number): string {
  const s = Math.max(0, Math.ceil(seconds));
  return Math.floor(s / 60) + ":" + String(s % 60).padStart(2, "0");
}

/** "" before any challenge, "open" while it takes games, "closed" after. */
export type StateKind = "" | "open" | "closed";

/** The challenge's state, `elapsed` seconds after the server said it. */
export function stateText(
  words: Words,
  info: ChallengeInfo | null,
  elapsed: number,
): [StateKind, string] {
  if (!info) return ["", words.waiting];
  const left = info.closes_in === null ? null : info.closes_in - elapsed;
  if (!info.open || (left !== null && left <= 0)) return ["closed", words.final];
  const time = left === null ? "" : " · " + fill(words.closes_in, { time: clock(left) });
  return ["open", words.open + time];
}

/**
 * The latest challenge the server sent, its window counted down from the server's own
 * "seconds left" (no clocks compared).
 */
export class ChallengeClock {
  info: ChallengeInfo | null = null;
  private at = 0;

  take(info: ChallengeInfo | null, now: number = Date.now()): void {
    this.info = info;
    this.at = now;
  }

  /** Seconds left in the window, or null when it has none. */
  secondsLeft(now: number = Date.now()): number | null {
    const c = this.info;
    return c && c.closes_in !== null ? c.closes_in - (now - this.at) / 1000 : null;
  }

  state(words: Words, now: number = Date.now()): [StateKind, string] {
    return stateText(words, this.info, (now - this.at) / 1000);
  }
}

/** The projector's columns, in order (each a <col> class and a word of the header). */
export const BOARD_COLUMNS = ["rank", "name", "score", "frames"] as const;

/** The rows the projector shows: with a replay playing, the top five (it fills the rest). */
export function boardRows(board: Board): BoardEntry[] {
  return board.replay && board.replay.code ? board.entries.slice(0, 5) : board.entries;
}

/** A student's name, or "Student {rank}" in the debrief's anonymous mode. */
export function shownName(words: Words, name: string | null, rank: number | null): string {
  return name ?? (rank === null ? "" : fill(words["debrief.anonymous_name"], { n: rank }));
}

/** A board row's cells. */
export function boardCells(e: BoardEntry, words: Words = {}): (string | number)[] {
  return BOARD_COLUMNS.map((c) => (c === "name" ? shownName(words, e.name, e.rank) : e[c]));
}

/** The replay's heading: who played it (`rank`: its place, named so when anonymous), and
 * what its moves were. */
export function replayHeading(words: Words, replay: Replay, rank: number | null = null): string {
  const name = shownName(words, replay.name, rank);
  return words.replay + ": " + name + " · " + fill(words.summary, { ...replay.summary });
}

/** The refused-games count as the pages say it. */
export function rejectedText(words: Words, rejected: number): string {
  return words.refused + ": " + rejected;
}

/** One entry of the lecturer's list (hidden ones too; rank null for those). */
export interface LecturerEntry {
  entry: number;
  rank: number | null;
  name: string;
  score: number;
  frames: number;
  edition: string;
  hidden: boolean;
}

/** An entry's text cells (a hidden entry has no rank). */
export function entryCells(e: LecturerEntry): (string | number)[] {
  return [e.rank === null ? "" : e.rank, e.name, e.score, e.frames, e.edition];
}

/** An entry row's classes: hidden (faded) and showing (on the projector). */
export function entryClass(e: LecturerEntry, showing: number | null | undefined): string {
  return [e.hidden ? "hidden" : "", e.entry === showing ? "showing" : ""].join(" ").trim();
}

/** A cell: text (a name, a number) or an element (the lecturer's buttons). */
export type Cell = string | number | Node;

/** Append a row of cells to a table; text goes in with textContent only. */
export function row(table: HTMLElement, cells: readonly Cell[], tag = "td"): HTMLTableRowElement {
  const tr = document.createElement("tr");
  for (const c of cells) {
    const td = document.createElement(tag);
    if (typeof c === "object") td.appendChild(c);
    else td.textContent = String(c);
    tr.appendChild(td);
  }
  table.appendChild(tr);
  return tr;
}
