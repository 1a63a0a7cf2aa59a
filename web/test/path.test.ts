// The debrief's paths (issue 36): the path the page computes for a game equals the one the
// Python edition computed for it (scripts/golden_starts.py -> golden/paths.json), point for
// point, and the sampling keeps the frames it says.
import { readFileSync } from "node:fs";
import { describe, expect, it } from "vitest";
import { makeSimulation } from "../src/game/engine";
import { gamePath, MAX_POINTS, roundT, strideOf, type GamePath } from "../src/game/path";
import type { Recording } from "../src/game/replay";

interface Case {
  recording: Recording;
  path: GamePath;
}
const CASES: Case[] = JSON.parse(
  readFileSync(new URL("./golden/paths.json", import.meta.url), "utf8"),
).cases;

describe("a game's path", () => {
  it("is the Python edition's, point for point", () => {
    expect(CASES.length).toBeGreaterThanOrEqual(4);
    for (const c of CASES) expect(gamePath(c.recording, makeSimulation)).toEqual(c.path);
  });

  it("keeps at most MAX_POINTS points, frame 0, every stride-th frame and the last", () => {
    for (const c of CASES) {
      const p = c.path;
      const stride = strideOf(p.frames);
      expect(p.k.length).toBeLessThanOrEqual(MAX_POINTS);
      expect(p.k[0]).toBe(0);
      expect(p.k[p.k.length - 1]).toBe(p.frames);
      for (const k of p.k.slice(0, -1)) expect(k % stride).toBe(0);
    }
  });

  it("stops at the verified length when given one", () => {
    const c = CASES[0];
    const short = gamePath(c.recording, makeSimulation, 100);
    expect(short.frames).toBe(100);
    expect(short.won).toBe(false);
    expect(short.k[short.k.length - 1]).toBe(100);
  });

  it("rounds T to 5 significant digits", () => {
    expect(roundT(80.00136587525876)).toBe(80.001);
    expect(roundT(0.000123456)).toBe(0.00012346);
  });
});
