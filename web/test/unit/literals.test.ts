// No English sentence on the page outside the catalogs (issue 23): scans the view, app, game and
// classroom layers for string literals a person could read. Not counted: comments; the words
// of exceptions, the console and the physics (a thrown message reaches the screen only as a
// catalog message's {problem}); import paths; message keys. Exceptions by file: ALLOWED.
import { readdirSync, readFileSync } from "node:fs";
import { join, resolve } from "node:path";
import { describe, expect, it } from "vitest";
import { CATALOGS } from "../../src/i18n";

const SRC = resolve(import.meta.dirname, "../../src");
const LAYERS = ["view", "app", "game", "classroom"];
/** Calls whose string arguments are for programmers (exceptions, the console). */
const TERMINAL = /(Error|console\.\w+|warn|fail|reject|matchMedia|mq|load|Worker)$/;
/** What makes a literal read as words: a word, a space or comma, another word. */
const SENTENCE = /[A-Za-z]{2,}[ ,;:]+[A-Za-z]+/;
/** (file, literal) pairs that are not words on screen. */
const ALLOWED = new Set([
  // The stored name of a nameless winner (data, as on the desktop).
  "game/highscores.ts|Anonymous",
  // Technical details a translated notice carries as {why}: a damaged row's reason.
  "game/highscores.ts|row is not an object",
  "game/highscores.ts|not valid JSON",
  "game/highscores.ts|no 'entries' list",
  "game/settingsStore.ts|not valid JSON",
  "game/settingsStore.ts|not a JSON object",
  // The replay codes' refusal words, shared with the class server and the desktop (the
  // verify panel shows them through reason.* messages).
  "game/replay.ts|does not replay to the claimed score",
  "game/replay.ts|other version",
  // The strategy file's own description (data).
  "game/autopilot.ts|the demo strategy",
  // The font stack (names of fonts) and the worker's name in the browser's task manager.
  "view/text.ts|'Microsoft YaHei', 'Hiragino Sans', 'Yu Gothic', 'Malgun Gothic', 'Noto Sans Arabic',",
  "view/text.ts|'Noto Naskh Arabic', Tahoma, sans-serif",
  "view/debrief/text.ts|'Hiragino Sans', 'Malgun Gothic', 'Noto Sans Arabic', 'Noto Naskh Arabic', Tahoma, sans-serif",
  "app/main.ts|evapcool physics",
  "app/main.ts|evapcool verify",
  // A saved run's file header (data a lab reader reads, as lab/io.py writes it; issue 48).
  "app/runlog.ts|# evapcool lab results",
  "app/runlog.ts|evapcool page: Save this run",
  "app/runlog.ts|every frame",
  "app/runlog.ts|every second",
  // The projector's empty frame (an address, not words).
  "classroom/projector.ts|about:blank",
  // A presented replay's placement: CSS values, not words (issue 45).
  "classroom/debrief/replays.ts|translate( px,  px) scale( )",
  "classroom/debrief/replays.ts|inset( px  px  px  px)",
  // A replay code's and a setting's refusal details, the class server's and the desktop's
  // words for them (shown only as a translated notice's {problem}, like the desktop's).
  ...[
    "settings.n_atoms must be  ..",
    "settings.radius must be  ..",
    "settings.escape must be rim or knife",
    "settings.tc_exponent must be in (0, 2]",
    "seed must be 0..2^53-1",
    "edition must be desktop or web",
    "moves: each run needs frames >= 1",
    "moves: heights must be  ..",
    "moves: at most   frames",
    "frames must equal the moves' frames",
    "score must be 0..n_atoms",
    "score must be 0 without a win",
  ].map((s) => `game/replay.ts|${s}`),
  ...[
    "a number from   to   px",
    "a positive number",
    "n_atoms must be a whole number from 1 to   for radius",
    "n_atoms must be a whole number >= 1",
  ].map((s) => `game/settings.ts|${s}`),
]);

interface Literal {
  value: string;
  /** The code just before it. */
  before: string;
  /** The function whose call it is an argument of (e.g. "RangeError"), or "". */
  call: string;
}

