import fc from "fast-check";
import { describe, expect, test } from "vitest";
import { cupCapacity } from "../../src/game/capacity";
import {
  cleanName,
  formatSeconds,
  HighScoreTable,
  MAX_ENTRIES,
  scoresKey,
} from "../../src/game/highscores";
import { forceWin, makeSimulation } from "../../src/game/engine";
import { Game, HEIGHT_MAX, HEIGHT_MIN, LOSE_REASONS } from "../../src/game/rules";
import { CORE_MOVES_CAPACITY, REACH_NAMES } from "../../src/physics/model";
import {
  DEFAULTS,
  describe as describeSettings,
  fromMapping,
  maxAtoms,
  step,
  validate,
} from "../../src/game/settings";
import { loadSettings, saveSettings, SETTINGS_KEY } from "../../src/game/settingsStore";
import { MemoryStore } from "../../src/game/store";
import { ADDRESS_OPTIONS, parseParams } from "../../src/app/params";

describe("cup capacity", () => {
  test("the same counts as the desktop's settings.cup_capacity (every atom below the rim)", () => {
    // python -c "from evapcool.game.settings import cup_capacity; ..." (desktop branch)
    const python: Record<number, number> = {
      1: 9508,
      2: 2354,
      3: 1038,
      4: 578,
      5: 366,
      6: 252,
      7: 181,
      8: 137,
      9: 105,
      10: 88,
      11: 73,
      12: 62,
      13: 49,
      14: 38,
      15: 38,
      16: 29,
      17: 29,
      18: 22,
      19: 22,
      20: 20,
    };
    for (const [r, n] of Object.entries(python)) expect(cupCapacity(Number(r))).toBe(n);
    expect(cupCapacity(0.5)).toBe(38214);
    expect(cupCapacity(2.5)).toBe(1498);
    expect(cupCapacity(7.3)).toBe(158);
    expect(maxAtoms(3)).toBe(1038);
    expect(step({ ...DEFAULTS, radius: 1 }, "radius", -1).radius).toBe(1);
    expect(maxAtoms(1)).toBe(9508);
    expect(maxAtoms(0.5)).toBe(20000);
  });
});

describe("settings", () => {
  test("one clear message per bad value, as the desktop words it", () => {
    expect(() => validate({ ...DEFAULTS, radius: 0.5 })).toThrow(
      "radius must be a number from 1 to 20 px (got 0.5)",
    );
    expect(() => validate({ ...DEFAULTS, nAtoms: 63 })).toThrow(
      "n_atoms must be a whole number from 1 to 62 for radius 12 (got 63)",
    );
    expect(() => validate({ ...DEFAULTS, tcLaw: "box" as never })).toThrow(
      "tc_law must be one of seed, cup (got 'box')",
    );
    const [s, notices] = fromMapping({ radius: 30, n_atoms: "many", escape: "knife", colour: 1 });
    expect(s).toEqual({ nAtoms: 49, radius: 12, tcLaw: "seed", escape: "knife" });
    expect(notices).toEqual([
      "Settings: ignored unknown entries colour.",
      "Settings: radius must be a number from 1 to 20 px (got 30); using the default 12.",
      "Settings: n_atoms must be a whole number from 1 to 62 for radius 12 (got 'many'); using the default 49.",
    ]);
  });

  test("the screen's steps: coarser for big counts, radius clamps the count, choices cycle", () => {
    expect(step(DEFAULTS, "n_atoms", 1).nAtoms).toBe(54);
    expect(step({ ...DEFAULTS, nAtoms: 20 }, "n_atoms", -1).nAtoms).toBe(19);
    expect(step({ ...DEFAULTS, nAtoms: 62 }, "n_atoms", 1).nAtoms).toBe(62);
    const big = step({ ...DEFAULTS, nAtoms: 62 }, "radius", 2);
    expect(big).toMatchObject({ radius: 13, nAtoms: 49 });
    expect(step(DEFAULTS, "tc_law", 1).tcLaw).toBe("cup");
    expect(step(DEFAULTS, "escape", -1).escape).toBe("knife");
    expect(describeSettings(DEFAULTS)[0]).toEqual(["Number of atoms", "49  (1 to 62)"]);
  });

  test("stored settings: corrupt or bad values are set aside and reported once", () => {
    const kv = new MemoryStore();
    kv.setItem(SETTINGS_KEY, "{not json");
    const [s, notes] = loadSettings(kv);
    expect(s).toEqual(DEFAULTS);
    expect(notes).toHaveLength(1);
    expect(notes[0]).toMatch(
      /damaged \(not valid JSON\); they were kept as "evapcool\.settings\.corrupt-/,
    );
    expect([...kv.map.values()]).toEqual(["{not json"]);
    expect(loadSettings(kv)[1]).toEqual([]);
    expect(saveSettings(kv, { ...DEFAULTS, nAtoms: 60 }).notices).toEqual([]);
    expect(loadSettings(kv)[0].nAtoms).toBe(60);
    expect(() => saveSettings(kv, { ...DEFAULTS, nAtoms: 0 })).toThrow(RangeError);
  });

  test("two tabs: saving writes only the fields this tab changed", () => {
    const kv = new MemoryStore();
    const base = { ...DEFAULTS };
    saveSettings(kv, { ...base, escape: "knife" }, base); // tab A
    const { saved } = saveSettings(kv, { ...base, tcLaw: "cup" }, base); // tab B
    expect(saved).toEqual({ ...DEFAULTS, escape: "knife", tcLaw: "cup" });
    expect(loadSettings(kv)[0]).toEqual(saved);
  });
});

