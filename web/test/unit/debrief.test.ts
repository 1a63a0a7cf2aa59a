// The debrief's views (issue 36) on their own: the colour scale reads in greyscale, the
// curves are drawn best on top, the won games' ends lie at or below the line, every word
// is drawn at a readable size, the pair's two games show the same frame until one ends,
// and the best path is put in words. Data: the golden games' paths (golden/paths.json).
import { readFileSync } from "node:fs";
import { describe, expect, it } from "vitest";
import { luminance, scaleRgb, scoreColor } from "../../src/view/debrief/colors";
import { drawHeights, drawPaths, logTicks, MIN_TEXT } from "../../src/view/debrief/charts";
import {
  archetypeList,
  describeBest,
  drawOrder,
  tcOf,
  type Debrief,
  type PairDoc,
  type PathColumns,
} from "../../src/view/debrief/model";
import {
  allEnded,
  drawPair,
  frameAt,
  nextFrame,
  stateAt,
  type Shown,
} from "../../src/view/debrief/pair";

const CASES: Array<{ path: PathColumns }> = JSON.parse(
  readFileSync(new URL("../golden/paths.json", import.meta.url), "utf8"),
).cases;

const WORDS: Record<string, string> = {
  "debrief.anonymous_name": "Student {n}",
  "debrief.describe": "{count} games; best {name} from {n0} at {t0} to {score} in {frames}",
  "debrief.best": "Best game",
  "debrief.fastest": "Fastest win",
  "debrief.frame": "frame {k}",
  "chart.readout_path": "N = {n} T = {t} Tc = {tc}",
};
const tr = (key: string, args: Record<string, string | number> = {}) =>
  (WORDS[key] ?? key).replace(/\{(\w+)\}/g, (_, k: string) => String(args[k]));

/** The golden games as a class: the three wins (first classic one best) and the lost one. */
function classDoc(anonymous = false): Debrief {
  const classic = CASES.filter((c, i) => c.path.n[0] === 49 && i !== 2); // case 2: p = 2/5
  const games = classic.map((c, i) => ({
    entry: 10 + i,
    name: anonymous ? null : `P${i}`,
    rank: 0,
    score: c.path.score,
    frames: c.path.frames,
    won: c.path.won,
    path: c.path,
  }));
  games.sort((a, b) => b.score - a.score || a.frames - b.frames);
  games.forEach((g, i) => (g.rank = i + 1));
  const t0 = classic[0].path.t0;
  return {
    challenge: 1,
    anonymous,
    law: { n0: 49, tc0: 0.75 * t0, exponent: 2 / 3, t0 },
    max_score: 49,
    lost: true,
    games,
    archetypes: { best: games[0].entry, fastest: games[1].entry, most_lost: null, never_won: null },
    you: null,
  };
}

/** A canvas context that draws nothing and measures text at 0.55 em a character. */
function fakeContext(): CanvasRenderingContext2D {
  const state: Record<string, unknown> = { font: "700 10px sans-serif" };
  return new Proxy(state, {
    get(target, prop: string) {
      if (prop === "measureText")
        return (text: string) => ({
          width: text.length * 0.55 * Number(/(\d+(?:\.\d+)?)px/.exec(String(target.font))![1]),
        });
      if (prop in target) return target[prop];
      return () => undefined;
    },
    set(target, prop: string, value) {
      target[prop] = value;
      return true;
    },
  }) as unknown as CanvasRenderingContext2D;
}

describe("the colour scale", () => {
  it("grows lighter all along (reads in greyscale), never as pale as the page", () => {
    let last = -1;
    for (let i = 0; i <= 100; i++) {
      const l = luminance(scaleRgb(i / 100));
      expect(l).toBeGreaterThan(last);
      last = l;
    }
    expect(last).toBeLessThan(0.6);
    expect(scoreColor(0, 49)).toBe("rgb(68,1,84)");
  });
});

describe("the class's paths", () => {
  it("are drawn best on top, a highlighted game over all", () => {
    const doc = classDoc();
    const order = drawOrder(doc).map((g) => g.entry);
    expect(order[order.length - 1]).toBe(doc.archetypes.best);
    const lit = drawOrder(doc, doc.games[2].entry).map((g) => g.entry);
    expect(lit[lit.length - 1]).toBe(doc.games[2].entry);
    expect(new Set(lit)).toEqual(new Set(order));
  });

  it("mark each won game's end at or below the line, words at readable sizes", () => {
    const doc = classDoc();
    const box = { x: 0, y: 0, w: 940, h: 860 };
    const drawn = drawPaths(fakeContext(), box, doc, { tr, locale: "en" });
    expect(drawn.curves).toEqual(drawOrder(doc).map((g) => g.entry));
    expect(Object.keys(drawn.ends).map(Number).sort()).toEqual(
      doc.games
        .filter((g) => g.won)
        .map((g) => g.entry)
        .sort(),
    );
    for (const g of doc.games.filter((g) => g.won)) {
      const p = g.path!;
      const n = p.n[p.n.length - 1];
      // Each golden game has a seed of its own: its own start's Tc.
      const own = { ...doc.law, tc0: 0.75 * p.t0 };
      expect(p.t[p.t.length - 1]).toBeLessThanOrEqual(tcOf(own, n) * 1.0001);
    }
    const sizes = drawn.words.map((w) => w.size);
    expect(Math.min(...sizes)).toBeGreaterThanOrEqual(MIN_TEXT);
    // On a 1080-line projector's half: the smallest word (a tick) at least 24 px.
    expect(Math.min(...sizes)).toBeGreaterThanOrEqual(24);
    for (const w of drawn.words) {
      expect(w.x).toBeGreaterThanOrEqual(box.x - 1);
      expect(w.x + w.w).toBeLessThanOrEqual(box.x + box.w + 1);
    }
    const heights = drawHeights(fakeContext(), box, doc, { tr, locale: "en" });
    expect(heights.curves).toEqual(drawn.curves);
  });
});

