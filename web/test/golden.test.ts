// Every golden trace of the Python engines (web/test/golden/, scripts/golden_traces.py)
// replayed through the web engine: the same events in the same order, every time and
// coordinate bit for bit, and the same text.
import { readdirSync, readFileSync } from "node:fs";
import { describe, expect, it } from "vitest";
import { numberText, readTrace, replayTrace, traceText, type Trace } from "../src/physics/trace";

const DIR = new URL("./golden/", import.meta.url);
// Golden files of other kinds (starts, wins, messages) share the folder.
const FILES = readdirSync(DIR)
  .filter((f) => f.endsWith(".json"))
  .filter((f) => readFileSync(new URL(f, DIR), "utf8").slice(0, 200).includes('"evapcool-trace"'))
  .sort();

/** The bits of a float as a hex string: equal bits, equal text (also -0 and 0 differ). */
function bits(x: number): string {
  const v = new DataView(new ArrayBuffer(8));
  v.setFloat64(0, x);
  return v.getBigUint64(0).toString(16);
}

function columnBits(state: Trace["end"], key: keyof Trace["end"]["atoms"]): string[] {
  return (state.atoms[key] as unknown[]).map((v) => (typeof v === "number" ? bits(v) : String(v)));
}

describe("golden traces", () => {
  it("cover the issue's cases", () => {
    const names = FILES.map((f) => f.replace(/\.json$/, ""));
    for (const c of ["classic-1", "classic-2", "classic-3", "two-atoms", "grazing", "mixed-200"])
      expect(names).toContain(c);
    for (const c of ["knife", "falling-height", "win-damping", "height-mid-frame"])
      expect(names).toContain(c);
    expect(names.length).toBeGreaterThanOrEqual(8);
  });

  for (const file of FILES) {
    it(`${file}: same events and end state, bit for bit`, () => {
      const text = readFileSync(new URL(file, DIR), "utf8");
      const golden = readTrace(text);
      expect(golden.events.length).toBeGreaterThanOrEqual(golden.events_requested);
      const mine = replayTrace(golden);
      expect(mine.events.length).toBe(golden.events.length);
      for (let k = 0; k < golden.events.length; k++) {
        const [kind, i, j, t] = golden.events[k];
        const [mk, mi, mj, mt] = mine.events[k];
        if (mk !== kind || mi !== i || mj !== j || bits(mt) !== bits(t))
          throw new Error(
            `event ${k}: expected ${kind} ${i} ${j} ${t}, got ${mk} ${mi} ${mj} ${mt}`,
          );
      }
      for (const key of ["x", "y", "vx", "vy", "t", "radius", "mass", "status"] as const)
        expect(columnBits(mine.end, key), `end state atoms.${key}`).toEqual(
          columnBits(golden.end, key),
        );
      for (const key of ["time", "energy_sum", "initial_temperature"] as const)
        expect(bits(mine.end[key]), `end state ${key}`).toBe(bits(golden.end[key]));
      expect(mine.end.won).toBe(golden.end.won);
      const s = mine.summary;
      const g = golden.summary;
      expect([s.n_trapped, s.n_escaped, s.won, s.pair_collisions, s.wall_collisions]).toEqual([
        g.n_trapped,
        g.n_escaped,
        g.won,
        g.pair_collisions,
        g.wall_collisions,
      ]);
      expect(bits(s.temperature)).toBe(bits(g.temperature));
      expect(bits(s.total_energy)).toBe(bits(g.total_energy));
      // Math.pow is not C's pow: Tc(N) is held to 1e-12 relative (docs/model.md).
      expect(Math.abs(s.critical_temperature - g.critical_temperature)).toBeLessThanOrEqual(
        1e-12 * Math.abs(g.critical_temperature),
      );
      expect(traceText(mine)).toBe(text);
    });
  }
});

describe("numberText", () => {
  it("writes every number of the golden traces as Python's %.17g did", () => {
    let n = 0;
    const wrong: string[] = [];
    for (const file of FILES) {
      const text = readFileSync(new URL(file, DIR), "utf8");
      const numbers = text.replace(/"[^"]*"/g, '""');
      for (const token of numbers.match(/-?\d[\d.]*(e[+-]\d+)?/g) ?? []) {
        if (numberText(Number(token)) !== token) wrong.push(token);
        n++;
      }
    }
    expect(wrong).toEqual([]);
    expect(n).toBeGreaterThan(50_000);
  });

  it("reads back to the same bits, rounds exact halves to even, keeps -0", () => {
    for (const x of [
      0.1,
      1 / 3,
      2 / 3,
      1e-5,
      1.5e-300,
      5e-324,
      1e17,
      1e16,
      123456.789,
      Math.PI * 1e20,
    ])
      expect(Number(numberText(x))).toBe(x);
    expect(numberText(-0)).toBe("-0");
    expect(numberText(400)).toBe("400");
    expect(numberText(1e17)).toBe("1e+17");
    expect(numberText(1e-5)).toBe("1.0000000000000001e-05");
    expect(numberText(0.0001)).toBe("0.0001");
    // m / 2^18 has 18 digits, the last a 5: a half, rounded to even as C does
    expect(numberText(26217 / 262144)).toBe("0.10000991821289062"); // 0.100009918212890625
    expect(numberText(26215 / 262144)).toBe("0.10000228881835938"); // 0.100002288818359375
    expect((26217 / 262144).toExponential(16)).toBe("1.0000991821289063e-1"); // what V8 does
  });
});