describe("high scores", () => {
  test("best first; ties to the faster time, then the earlier date; top 10 only", () => {
    const t = new HighScoreTable(new MemoryStore(), scoresKey("k"));
    const d = (s: number) => new Date(2024, 0, 1, 12, 0, s);
    t.add("slow", 30, 50, d(1));
    t.add("fast", 30, 40, d(2));
    t.add("late", 30, 40, d(3));
    t.add("best", 31, 90, d(4));
    expect(t.entries.map((e) => e.name)).toEqual(["best", "fast", "late", "slow"]);
    for (let k = 0; k < 8; k++) t.add(`p${k}`, 10, 10, d(5 + k));
    expect(t.entries).toHaveLength(MAX_ENTRIES);
    expect(t.qualifies(10, 10)).toBe(false);
    expect(t.qualifies(10, 9.99)).toBe(true);
    expect(t.add("last", 1, 1, d(30))).toBeNull();
    expect(t.add("  ", 99, 1, d(31))).toBe(1);
    expect(t.entries[0].name).toBe("Anonymous");
  });

  test("names and times are shown like the desktop's", () => {
    expect(cleanName("  Ada\t\nLovelace ")).toBe("Ada Lovelace");
    expect(cleanName("a\u0000b")).toBe("a b");
    expect(cleanName("字".repeat(20))).toBe("字".repeat(16));
    expect(cleanName("😀".repeat(17))).toHaveLength(32); // 16 code points, 2 units each
    expect(formatSeconds(83.25)).toBe("1:23.3");
    expect(formatSeconds(59.96)).toBe("1:00.0");
    expect(formatSeconds(0)).toBe("0:00.0");
  });

  test("a damaged or foreign stored table is set aside, reported once, and the new one saved", () => {
    const kv = new MemoryStore();
    const key = scoresKey("49-r12-seed-rim");
    for (const bad of ["[1,2", '{"version": 2, "entries": []}', '{"entries": 3}']) {
      kv.map.clear();
      kv.setItem(key, bad);
      const t = new HighScoreTable(kv, key);
      const notes = t.takeNotices();
      expect(notes).toHaveLength(1);
      expect(t.entries).toEqual([]);
      expect([...kv.map.values()]).toEqual([bad]);
      expect(new HighScoreTable(kv, key).takeNotices()).toEqual([]);
      t.add("Bo", 5, 5);
      expect(new HighScoreTable(kv, key).entries[0].name).toBe("Bo");
    }
  });

  test("one bad row: only it is set aside, the good rows stay in the table (issue 27.11)", () => {
    const kv = new MemoryStore();
    const key = scoresKey("49-r12-seed-rim");
    const good = (name: string, score: number) => ({
      name,
      score,
      seconds: 40,
      date: "2026-11-20 10:00:00",
    });
    const bad = { name: "", score: 9, seconds: 1, date: "2026-11-20 10:00:00" };
    kv.setItem(
      key,
      JSON.stringify({ version: 1, entries: [good("Ann", 30), bad, good("Bo", 20)] }),
    );
    const t = new HighScoreTable(kv, key);
    expect(t.entries.map((e) => e.name)).toEqual(["Ann", "Bo"]);
    const notes = t.takeNotices();
    expect(notes).toHaveLength(1);
    expect(notes[0]).toMatch(
      /1 damaged row \(bad name ""\); kept as "evapcool\.highscores\..*corrupt-/,
    );
    const aside = [...kv.map.entries()].filter(([k]) => k !== key);
    expect(aside).toHaveLength(1);
    expect(JSON.parse(aside[0][1]).entries).toEqual([bad]);
    // Written back without the bad row: the next visit sees the two rows and no notice.
    const again = new HighScoreTable(kv, key);
    expect(again.entries.map((e) => e.name)).toEqual(["Ann", "Bo"]);
    expect(again.takeNotices()).toEqual([]);
  });

  test("two tabs: each result is merged into what the other stored meanwhile", () => {
    const kv = new MemoryStore();
    const key = scoresKey("k");
    const a = new HighScoreTable(kv, key);
    const b = new HighScoreTable(kv, key);
    expect(a.add("Ann", 20, 10)).toBe(1);
    expect(b.add("Ben", 30, 10)).toBe(1);
    expect(b.entries.map((e) => e.name)).toEqual(["Ben", "Ann"]);
    expect(a.add("Cy", 25, 10)).toBe(2);
    expect(new HighScoreTable(kv, key).entries.map((e) => e.name)).toEqual(["Ben", "Cy", "Ann"]);
    b.load();
    expect(b.entries).toHaveLength(3);
  });

  test("a browser that refuses to store gives a notice, the table lives on", () => {
    const kv = new MemoryStore();
    kv.setItem = () => {
      throw new DOMException("full", "QuotaExceededError");
    };
    const t = new HighScoreTable(kv, scoresKey("x"));
    expect(t.add("Cy", 3, 3)).toBe(1);
    expect(t.takeNotices()).toEqual([
      "High scores could not be saved in this browser (QuotaExceededError); kept for this visit.",
    ]);
    expect(t.entries).toHaveLength(1);
  });
});

