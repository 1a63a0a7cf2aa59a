// Invariants of the exact model, over random gases (fast-check), through the WebAssembly core
// (Simulation's one engine, test/wasm.test.ts): energy kept, no overlap, no centre below the
// wall, no NaN, consistent counts, and exact resumption from a state.
import fc from "fast-check";
import { describe, expect, it } from "vitest";
import { Simulation, type SimulationOptions } from "../src/physics/index";
import { stateText } from "../src/physics/trace";

// CI runs the same examples every time (as Python's hypothesis profile does); developers'
// runs explore new ones and print the seed of any failure.
if (process.env.CI) fc.configureGlobal({ seed: 20_261_123 });

/** A gas of the game's start with random count, radius, masses, seed and rules. */
const gas = fc
  .record({
    fill: fc.double({ min: 0, max: 1, noNaN: true }),
    radius: fc.double({ min: 2, max: 12, noNaN: true }),
    seed: fc.nat(),
    heavy: fc.double({ min: 1, max: 4, noNaN: true }),
    tcExponent: fc.constantFrom(2 / 3, 2 / 5),
    trapHeight: fc.constantFrom(Infinity, 450, 200, 80),
    escape: fc.constantFrom("rim" as const, "knife" as const),
  })
  .map(({ fill, ...g }) => {
    // At most 150 atoms, and at most what the cup holds below the window (93 of radius 12).
    const room = Math.min(150, Math.floor(80 * (12 / g.radius) ** 2));
    return { ...g, nAtoms: Math.max(1, Math.round(fill * room)) };
  });
type Gas = typeof gas extends fc.Arbitrary<infer T> ? T : never;

/** The game's start for the gas, then every third atom made heavier (per-atom masses). */
function build(g: Gas, extra: SimulationOptions = {}): Simulation {
  const start = new Simulation({ nAtoms: g.nAtoms, radius: g.radius, seed: g.seed });
  const mass = Array.from({ length: g.nAtoms }, (_, i) => (i % 3 === 0 ? g.heavy : 1));
  return new Simulation({
    positions: start.positions,
    velocities: start.velocities,
    radius: g.radius,
    mass,
    trapHeight: g.trapHeight,
    escape: g.escape,
    tcExponent: g.tcExponent,
    ...extra,
  });
}

/** Every invariant of a state now; a message for the first one broken, else "". */
function broken(sim: Simulation): string {
  const p = sim.positions;
  const v = sim.velocities;
  const r = sim.radii;
  const n = sim.nTrapped;
  for (let k = 0; k < p.length; k++)
    if (!Number.isFinite(p[k]) || !Number.isFinite(v[k])) return `NaN at ${k}`;
  for (let i = 0; i < n; i++) {
    const x = p[2 * i];
    const wall = sim.curvature * x * x;
    if (p[2 * i + 1] < wall - 1e-9 * (1 + wall))
      return `atom ${i} below the wall by ${wall - p[2 * i + 1]}`;
    // After the win the condensate's atoms no longer collide with each other (docs/model.md).
    for (let j = i + 1; j < n && !sim.won; j++) {
      const d = Math.hypot(p[2 * j] - x, p[2 * j + 1] - p[2 * i + 1]);
      if (d < (r[i] + r[j]) * (1 - 1e-9)) return `atoms ${i}, ${j} overlap: ${d} < ${r[i] + r[j]}`;
    }
  }
  const gone = sim.nAtoms - sim.nTrapped - sim.nEscaped;
  if (gone < 0) return "more atoms trapped and escaped than there are";
  if (sim.collisionCount !== sim.pairCollisionCount + sim.wallCollisionCount) return "counters";
  if (sim.engineStats.gridErrors !== 0) return `${sim.engineStats.gridErrors} atoms in wrong cells`;
  return "";
}

describe("properties", () => {
  it("energy is conserved to 1e-9 over long runs with the rim out of reach", () => {
    fc.assert(
      fc.property(gas, fc.integer({ min: 200, max: 1500 }), (g, frames) => {
        const sim = build({ ...g, trapHeight: Infinity, escape: "rim" });
        const e0 = sim.totalEnergy();
        for (let f = 0; f < frames; f += 100) {
          sim.advance(Math.min(100, frames - f));
          expect(broken(sim)).toBe("");
        }
        expect(sim.nTrapped).toBe(g.nAtoms);
        expect(Math.abs(sim.totalEnergy() - e0)).toBeLessThanOrEqual(1e-9 * e0);
      }),
      { numRuns: 25 },
    );
  });

  it("no overlap, no centre below the wall, no NaN, counts consistent, with escapes and the knife", () => {
    fc.assert(
      fc.property(
        gas,
        fc.array(fc.double({ min: 0, max: 40, noNaN: true }), { minLength: 1, maxLength: 12 }),
        (g, dts) => {
          const sim = build(g, { recordEvents: true });
          let trapped = sim.nTrapped;
          for (const dt of dts) {
            sim.advance(dt);
            expect(broken(sim)).toBe("");
            expect(sim.nTrapped).toBeLessThanOrEqual(trapped);
            trapped = sim.nTrapped;
          }
          const log = sim.eventLog;
          const count = (k: string) => log.filter((e) => e.kind === k).length;
          expect(count("pair")).toBe(sim.pairCollisionCount);
          expect(count("wall")).toBe(sim.wallCollisionCount);
          expect(count("escape") + count("knife")).toBe(g.nAtoms - sim.nTrapped);
          expect(count("gone")).toBe(count("escape") - sim.nEscaped);
          for (let k = 1; k < log.length; k++)
            expect(log[k].time).toBeGreaterThanOrEqual(log[k - 1].time);
        },
      ),
      { numRuns: 40 },
    );
  });

  it("splitting a run into steps changes no event", () => {
    fc.assert(
      fc.property(
        gas,
        fc.array(fc.double({ min: 0, max: 5, noNaN: true }), { minLength: 1, maxLength: 20 }),
        (g, dts) => {
          const whole = build(g, { recordEvents: true });
          const split = build(g, { recordEvents: true });
          let total = 0;
          for (const dt of dts) {
            split.advance(dt);
            total = split.time;
          }
          whole.advance(total);
          expect(split.eventLog).toEqual(whole.eventLog);
        },
      ),
      { numRuns: 30 },
    );
  });

  it("a state saved at any time resumes exactly", () => {
    fc.assert(
      fc.property(
        gas,
        fc.double({ min: 0, max: 60, noNaN: true }),
        fc.double({ min: 0, max: 60, noNaN: true }),
        (g, t1, t2) => {
          const straight = build(g, { recordEvents: true });
          straight.advance(t1);
          const resumed = Simulation.fromState(stateText(straight), { recordEvents: true });
          const before = straight.eventCount;
          straight.advance(t2);
          resumed.advance(t2);
          expect(resumed.eventLog).toEqual(straight.eventLog.slice(before));
          expect(stateText(resumed)).toBe(stateText(straight));
        },
      ),
      { numRuns: 30 },
    );
  });
});
