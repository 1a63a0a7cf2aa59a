/**
 * The local top-10 table with the desktop's rules (Python's `game/highscores.py`): best
 * score first, ties to the faster time, then the earlier date; names cleaned and cut to
 * 16 characters, each a whole grapheme cluster (a letter with its marks, an emoji family).
 * One table per settings combination, each under its own storage key in the desktop's JSON
 * format. A damaged or foreign stored table is set aside and reported.
 */
import { t } from "../i18n";
import { SCORE_SECONDS_MAX } from "../limits";
import { formatDate, PREFIX, readKey, setAside, writeKey, type KeyValue } from "./store";

export const FORMAT_VERSION = 1;
export const MAX_ENTRIES = 10;
export const NAME_MAX = 16;
/** Code points a name may hold at most (marks and joiners in its 16 characters). */
export const NAME_CODE_POINTS = 4 * NAME_MAX;
export const DEFAULT_NAME = "Anonymous";
/** The longest time a stored row may claim, s (limits.py's, as the desktop's table). */
export const SECONDS_MAX = SCORE_SECONDS_MAX;
const DATE_RE = /^(\d{4})-(\d{2})-(\d{2}) (\d{2}):(\d{2}):(\d{2})$/;

export interface Entry {
  name: string;
  score: number;
  seconds: number;
  date: string;
}

/** -1 if a ranks above b: more atoms, then faster, then earlier. */
export function compareEntries(a: Entry, b: Entry): number {
  if (a.score !== b.score) return b.score - a.score;
  if (a.seconds !== b.seconds) return a.seconds - b.seconds;
  return a.date < b.date ? -1 : a.date > b.date ? 1 : 0;
}

/** Python's str.isprintable for one code point (ASCII space is printable, other spaces not). */
function printable(ch: string): boolean {
  if (ch === " ") return true;
  return !/[\p{C}\p{Z}]/u.test(ch);
}

/** Inside a character (after its first code point) a format mark is part of it: the joiner
 * of an emoji family, a flag's tags. */
const inCluster = (ch: string): boolean => printable(ch) || /\p{Cf}/u.test(ch);

const GRAPHEMES = new Intl.Segmenter("en", { granularity: "grapheme" });

/** The text's characters as a reader counts them (grapheme clusters). */
export function graphemes(text: string): string[] {
  return Array.from(GRAPHEMES.segment(text), (s) => s.segment);
}

/** A character kept whole if it is printable, else a space (a space with a joiner too). */
function cleanCluster(cluster: string): string {
  const [first, ...rest] = Array.from(cluster);
  return first !== " " && printable(first) && rest.every(inCluster) ? cluster : " ";
}

/** The first whole characters of text: at most maxLength, and NAME_CODE_POINTS code points. */
export function cutName(text: string, maxLength = NAME_MAX): string {
  let out = "";
  let points = 0;
  for (const cluster of graphemes(text).slice(0, maxLength)) {
    points += Array.from(cluster).length;
    if (points > NAME_CODE_POINTS) break;
    out += cluster;
  }
  return out;
}

/** Printable characters only, whitespace runs made one space, cut to maxLength characters
 * (whole grapheme clusters: no mark left without its letter, a joiner kept). */
export function cleanName(raw: string, maxLength = NAME_MAX): string {
  const kept = graphemes(String(raw)).map(cleanCluster).join("");
  const words = kept.split(/\s+/u).filter((w) => w.length > 0);
  return cutName(words.join(" "), maxLength).trimEnd();
}

/** Seconds as m:ss.s for the table (83.25 -> "1:23.3"), half up. */
export function formatSeconds(seconds: number): string {
  const tenths = Math.floor(Math.max(0, seconds) * 10 + 0.5);
  const minutes = Math.floor(tenths / 600);
  const rest = tenths % 600;
  return `${minutes}:${String(Math.floor(rest / 10)).padStart(2, "0")}.${rest % 10}`;
}

