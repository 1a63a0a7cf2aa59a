// The reach rule written once in the core (core_out_of_reach, issue 47) in WebAssembly: the
// answer of the Python edition's readable rule, the core's oracle, on states near every
// threshold (cases/reach.json, written by scripts/reach_cases.py and checked fresh by
// tests/physics/test_core_reach.py), the game's message for it, and over any trap height.
import { readFileSync } from "node:fs";
import fc from "fast-check";
import { describe, expect, it } from "vitest";
import { Game, HEIGHT_MAX, HEIGHT_MIN, LOSE_REASONS } from "../src/game/rules";
import { emptyAtoms } from "../src/game/sim";
import { REACH_NAMES, REACH_STUCK_HERE, REACH_WITHIN } from "../src/physics/model";
import { Simulation } from "../src/physics/simulation";

if (process.env.CI) fc.configureGlobal({ seed: 20_261_123 });

interface Case {
  case: string;
  state: Parameters<typeof Simulation.fromState>[0];
  height: number;
  code: number;
  reason: string;
}
const FIXTURE = JSON.parse(
  readFileSync(new URL("./cases/reach.json", import.meta.url), "utf8"),
) as {
  lowest: number;
  cases: Case[];
};
const CASES = FIXTURE.cases;
const SIMS = CASES.map((c) => Simulation.fromState(c.state));

describe("the core's reach rule in WebAssembly", () => {
  it("gives the Python edition's answer on every shared case", () => {
    expect(FIXTURE.lowest).toBe(HEIGHT_MIN);
    expect(new Set(CASES.map((c) => c.reason))).toEqual(new Set(REACH_NAMES));
    CASES.forEach((c, k) => {
      expect([c.case, SIMS[k].outOfReach(HEIGHT_MIN, c.height)]).toEqual([c.case, c.code]);
      expect(REACH_NAMES[c.code]).toBe(c.reason);
    });
  });

  it("is the game's message, for the trap the player asked for", () => {
    for (const c of CASES) {
      const sim = Object.assign(Simulation.fromState(c.state), {
        trapped: emptyAtoms,
        escaped: emptyAtoms,
      });
      const game = new Game(() => sim);
      game.setTrapHeight(c.height);
      const want = c.reason === "within" ? null : `lose.${c.reason}`;
      expect([c.case, game.tooFewAtoms()]).toEqual([c.case, want]);
      expect(LOSE_REASONS[c.code]).toBe(want);
    }
  });

  it("over any trap height: the answer at the lowest rim, or 'lower the trap' while E <= m g H", () => {
    const lightest = (sim: Simulation) => Math.min(...sim.atoms().mass.subarray(0, sim.nTrapped));
    fc.assert(
      fc.property(
        fc.nat({ max: CASES.length - 1 }),
        fc.double({ min: HEIGHT_MIN, max: HEIGHT_MAX, noNaN: true }),
        (k, h) => {
          const sim = SIMS[k];
          const base = sim.outOfReach(HEIGHT_MIN, HEIGHT_MIN);
          let want = base;
          if (base === REACH_WITHIN && !sim.won && sim.winRule && sim.nTrapped > 1) {
            const below = sim.temperature < sim.criticalTemperature;
            const stuck = sim.totalEnergy() <= lightest(sim) * sim.gravity * h;
            want = !below && stuck ? REACH_STUCK_HERE : REACH_WITHIN;
          }
          expect(sim.outOfReach(HEIGHT_MIN, h)).toBe(want);
        },
      ),
      { numRuns: 500 },
    );
  });
});