/** The callee of the innermost call still open at `at` (within its statement), or "". */
function callee(text: string, at: number): string {
  let depth = 0;
  for (let k = at - 1; k >= Math.max(0, at - 600); k--) {
    const c = text[k];
    if (c === ")" || c === "]" || c === "}") depth += 1;
    else if (c === "(" || c === "[" || c === "{") {
      if (depth === 0) {
        if (c !== "(") return c === "{" ? "" : callee(text, k);
        return /([\w.]+)\s*$/.exec(text.slice(Math.max(0, k - 40), k))?.[1] ?? "";
      }
      depth -= 1;
    } else if (c === ";" && depth === 0) return "";
  }
  return "";
}

/** For programmers: an exception's or the console's words, a thrown value, CSS, fonts. */
function terminal(call: string, before: string): boolean {
  return TERMINAL.test(call) || /\b(throw|className|font|FONT_FAMILY)\s*[=(]?$/.test(before);
}

/** The string literals of TypeScript source `text`, each with where it stands. */
export function literals(text: string): Literal[] {
  const out: Literal[] = [];
  let i = 0;
  while (i < text.length) {
    const c = text[i];
    if (c === "/" && text[i + 1] === "/") i = text.indexOf("\n", i) >>> 0 || text.length;
    else if (c === "/" && text[i + 1] === "*") i = text.indexOf("*/", i + 2) + 2 || text.length;
    else if (c === '"' || c === "'" || c === "`") {
      let j = i + 1;
      let value = "";
      while (j < text.length && text[j] !== c) {
        if (text[j] === "\\") j += 1;
        else if (c === "`" && text[j] === "$" && text[j + 1] === "{") {
          let depth = 0;
          for (; j < text.length; j++) {
            if (text[j] === "{") depth += 1;
            if (text[j] === "}" && --depth === 0) break;
          }
          value += " ";
        } else value += text[j];
        j += 1;
      }
      const before = text.slice(Math.max(0, i - 60), i).trimEnd();
      out.push({ value, before, call: callee(text, i) });
      i = j + 1;
    } else i += 1;
  }
  return out;
}

/** The literals of one file that read as English words on a screen. */
function english(path: string): string[] {
  const text = readFileSync(path, "utf8");
  return literals(text)
    .filter(({ value, call, before }) => SENTENCE.test(value) && !terminal(call, before))
    .filter(({ before }) => !/\b(from|import)$/.test(before))
    .map(({ value }) => value.trim());
}

const files = LAYERS.flatMap((layer) =>
  (readdirSync(join(SRC, layer), { recursive: true }) as string[])
    .filter((f) => f.endsWith(".ts") && !f.endsWith(".d.ts"))
    .map((f) => `${layer}/${f}`),
);

describe("no English on the page outside the catalogs", () => {
  it.each(files)("%s", (name) => {
    const found = english(join(SRC, name)).filter((s) => !ALLOWED.has(`${name}|${s}`));
    expect(found, `${name}: move these to src/evapcool/locales/en.json`).toEqual([]);
  });

  it("finds a sentence, and skips errors, comments and imports", () => {
    const sample = [
      'import { x } from "./some where";',
      "// Press R now",
      'throw new RangeError("bad thing happened");',
      'draw(ctx, "Press R now");',
    ].join("\n");
    const found = literals(sample)
      .filter(({ value, call, before }) => SENTENCE.test(value) && !terminal(call, before))
      .filter(({ before }) => !/\b(from|import)$/.test(before))
      .map((l) => l.value);
    expect(found).toEqual(["Press R now"]);
  });

  it("every message key the page names exists in English", () => {
    const keys = new Set<string>();
    for (const name of [...files, "i18n.ts"])
      for (const { value } of literals(readFileSync(join(SRC, name), "utf8")))
        if (
          /^(hint|page|control|button|verify|reason|help|lose|win|scores|settings|table|chart|notice|status|start|controls|app|autopilot)\.[a-z0-9_.]+$/.test(
            value,
          )
        )
          keys.add(value);
    const missing = [...keys].filter((k) => !(k in CATALOGS.en.messages));
    expect(missing).toEqual([]);
    expect(keys.size).toBeGreaterThan(150);
  });
});