function validDate(date: string): boolean {
  const m = DATE_RE.exec(date);
  if (!m) return false;
  const [y, mo, d, h, mi, s] = m.slice(1).map(Number);
  // Years 1 to 9999 as the desktop's datetime reads them (Date takes 0-99 as 1900-1999).
  const t = new Date(0);
  t.setUTCFullYear(y, mo - 1, d);
  const real = t.getUTCMonth() === mo - 1 && t.getUTCDate() === d;
  return y >= 1 && real && h < 24 && mi < 60 && s < 60;
}

/** A stored value as a refusal quotes it: its JSON, cut to 40 characters. */
function shown(value: unknown): string {
  const chars = Array.from(JSON.stringify(value) ?? String(value));
  return chars.length <= 40 ? chars.join("") : `${chars.slice(0, 39).join("")}…`;
}

/** Parse one stored row; throws Error saying what is off. */
export function entryFromJson(obj: unknown): Entry {
  if (typeof obj !== "object" || obj === null || Array.isArray(obj)) {
    throw new Error("row is not an object");
  }
  const { name, score, seconds, date } = obj as Record<string, unknown>;
  if (typeof name !== "string" || !name || cleanName(name) !== name) {
    throw new Error(`bad name ${shown(name)}`);
  }
  // 1e308 is a whole number to JavaScript but a float to the desktop, which refuses it.
  if (typeof score !== "number" || !Number.isSafeInteger(score) || score < 0) {
    throw new Error(`bad score ${shown(score)}`);
  }
  if (typeof seconds !== "number" || !(seconds >= 0 && seconds <= SECONDS_MAX)) {
    throw new Error(`bad seconds ${shown(seconds)}`);
  }
  if (typeof date !== "string" || !validDate(date)) {
    throw new Error(`bad date ${shown(date)}`);
  }
  return { name, score, seconds, date };
}

export function scoresKey(settingsKey: string): string {
  return `${PREFIX}highscores.${settingsKey}`;
}

export class HighScoreTable {
  private rows: Entry[] = [];
  /** Results of this visit not yet written (the browser refused them so far). */
  private unsaved: Entry[] = [];
  /** Messages for the page (damaged table set aside, storage refused...); see takeNotices. */
  notices: string[] = [];

  constructor(
    private readonly kv: KeyValue,
    readonly key: string,
  ) {
    this.load();
  }

  /** The rows, best first (a copy). */
  get entries(): Entry[] {
    return this.rows.slice();
  }

  /** (Re)read the table; a damaged or foreign one is set aside with one notice. */
  load(): void {
    const rows = this.read();
    if (rows !== null) this.rows = sortRows([...rows, ...this.unsaved]);
  }

  /** The stored rows ([] if none, or set aside); null if storage cannot be read. */
  private read(): Entry[] | null {
    const notices: string[] = [];
    const text = readKey(this.kv, this.key, notices);
    this.notices.push(...notices);
    if (text === null) return notices.length ? null : [];
    try {
      return this.keepGoodRows(parseTable(text));
    } catch (err) {
      const moved = setAside(this.kv, this.key, text);
      const why = (err as Error).message;
      this.notices.push(
        moved
          ? t("page.scores_damaged", { why, name: moved })
          : t("page.scores_damaged_kept", { why }),
      );
      return [];
    }
  }

  /**
   * The good rows of a stored table; its bad rows alone are set aside (under a key of their
   * own, with one notice) and the table is written back without them (issue 27.11).
   */
  private keepGoodRows({ rows, bad }: ParsedTable): Entry[] {
    if (!bad.length) return rows;
    const aside = JSON.stringify({ version: FORMAT_VERSION, entries: bad.map((b) => b.row) });
    const moved = setAside(this.kv, this.key, aside);
    const good = JSON.stringify({ version: FORMAT_VERSION, entries: rows });
    writeKey(this.kv, this.key, good, "scores", this.notices);
    const args = { n: bad.length, why: bad[0].why, name: moved ?? "" };
    this.notices.push(t(moved ? "page.rows_damaged" : "page.rows_damaged_kept", args));
    return rows;
  }

