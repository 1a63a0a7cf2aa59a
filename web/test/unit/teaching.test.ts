// The page's teacher parts without a browser (issue 48): preferences kept and refused, the
// run's CSV in the lab's columns, the scene's sentence, the tick's pitch, the link written.
import { expect, test } from "vitest";
import { MemoryStore } from "../../src/game/store";
import { DEFAULTS } from "../../src/game/settings";
import { loadPrefs, PREFS_KEY, savePrefs, stepPref } from "../../src/app/prefs";
import { LAB_COLUMNS, RunLog } from "../../src/app/runlog";
import { SceneWatch } from "../../src/app/describe";
import { tickPitch } from "../../src/app/sound";
import { linkFor, Setup } from "../../src/app/setup";
import { parseParams } from "../../src/app/params";
import type { GameLike } from "../../src/runtime/remote";

test("preferences: stored, and anything unusable falls back per field", () => {
  const kv = new MemoryStore();
  expect(loadPrefs(kv)).toEqual({ theme: "dark", sound: null, volume: 0.6, everyFrame: false });
  savePrefs(kv, { theme: "projector", sound: false, volume: 0.3, everyFrame: true });
  expect(loadPrefs(kv)).toEqual({
    theme: "projector",
    sound: false,
    volume: 0.3,
    everyFrame: true,
  });
  kv.setItem(PREFS_KEY, '{"theme":"pink","sound":"loud","volume":7}');
  expect(loadPrefs(kv)).toEqual({ theme: "dark", sound: null, volume: 0.6, everyFrame: false });
  kv.setItem(PREFS_KEY, "{not json");
  expect(loadPrefs(kv).theme).toBe("dark");
  const p = loadPrefs(kv);
  expect(stepPref(p, 0, 1, true).theme).toBe("projector");
  expect(stepPref(p, 1, 1, true).sound).toBe(false);
  expect(stepPref({ ...p, volume: 1 }, 2, 1, true).volume).toBe(1);
  expect(stepPref({ ...p, volume: 0.1 }, 2, -1, true).volume).toBe(0);
});

/** A game as the page sees it, moved by hand. */
function fakeGame(): { g: GameLike; sim: Record<string, number> } {
  const sim = { time: 0, nAtoms: 10, nTrapped: 10, temperature: 9, criticalTemperature: 3 };
  const g = {
    sim,
    generation: 0,
    trapHeight: 300,
    won: false,
    paused: false,
    score: null,
    config: { seed: 4 },
    tooFewAtoms: () => null,
  } as unknown as GameLike;
  return { g, sim };
}

test("the run's rows: one a second (or a frame), the lab's columns, nan where not counted", () => {
  const { g, sim } = fakeGame();
  const log = new RunLog();
  for (let f = 0; f <= 90; f += 1.5) {
    sim.time = f;
    sim.nTrapped = 10 - Math.floor(f / 30);
    log.record(g);
  }
  expect(log.count).toBe(4);
  const lines = log.csv({ seed: 4 }, "EC1.x").trimEnd().split("\n");
  expect(lines[0]).toBe("# evapcool lab results");
  expect(lines).toContain('# replay_code: "EC1.x"');
  const header = lines.indexOf(LAB_COLUMNS.join(","));
  expect(header).toBeGreaterThan(0);
  expect(lines[header + 2]).toBe("30,9,9.0,3.0,300.0,nan,nan,nan,1,nan,nan,nan,nan,nan,nan,0");
  const every = new RunLog();
  every.everyFrame = true;
  for (let f = 0; f < 10; f++) {
    sim.time = f;
    every.record(g);
  }
  expect(every.count).toBe(10);
});

test("the scene's sentence says what happens", () => {
  const { g, sim } = fakeGame();
  const w = new SceneWatch();
  w.frame(g);
  expect(w.sentence(g)).toBe(
    "Atoms in the cup: 10; T 9.00, Tc 3.00; trap height 300 px; no atom leaving now.",
  );
  sim.time = 10;
  sim.nTrapped = 9;
  w.frame(g);
  expect(w.happening(g)).toBe("atoms leaving");
  sim.temperature = 3.5;
  expect(w.happening(g)).toBe("atoms leaving, close to condensing");
  sim.time = 200;
  expect(w.happening(g)).toBe("close to condensing");
});

test("a tick's pitch rises with the energy the atom needed to leave", () => {
  expect(tickPitch(25)).toBeCloseTo(300);
  expect(tickPitch(450)).toBeCloseTo(2400);
  expect(tickPitch(200)).toBeGreaterThan(tickPitch(100));
});

test("the link written parses back to the same options, with no notice", () => {
  const setup = new Setup({
    trap: 250,
    lock: ["atoms", "trap"],
    hide: ["help"],
    theme: "projector",
    sound: false,
  });
  const link = linkFor("file:///x/evapcool.html", {
    settings: { ...DEFAULTS, nAtoms: 30, escape: "knife" },
    seed: 12,
    speed: 0.5,
    trapHeight: 250,
    theme: "projector",
    soundOn: false,
    setup,
  });
  const p = parseParams(link.slice(link.indexOf("?")), DEFAULTS);
  expect(p.notices).toEqual([]);
  expect(p.overrides).toMatchObject({ nAtoms: 30, escape: "knife" });
  expect([p.seed, p.speed, p.trap, p.theme, p.sound]).toEqual([12, 0.5, 250, "projector", false]);
  expect(p.lock).toEqual(["atoms", "trap"]);
  expect(p.hide).toEqual(["help"]);
});
