// A fuzz of the page's inputs (issue 37), as the desktop's tests/test_fuzz.py fuzzes its
// own: the address, what storage holds, replay codes and names, each with fast-check. Each
// input is refused in one short line or taken whole; nothing throws, nothing grows unbounded.
import fc from "fast-check";
import { describe, expect, test } from "vitest";
import { deflateSync } from "node:zlib";
import { ADDRESS_OPTIONS, parseParams } from "../../src/app/params";
import {
  cleanName,
  formatSeconds,
  graphemes,
  HighScoreTable,
  NAME_CODE_POINTS,
  NAME_MAX,
  parseTable,
  SECONDS_MAX,
} from "../../src/game/highscores";
import { ReplayError } from "../../src/game/replay";
import { crc32Hex, decode } from "../../src/game/replaycode";
import { DEFAULTS } from "../../src/game/settings";
import { loadSettings, SETTINGS_KEY } from "../../src/game/settingsStore";
import { MemoryStore } from "../../src/game/store";
import { chooseLocale } from "../../src/i18n";

if (process.env.CI) fc.configureGlobal({ seed: 20_261_127 });

/** A refusal or notice is one line: at most this many characters. */
const LINE = 300;
/** Names an object has without owning them: what `in` let through. */
const INHERITED = ["toString", "constructor", "__proto__", "valueOf", "hasOwnProperty"];

const value = fc.oneof(
  fc.string({ maxLength: 40 }),
  fc.constantFrom(...INHERITED, "seed", "cup", "rim", "knife", "de", "fr", "1e308", "0x20"),
  fc.double().map(String),
  fc.string({ minLength: 500, maxLength: 3000 }),
);
const option = fc.oneof(
  fc.constantFrom(...ADDRESS_OPTIONS),
  fc.constantFrom(...INHERITED),
  fc.string(),
);
const query = fc
  .array(fc.tuple(option, value), { maxLength: 12 })
  .map((pairs) => new URLSearchParams(pairs).toString());

describe("the address", () => {
  test("every option is taken as allowed or refused in one line; repeats never count", () => {
    fc.assert(
      fc.property(query, (search) => {
        const q = new URLSearchParams(search);
        const p = parseParams(search, DEFAULTS);
        for (const line of p.notices) expect(line.length).toBeLessThan(LINE);
        const o = p.overrides;
        if (o.tcLaw !== undefined) expect(["seed", "cup"]).toContain(o.tcLaw);
        if (o.escape !== undefined) expect(["rim", "knife"]).toContain(o.escape);
        for (const name of ["tc-law", "escape", "radius", "speed", "seed", "replay", "lang"])
          if (q.getAll(name).length > 1)
            expect(p.notices.some((n) => n.includes(`${name} is given`))).toBe(true);
        if (q.getAll("tc-law").length > 1) expect(o.tcLaw).toBeUndefined();
        if (q.getAll("replay").length !== 1) expect(p.replay).toBeNull();
        // The language the page speaks is the address's only when the address names one.
        const chosen = chooseLocale([], search, null);
        if (p.lang === null) expect(chosen).toBe("en");
      }),
      { numRuns: 400 },
    );
  });
});

/** Stored rows as JSON could hold them: good ones, extreme numbers, odd dates and names. */
const row = fc.record({
  name: fc.oneof(fc.string({ maxLength: 30 }), fc.constantFrom("Ada", "👨‍👩‍👧 Ann", "e\u0301")),
  score: fc.oneof(fc.integer(), fc.double(), fc.constantFrom(1e308, 2 ** 53, -0)),
  seconds: fc.oneof(fc.double(), fc.constantFrom(1e308, SECONDS_MAX, 61.5)),
  date: fc.oneof(
    fc.constantFrom("0000-01-01 00:00:00", "0099-12-31 10:00:00", "2026-02-30 00:00:00"),
    fc.date({ noInvalidDate: true }).map((d) => d.toISOString().replace("T", " ").slice(0, 19)),
  ),
});

