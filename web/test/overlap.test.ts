// The overlap check is the core's (core/overlap.c, issue 47) in WebAssembly: the first pair
// the Python edition's readable check finds (scripts/overlap_cases.py -> cases/overlaps.json),
// and over random atoms (fast-check) the pair every pair's comparison gives.
import fc from "fast-check";
import { readFileSync } from "node:fs";
import { describe, expect, it } from "vitest";
import { firstOverlap } from "../src/physics/validation";

if (process.env.CI) fc.configureGlobal({ seed: 20_261_207 });

interface Case {
  x: number[];
  y: number[];
  radius: number[];
  include: number[];
  tol: number;
  pair: [number, number] | null;
}
const CASES: Case[] = JSON.parse(
  readFileSync(new URL("./cases/overlaps.json", import.meta.url), "utf8"),
).cases;

const f64 = (v: number[]) => Float64Array.from(v);

/** The first pair by looking at every one, with the comparison both editions make. */
function everyPair(c: Omit<Case, "pair">): [number, number] | null {
  const { x, y, radius: r, include, tol } = c;
  for (let i = 0; i < x.length; i++)
    for (let j = i + 1; j < x.length; j++) {
      const dx = x[i] - x[j];
      const dy = y[i] - y[j];
      const lim = (r[i] + r[j]) * (1 - tol);
      if (include[i] && include[j] && dx * dx + dy * dy < lim * lim) return [i, j];
    }
  return null;
}

const check = (c: Omit<Case, "pair">) =>
  firstOverlap(f64(c.x), f64(c.y), f64(c.radius), (i) => c.include[i] === 1, c.tol);

/** Atoms of mixed radii in a box, some put at a partner's contact distance (give or take a
 * unit in the last place of the product), a tolerance and a mask. */
const atoms = fc.integer({ min: 0, max: 40 }).chain((n) => {
  const column = (min: number, max: number) =>
    fc.array(fc.double({ min, max, noNaN: true }), { minLength: n, maxLength: n });
  const sizes = fc.array(
    fc.oneof(
      fc.double({ min: 0.01, max: 0.1, noNaN: true }),
      fc.double({ min: 0.5, max: 3, noNaN: true }),
      fc.double({ min: 5, max: 20, noNaN: true }),
    ),
    { minLength: n, maxLength: n },
  );
  const touch = fc.array(
    fc.record({ i: fc.nat(), j: fc.nat(), angle: fc.double({ min: 0, max: 6.3, noNaN: true }) }),
    { maxLength: 3 },
  );
  return fc.record({
    x: column(-60, 60),
    y: column(-60, 60),
    radius: sizes,
    include: fc.array(fc.constantFrom(1, 1, 1, 0), { minLength: n, maxLength: n }),
    tol: fc.constantFrom(0, 1e-9, 0.05, 0.3),
    touch,
    nudge: fc.constantFrom(1 - 2 ** -52, 1, 1 + 2 ** -52),
  });
});

describe("the core's overlap check in WebAssembly", () => {
  it("finds the Python edition's pair in every shared case", () => {
    expect(CASES.length).toBeGreaterThanOrEqual(50);
    expect(CASES.filter((c) => c.pair !== null).length).toBeGreaterThanOrEqual(10);
    for (const c of CASES) expect(check(c)).toEqual(c.pair);
  });

  it("finds the first pair that every pair's comparison finds", () => {
    fc.assert(
      fc.property(atoms, ({ touch, nudge, ...c }) => {
        const n = c.x.length;
        for (const { i, j, angle } of n >= 2 ? touch : []) {
          const [a, b] = [i % n, j % n];
          if (a === b) continue;
          const reach = (c.radius[a] + c.radius[b]) * (1 - c.tol) * nudge;
          c.x[b] = c.x[a] + reach * Math.cos(angle);
          c.y[b] = c.y[a] + reach * Math.sin(angle);
        }
        expect(check(c)).toEqual(everyPair(c));
      }),
      { numRuns: 300 },
    );
  });

  it("answers a heap of atoms on one spot at once", () => {
    const n = 100_000;
    const heap = {
      x: new Array(n).fill(0),
      y: new Array(n).fill(10),
      radius: new Array(n).fill(1),
    };
    const include = Array.from({ length: n }, (_, i) => (i < 3 ? 0 : 1));
    expect(check({ ...heap, include, tol: 0 })).toEqual([3, 4]);
  });
});