  /** Would this result enter the table (so it is worth asking for a name)? */
  qualifies(score: number, seconds: number): boolean {
    if (this.rows.length < MAX_ENTRIES) return true;
    const probe: Entry = { name: "", score, seconds, date: "9999-12-31 23:59:59" };
    return compareEntries(probe, this.rows[this.rows.length - 1]) < 0;
  }

  takeNotices(): string[] {
    const out = this.notices;
    this.notices = [];
    return out;
  }

  /**
   * Store a result; its 1-based rank, or null if it did not make the top 10. The stored
   * table is read again first and the result merged into it, so what another tab stored
   * meanwhile is kept (the desktop does the same with its file). The table here is
   * updated even if the browser refuses to save (a notice says so).
   */
  add(name: string, score: number, seconds: number, when = new Date()): number | null {
    if (!Number.isInteger(score) || score < 0) {
      throw new RangeError(`score must be a whole number >= 0 (got ${score})`);
    }
    if (!(seconds >= 0 && seconds <= SECONDS_MAX)) {
      throw new RangeError(`seconds must be a number from 0 to ${SECONDS_MAX} (got ${seconds})`);
    }
    // Stored to 0.01 s so the order in memory equals the order after a reload.
    const entry: Entry = {
      name: cleanName(name) || DEFAULT_NAME,
      score,
      seconds: Math.round(seconds * 100) / 100,
      date: formatDate(when),
    };
    this.unsaved.push(entry);
    this.write(true);
    const index = this.rows.indexOf(entry);
    if (index < 0) this.unsaved = this.unsaved.filter((e) => e !== entry);
    return index < 0 ? null : index + 1;
  }

  /** Empty the table and save (the page asks for confirmation first). */
  reset(): boolean {
    this.rows = [];
    this.unsaved = [];
    return this.write(false);
  }

  private write(merge: boolean): boolean {
    if (merge) {
      const stored = this.read();
      const base = stored ?? this.knownRows();
      this.rows = sortRows([...base, ...this.unsaved]);
    }
    const payload = JSON.stringify({ version: FORMAT_VERSION, entries: this.rows });
    if (!writeKey(this.kv, this.key, payload, "scores", this.notices)) {
      this.rows = sortRows([...this.knownRows(), ...this.unsaved]);
      return false;
    }
    this.unsaved = [];
    return true;
  }

  /** Rows here that came from storage (not this visit's unsaved ones). */
  private knownRows(): Entry[] {
    return this.rows.filter((e) => !this.unsaved.includes(e));
  }
}

function sortRows(rows: Entry[]): Entry[] {
  return rows.sort(compareEntries).slice(0, MAX_ENTRIES);
}

/** A stored table's good rows, and its bad ones with what is wrong with each. */
export interface ParsedTable {
  rows: Entry[];
  bad: Array<{ row: unknown; why: string }>;
}

/** A stored table's rows; throws Error saying what is off if the table as a whole is. */
export function parseTable(text: string): ParsedTable {
  let data: unknown;
  try {
    data = JSON.parse(text);
  } catch {
    throw new Error("not valid JSON");
  }
  if (typeof data !== "object" || data === null || Array.isArray(data)) {
    throw new Error("not a table");
  }
  const d = data as Record<string, unknown>;
  if (d.version !== undefined && d.version !== FORMAT_VERSION) {
    throw new Error(`format version ${JSON.stringify(d.version)}, not ${FORMAT_VERSION}`);
  }
  if (!Array.isArray(d.entries)) throw new Error("no 'entries' list");
  const out: ParsedTable = { rows: [], bad: [] };
  for (const row of d.entries as unknown[]) {
    try {
      out.rows.push(entryFromJson(row));
    } catch (err) {
      out.bad.push({ row, why: (err as Error).message });
    }
  }
  return out;
}