describe("what storage holds", () => {
  test("a table's accepted rows are ones the table can show; the rest are named shortly", () => {
    fc.assert(
      fc.property(fc.array(fc.oneof(row, fc.anything()), { maxLength: 12 }), (rows) => {
        const { rows: good, bad } = parseTable(JSON.stringify({ version: 1, entries: rows }));
        for (const r of good) {
          expect(Number.isSafeInteger(r.score) && r.score >= 0).toBe(true);
          expect(formatSeconds(r.seconds)).toMatch(/^\d+:\d\d\.\d$/);
          expect(Number(r.date.slice(0, 4))).toBeGreaterThanOrEqual(1);
          expect(cleanName(r.name)).toBe(r.name);
        }
        for (const b of bad) expect(b.why.length).toBeLessThan(LINE);
      }),
      { numRuns: 300 },
    );
  });

  test("any stored text: the table and the settings load, with short notices", () => {
    fc.assert(
      fc.property(
        fc.oneof(
          fc.string(),
          fc.json(),
          fc.jsonValue().map((v) => JSON.stringify(v)),
        ),
        (text) => {
          const kv = new MemoryStore();
          kv.setItem("evapcool.highscores.x", text);
          kv.setItem(SETTINGS_KEY, text);
          const table = new HighScoreTable(kv, "evapcool.highscores.x");
          for (const n of table.takeNotices()) expect(n.length).toBeLessThan(LINE + 100);
          const [settings, notices] = loadSettings(kv);
          expect(settings.nAtoms).toBeGreaterThanOrEqual(1);
          for (const n of notices) expect(n.length).toBeLessThan(LINE + 100);
        },
      ),
      { numRuns: 200 },
    );
  });
});

test("stored settings of megabytes and a thousand unknown names: each notice one line", () => {
  const kv = new MemoryStore();
  const unknown = Object.fromEntries(
    Array.from({ length: 1000 }, (_, k) => [`k${"x".repeat(k)}`, k]),
  );
  const data = { ...unknown, tc_law: "x".repeat(1_000_000), radius: Array(100_000).fill(3) };
  kv.setItem(SETTINGS_KEY, JSON.stringify(data));
  const [settings, notices] = loadSettings(kv);
  expect(settings.tcLaw).toBe(DEFAULTS.tcLaw);
  expect(notices.length).toBeGreaterThanOrEqual(3);
  for (const n of notices) expect(n.length).toBeLessThan(LINE);
});

/** A code of any JSON text, checksummed as the editions make them (so it reaches inflate). */
const codeOf = (text: string) => {
  const payload = deflateSync(Buffer.from(text)).toString("base64url");
  return `EC1.${payload}.${crc32Hex(payload)}`;
};

describe("replay codes", () => {
  test("any text, any JSON in a well-formed code: a ReplayError of one line, or a recording", async () => {
    const code = fc.oneof(
      fc.string(),
      fc.string().map((s) => `EC1.${s}.${crc32Hex(s)}`),
      fc.jsonValue().map((v) => codeOf(JSON.stringify(v))),
      fc
        .string({ minLength: 1000, maxLength: 5000 })
        .map((s) => codeOf(JSON.stringify({ format: 1, version: s }))),
    );
    await fc.assert(
      fc.asyncProperty(code, async (c) => {
        try {
          await decode(c);
        } catch (err) {
          expect(err).toBeInstanceOf(ReplayError);
          expect((err as Error).message.length).toBeLessThan(LINE);
        }
      }),
      { numRuns: 200 },
    );
  });

  test("a code unpacking past the longest game is refused as it unpacks", async () => {
    const huge = codeOf(`{"pad":"${" ".repeat(50_000_000)}"}`);
    await expect(decode(huge)).rejects.toThrow(/unpacks to more than/);
  });
});

describe("names", () => {
  const text = fc.oneof(
    fc.string({ unit: "grapheme", maxLength: 40 }),
    fc.string({ unit: "binary", maxLength: 40 }),
    fc
      .array(fc.constantFrom("e\u0301", "👨‍👩‍👧", "🏴󠁧󠁢󠁳󠁣󠁴󠁿", "a", " ", "\u200d", "\u0000", "\t"), {
        maxLength: 30,
      })
      .map((a) => a.join("")),
  );
  test("cut by whole characters: at most 16, no mark without its letter, idempotent", () => {
    fc.assert(
      fc.property(text, (raw) => {
        const name = cleanName(raw);
        const chars = graphemes(name);
        expect(chars.length).toBeLessThanOrEqual(NAME_MAX);
        expect(Array.from(name).length).toBeLessThanOrEqual(NAME_CODE_POINTS);
        expect(cleanName(name)).toBe(name);
        // Each character kept is one of the typed text's, whole.
        const typed = new Set(graphemes(raw));
        for (const ch of chars) if (ch !== " ") expect(typed.has(ch)).toBe(true);
      }),
      { numRuns: 500 },
    );
  });

  test("the joiner inside a family stays; a mark stays with its letter at the cut", () => {
    expect(cleanName("👨‍👩‍👧 Ann")).toBe("👨‍👩‍👧 Ann");
    expect(cleanName(`${"a".repeat(15)}e\u0301xyz`)).toBe(`${"a".repeat(15)}e\u0301`);
  });
});
