// The same out-of-range states and parameters are refused by both editions in the same
// words (issue 25.1): web/test/cases/refusals.json holds the Python edition's refusal of
// each (scripts/refusals.py, checked by tests/web/test_refusals.py).
import { readFileSync } from "node:fs";
import { describe, expect, test } from "vitest";
import { Simulation } from "../src/physics/simulation";
import { CURVATURE, N_ATOMS, TRAP_HEIGHT, pyFloat, pyG } from "../src/limits";

interface Fixture {
  states: { case: string; state: unknown; message: string }[];
  parameters: { case: string; python: string; web: string; value: number; refusal: string }[];
}
const FIXTURE = JSON.parse(
  readFileSync(new URL("./cases/refusals.json", import.meta.url), "utf8"),
) as Fixture;

function refusal(make: () => unknown): string {
  try {
    make();
  } catch (e) {
    expect(e).toBeInstanceOf(RangeError);
    return (e as Error).message;
  }
  throw new Error("the web edition accepted a case the Python edition refuses");
}

describe("refusals on the WebAssembly core", () => {
  test.each(FIXTURE.states.map((c) => [c.case, c] as const))("state: %s", (_, c) => {
    expect(refusal(() => Simulation.fromState(c.state as never))).toBe(c.message);
  });
  test.each(FIXTURE.parameters.map((c) => [c.case, c] as const))("parameter: %s", (_, c) => {
    expect(refusal(() => new Simulation({ [c.web]: c.value }))).toBe(c.web + c.refusal);
  });
});

test("the fixture covers the states and the parameters", () => {
  expect(FIXTURE.states.length).toBeGreaterThanOrEqual(12);
  expect(FIXTURE.parameters.length).toBeGreaterThanOrEqual(9);
});

test("numbers print as Python prints them", () => {
  expect([1e-5, 120.5, 120, 1e16, 2.5e8, 0.00025].map(pyFloat)).toEqual([
    "1e-05",
    "120.5",
    "120.0",
    "1e+16",
    "250000000.0",
    "0.00025",
  ]);
  expect([1e8, 1e-5, 0.001, 4.785891234, 1000, 0, -101.25].map(pyG)).toEqual([
    "1e+08",
    "1e-05",
    "0.001",
    "4.78589",
    "1000",
    "0",
    "-101.25",
  ]);
  expect(CURVATURE.allowed()).toBe("a number from 1e-05 to 10 1/px");
  expect(N_ATOMS.allowed()).toBe("a whole number from 1 to 1000000");
  expect(TRAP_HEIGHT.allowed()).toBe("a number > 0 px");
});
