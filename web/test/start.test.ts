// The shared start generator and the win (issue 22.1): the starts and the autopilot's won games
// the Python edition wrote (scripts/golden_starts.py -> golden/starts.json, wins.json) come out
// of the page's engine, the WebAssembly core, bit for bit.
import { readFileSync } from "node:fs";
import fc from "fast-check";
import { describe, expect, it } from "vitest";
import { Game } from "../src/game/rules";
import { makeSimulation } from "../src/game/engine";
import { Simulation } from "../src/physics/simulation";
import { SEED_PORTABLE_MAX } from "../src/physics/start";
import { loadCup, power } from "../src/physics/instance";

interface StartCase {
  atoms: number;
  radius: number;
  seed: number;
  positions: number[];
  velocities: number[];
  critical_temperature: number;
}
interface Recording {
  settings: { n_atoms: number; radius: number; escape: "rim" | "knife"; tc_exponent: number };
  seed: number;
  moves: [number, number][];
  won: boolean;
  score: number;
  frames: number;
}

const read = (name: string) =>
  JSON.parse(readFileSync(new URL(`./golden/${name}`, import.meta.url), "utf8"));
const STARTS: StartCase[] = read("starts.json").cases;
const WINS: Recording[] = read("wins.json").recordings;

/** The bits of a float as hex (0 and -0 differ). */
function bits(x: number): string {
  const v = new DataView(new ArrayBuffer(8));
  v.setFloat64(0, x);
  return v.getBigUint64(0).toString(16);
}

/** Replay like game/replay.py: hold each frame's height, one whole frame, stop at the win. */
function replay(rec: Recording): { won: boolean; score: number; frames: number } {
  const s = rec.settings;
  const game = new Game(makeSimulation, {
    nAtoms: s.n_atoms,
    radius: s.radius,
    seed: rec.seed,
    speed: 1,
    tcExponent: s.tc_exponent,
    escape: s.escape,
  });
  game.togglePause();
  let frames = 0;
  for (const [height, n] of rec.moves)
    for (let k = 0; k < n; k++) {
      game.setTrapHeight(height);
      game.runFrames(1);
      frames++;
      if (game.won) return { won: true, score: game.score ?? 0, frames };
    }
  return { won: false, score: 0, frames };
}

describe("the WebAssembly core", () => {
  for (const c of STARTS)
    it(`starts ${c.atoms} atoms of radius ${c.radius} from seed ${c.seed} as Python does`, () => {
      const sim = new Simulation({ nAtoms: c.atoms, radius: c.radius, seed: c.seed });
      expect(Array.from(sim.positions, bits)).toEqual(c.positions.map(bits));
      expect(Array.from(sim.velocities, bits)).toEqual(c.velocities.map(bits));
      expect(bits(sim.criticalTemperature)).toBe(bits(c.critical_temperature));
    });
  for (const rec of WINS)
    it(`replays the won game of seed ${rec.seed} (${rec.settings.escape}, p = ${rec.settings.tc_exponent}) to its score`, () => {
      expect(replay(rec)).toEqual({ won: rec.won, score: rec.score, frames: rec.frames });
    });
});

describe("the start generator (the core's)", () => {
  it("refuses a seed a double cannot hold or a negative one", () => {
    expect(() => loadCup(49, 12, 0.01, 532, 2 ** 53)).toThrow(RangeError);
    expect(() => loadCup(49, 12, 0.01, 532, -1)).toThrow(/seed must be a whole number/);
    expect(() => loadCup(49, 12, 0.01, 532, SEED_PORTABLE_MAX)).not.toThrow();
  });

  it("refuses more atoms than the cup holds, saying how many fit", () => {
    expect(() => loadCup(200, 12, 0.01, 400, 1)).toThrow(
      /nAtoms: 200 atoms of radius 12 do not fit in the cup below the window top \(at most \d+ fit\)/,
    );
  });

  it("places atoms apart, at speeds of their rows, the same from the same seed", () => {
    fc.assert(
      fc.property(fc.integer({ min: 0, max: SEED_PORTABLE_MAX }), (seed) => {
        const { positions: p, velocities: v } = loadCup(64, 5, 0.01, 2000, seed);
        const again = loadCup(64, 5, 0.01, 2000, seed);
        if (!again.positions.every((x, k) => Object.is(x, p[k]))) return false;
        for (let i = 0; i < 64; i++) {
          const speed = Math.hypot(v[2 * i], v[2 * i + 1]);
          if (!(speed >= 100 / 30 && speed < 100 / 30 + 10)) return false;
          for (let j = 0; j < i; j++)
            if (Math.hypot(p[2 * i] - p[2 * j], p[2 * i + 1] - p[2 * j + 1]) < 10) return false;
        }
        return true;
      }),
      { numRuns: 100 },
    );
  });
});

describe("power from products and square roots", () => {
  it("is within a few units in the last place of Math.pow", () => {
    fc.assert(
      fc.property(
        fc.double({ min: 1e-6, max: 1, noNaN: true }),
        fc.double({ min: 0.01, max: 10, noNaN: true }),
        (x, p) => {
          const want = Math.pow(x, p);
          return want === 0 || Math.abs(power(x, p) - want) / want < 64 * Number.EPSILON;
        },
      ),
      { numRuns: 2000 },
    );
    expect(power(0, 2 / 3)).toBe(0);
    expect(power(1, 2 / 5)).toBe(1);
    expect(power(0.25, 0.5)).toBe(0.5);
  });
});