describe("game rules (the clock is the core's: core/play.c)", () => {
  const make = () => new Game(makeSimulation, { nAtoms: 49, seed: 3 });

  test("starts paused at 400; speed doubles and halves within 1/4 to 4", () => {
    const game = make();
    expect(game.paused).toBe(true);
    expect(game.trapHeight).toBe(400);
    expect(game.update(1)).toBe(0);
    for (let k = 0; k < 5; k++) game.faster();
    expect(game.speed).toBe(4);
    for (let k = 0; k < 7; k++) game.slower();
    expect(game.speed).toBe(0.25);
  });

  test("the trap is clamped to the slider and moves only at whole frames", () => {
    const game = make();
    game.setTrapHeight(1000);
    expect(game.trapHeight).toBe(HEIGHT_MAX);
    game.setTrapHeight(-5);
    expect(game.trapHeight).toBe(HEIGHT_MIN);
    game.setTrapHeight(400);
    game.paused = false;
    game.update(0.5 / 30); // half a frame: now between boundaries
    game.setTrapHeight(380);
    expect(game.sim.trapHeight).toBe(400);
    expect(game.trapHeight).toBe(380);
    game.update(0.25 / 30);
    expect(game.sim.trapHeight).toBe(400);
    game.update(0.5 / 30);
    // The change took effect exactly at frame 1.
    expect(game.sim.trapHeight).toBe(380);
    expect(game.moves()).toEqual([[400, 1]]);
    game.runFrames(2);
    expect(game.moves()).toEqual([
      [400, 1],
      [380, 2],
    ]);
  });

  test("holdHeight: the worker holds a height as the page's mirror sent it (clamped once)", () => {
    const game = make();
    expect(game.holdHeight(300)).toBe(true);
    expect(game.sim.trapHeight).toBe(300); // paused: at once
    expect(game.holdHeight(300)).toBe(false);
    game.paused = false;
    game.runFrames(2);
    forceWin(game.sim);
    game.runFrames(1);
    expect(game.won).toBe(true);
    expect(game.holdHeight(350)).toBe(false); // frozen after the win
    expect(game.trapHeight).toBe(300);
  });

  test("pausing mid-frame finishes the frame: a paused height lands on a whole frame", () => {
    const game = make();
    game.paused = false;
    game.update(0.4 / 30);
    game.paused = true;
    expect(game.sim.time).toBe(1);
    game.setTrapHeight(320);
    expect(game.sim.trapHeight).toBe(320); // at once: frame 1 on starts with it
    const held: number[] = [];
    game.onFrame.push((h) => held.push(h));
    game.paused = false;
    game.runFrames(2);
    expect(held).toEqual([320, 320]);
  });

  test("a stall never jumps the game ahead: at most 2 physics frames a drawn frame at 1x", () => {
    const game = make();
    game.paused = false;
    game.update(5);
    expect(game.sim.time).toBeCloseTo(2, 12);
  });

  test("the win is announced once, with its frame's play time; the trap then freezes", () => {
    const game = make();
    const wins: number[] = [];
    game.onWin.push((g) => wins.push(g.wonAt ?? -1));
    game.paused = false;
    game.runFrames(1);
    forceWin(game.sim); // the gas condenses in frame 1: seen at its end
    game.update(1.5 / 30);
    game.runFrames(3);
    expect(wins).toEqual([2 / 30]);
    expect(game.score).toBe(game.sim.nTrapped);
    expect(game.moves()).toEqual([[400, 2]]); // the moves end with the win's frame
    expect(game.setTrapHeight(100)).toBe(false);
    game.restart();
    expect(game.score).toBeNull();
    expect(game.paused).toBe(true);
  });

  test("a recording watched holds its heights from the start and refuses the player's", () => {
    const game = make();
    game.playback([
      [300, 2],
      [200, 1],
    ]);
    expect(game.trapHeight).toBe(300);
    expect(game.setTrapHeight(100)).toBe(false);
    game.paused = false;
    game.runFrames(3);
    expect(game.sim.trapHeight).toBe(200);
    expect(game.setTrapHeight(100)).toBe(true); // its frames are over: the player's again
    expect(game.moves()).toEqual([
      [300, 2],
      [200, 1],
    ]);
  });

  test("moves beyond the core's buffer of runs are all kept (CORE_MOVES_CAPACITY)", () => {
    const game = make();
    game.paused = false;
    const want: Array<[number, number]> = [];
    for (let k = 0; k < 3 * CORE_MOVES_CAPACITY + 5; k++) want.push([450 - (k % 7), 1 + (k % 3)]);
    for (const [h, n] of want) {
      game.setTrapHeight(h);
      game.runFrames(n);
    }
    expect(game.moves()).toEqual(want);
  });

  test("step: one frame, only while paused", () => {
    const game = make();
    expect(game.step()).toBe(1);
    game.paused = false;
    expect(game.step()).toBe(0);
    expect(game.sim.time).toBe(1);
  });
});

