// A game's path sampled in the core (core_path, issue 47) in WebAssembly: the same points as
// the Python edition computed (golden/paths.json, whose native core_path the reference
// engine's loop checks bit for bit in tests/game/test_path.py), once T is rounded as both
// editions round it.
import { readFileSync } from "node:fs";
import { describe, expect, it } from "vitest";
import { makeSimulation } from "../src/game/engine";
import { roundT, strideOf, type GamePath } from "../src/game/path";
import { startOf, type Recording } from "../src/game/replay";
import { clampHeight } from "../src/game/rules";
import { framesOf } from "../src/game/moves";
import type { WasmEngine } from "../src/physics/wasm";

interface Case {
  recording: Recording;
  path: GamePath;
}
const CASES: Case[] = JSON.parse(
  readFileSync(new URL("./golden/paths.json", import.meta.url), "utf8"),
).cases;

/** The WebAssembly engine under a game's simulation (a test's look inside). */
const engineOf = (sim: unknown) => (sim as { engine: WasmEngine }).engine;

describe("the core's path sampling in WebAssembly", () => {
  it("is the Python edition's path, point for point", () => {
    expect(CASES.length).toBeGreaterThanOrEqual(4);
    for (const { recording: rec, path: want } of CASES) {
      const sim = startOf(rec, makeSimulation);
      const t0 = sim.temperature;
      const runs = rec.moves.map(([h, n]) => [clampHeight(h), n] as const);
      const total = framesOf(rec.moves);
      const { frames, rows } = engineOf(sim).path(runs, total, strideOf(total), runs[0][0]);
      const got: GamePath = {
        k: rows.map((r) => r[0]),
        n: rows.map((r) => r[1]),
        t: rows.map((r) => roundT(r[2])),
        h: rows.map((r) => r[3]),
        frames,
        won: sim.score !== null,
        score: sim.score ?? 0,
        t0,
      };
      expect(got).toEqual(want);
    }
  });
});