describe("the archetypes and the words", () => {
  it("list the archetypes there are and put the best path in words", () => {
    const doc = classDoc();
    expect(archetypeList(doc, tr).map((a) => [a.kind, a.label])).toEqual([
      ["best", "Best game"],
      ["fastest", "Fastest win"],
    ]);
    const best = doc.games[0];
    const text = describeBest(doc, tr, "en");
    expect(text).toContain(`best ${best.name} from 49`);
    expect(text).toContain(`to ${best.score} in ${best.frames}`);
    expect(describeBest(classDoc(true), tr, "en")).toContain("best Student 1 ");
  });
});

describe("two games side by side", () => {
  /** A path with every frame, as the server's /api/debrief/pair gives. */
  function everyFrame(frames: number, n0: number): PathColumns {
    const k = Array.from({ length: frames + 1 }, (_, i) => i);
    return {
      k,
      n: k.map((i) => n0 - Math.floor(i / 10)),
      t: k.map((i) => 80 - i / 10),
      h: k.map(() => 300),
      frames,
      won: true,
      score: n0 - Math.floor(frames / 10),
      t0: 80,
    };
  }

  it("show the same frame in both until the shorter ends, then its last", () => {
    const pair: PairDoc = {
      challenge: 1,
      games: [
        { entry: 1, name: "A", rank: 1, path: everyFrame(120, 49) },
        { entry: 2, name: null, rank: 2, path: everyFrame(300, 49) },
      ],
    };
    const law = { n0: 49, tc0: 60, exponent: 2 / 3, t0: 80 };
    expect(frameAt(pair, 0)).toBe(0);
    expect(frameAt(pair, 1000)).toBe(30);
    expect(frameAt(pair, 1e9)).toBe(300);
    for (const k of [0, 1, 60, 119, 120, 121, 299, 300]) {
      const drawn = drawPair(
        fakeContext(),
        { x: 0, y: 0, w: 1800, h: 380 },
        pair,
        law,
        k,
        tr,
        "en",
      );
      expect(drawn.shown).toEqual([Math.min(k, 120), k]);
      expect(stateAt(pair.games[0].path, law, k).n).toBe(49 - Math.floor(Math.min(k, 120) / 10));
      expect(drawn.words.some((w) => w.text.startsWith("Student 2 · frame"))).toBe(true);
    }
  });
});

describe("the shared clock of two replays in step", () => {
  /** A replay of `last` frames that shows the frame asked for (or its last), unless it is
   * still loading or lags (then it stays where it was). */
  function replay(last: number) {
    let frame = 0;
    return (k: number, ready: boolean): Shown => {
      if (!ready) return null;
      frame = Math.min(k, last);
      return { frame, ended: frame === last };
    };
  }

  it("moves on only when both show the shared frame, and ends on each one's last", () => {
    const lasts = [7, 12];
    const replays = lasts.map(replay);
    let k = 0;
    const seen: number[][] = [];
    for (let tick = 0; tick < 60; tick++) {
      // The second replay is not ready for the first 3 ticks, and misses every 4th ask.
      const shown = replays.map((r, i) => r(k, i === 0 || (tick >= 3 && tick % 4 !== 1)));
      if (shown.every((s) => s !== null)) seen.push(shown.map((s) => s!.frame));
      const next = nextFrame(k, shown);
      if (shown.some((s) => s === null)) expect(next).toBe(k);
      expect(next - k).toBeLessThanOrEqual(1);
      k = next;
      if (allEnded(shown)) break;
    }
    expect(k).toBe(12);
    for (const [a, b] of seen) expect(a).toBe(Math.min(b, 7));
    expect(seen.at(-1)).toEqual([7, 12]);
    expect(new Set(seen.map(([, b]) => b)).size).toBe(13);
  });

  it("holds the shared frame while one replay lags behind it", () => {
    expect(
      nextFrame(5, [
        { frame: 5, ended: false },
        { frame: 4, ended: false },
      ]),
    ).toBe(5);
    expect(
      nextFrame(5, [
        { frame: 5, ended: false },
        { frame: 3, ended: true },
      ]),
    ).toBe(6);
    expect(
      nextFrame(5, [
        { frame: 5, ended: true },
        { frame: 3, ended: true },
      ]),
    ).toBe(5);
    expect(allEnded([{ frame: 5, ended: true }, null])).toBe(false);
    expect(allEnded([])).toBe(false);
  });
});

describe("the debrief's log axes", () => {
  it("tick a narrow range more than once, a wide one at most six times", () => {
    expect(logTicks(24, 56)).toEqual([30, 40, 50]);
    expect(logTicks(1, 61)).toEqual([1, 2, 5, 10, 20, 50]);
    expect(logTicks(0.5, 80)).toEqual([1, 3, 10, 30]);
    for (const [lo, hi] of [
      [3, 4.5],
      [24, 56],
      [0.01, 1e4],
    ]) {
      const t = logTicks(lo, hi);
      expect(t.length).toBeLessThanOrEqual(6);
      expect(t.every((v) => v >= lo && v <= hi)).toBe(true);
    }
  });
});