describe("too few atoms (the core's reach rule)", () => {
  test("each code of the core is its message key, asked with H_min and the trap asked for", () => {
    const game = new Game(makeSimulation, { nAtoms: 49, seed: 3 });
    let code = 0;
    let asked: number[] = [];
    game.sim.outOfReach = (lowest: number, height: number) => ((asked = [lowest, height]), code);
    const keys = [null, "lose.all_escaped", "lose.one_atom", "lose.stuck", "lose.stuck_here"];
    keys.forEach((key, k) => {
      code = k;
      expect(game.tooFewAtoms()).toBe(key);
    });
    expect(LOSE_REASONS).toEqual(keys);
    // one key per code of the core's (generated from its header): a new code needs its key
    expect(LOSE_REASONS).toEqual(REACH_NAMES.map((n) => (n === "within" ? null : `lose.${n}`)));
    expect(asked).toEqual([HEIGHT_MIN, 400]);
    game.setTrapHeight(60);
    game.tooFewAtoms();
    expect(asked).toEqual([HEIGHT_MIN, 60]);
  });
});

describe("address options", () => {
  test("values for this visit; one message per bad value", () => {
    const p = parseParams("?atoms=10000&radius=1&seed=3&speed=2", DEFAULTS);
    expect(p).toEqual({
      overrides: { radius: 1, nAtoms: 10000 },
      seed: 3,
      speed: 2,
      replay: null,
      lang: null,
      trap: null,
      lock: [],
      hide: [],
      theme: null,
      sound: null,
      notices: [],
    });
    const q = parseParams("?atoms=2.5&speed=8&escape=door&zoom=2", DEFAULTS);
    expect(q.overrides).toEqual({});
    expect(q.notices).toEqual([
      'Address: unknown option "zoom"; known: atoms, radius, seed, speed, tc-law, escape, replay, lang, trap, lock, hide, theme, sound.',
      'Address: atoms must be a whole number from 1 to 100000 (got "2.5"); ignored.',
      'Address: escape must be one of rim, knife (got "door"); ignored.',
      'Address: speed must be a number from 0.25 to 4 (got "8"); ignored.',
    ]);
    expect(parseParams("?radius=20", DEFAULTS).overrides).toEqual({ radius: 20, nAtoms: 20 });
  });

  test("notices name what was typed, shortened; hex, words and repeats are refused (issues 25.6, 27.10)", () => {
    const long = "9".repeat(5000);
    expect(parseParams(`?radius=abc&atoms=${long}`, DEFAULTS).notices).toEqual([
      'Address: radius must be a number from 0.01 to 1000 px (got "abc"); ignored.',
      'Address: atoms must be a whole number from 1 to 100000 (got "99999999999999999999…" (5,000 characters)); ignored.',
    ]);
    const hex = parseParams("?atoms=0x20&seed=1e3&speed=Infinity", DEFAULTS);
    expect(hex.overrides).toEqual({});
    expect(hex.seed).toBe(1000);
    expect(hex.notices).toEqual([
      'Address: atoms must be a whole number from 1 to 100000 (got "0x20"); ignored.',
      'Address: speed must be a number from 0.25 to 4 (got "Infinity"); ignored.',
    ]);
    const twice = parseParams("?atoms=50&atoms=7&seed=2", DEFAULTS);
    expect(twice.overrides).toEqual({});
    expect(twice.seed).toBe(2);
    expect(twice.notices).toEqual(["Address: atoms is given 2 times; give it once. Ignored."]);
    const name = "x".repeat(3000);
    const [notice] = parseParams(`?${name}=1`, DEFAULTS).notices;
    // Shortened: the typed name to 24 characters, then the known options' list.
    expect(notice.length).toBeLessThan(80 + ADDRESS_OPTIONS.join(", ").length);
    expect(notice).toContain("(3,000 characters)");
  });

  test("any radius and count in range is accepted or named", () => {
    fc.assert(
      fc.property(fc.double({ noNaN: false }), fc.integer({ min: -5, max: 200_000 }), (r, n) => {
        const p = parseParams(`?radius=${r}&atoms=${n}`, DEFAULTS);
        const ok = Object.keys(p.overrides).length === 2;
        return ok ? p.notices.length === 0 : p.notices.length >= 1;
      }),
    );
  });
});
