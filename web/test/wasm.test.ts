// The WebAssembly engine core (web/wasm/, src/physics/wasm.ts): every golden trace replayed
// through it, events and end state bit for bit, the same text as the Python engines wrote;
// and beside the TypeScript engine on runs longer than the traces.
import { readdirSync, readFileSync } from "node:fs";
import { afterAll, beforeAll, describe, expect, it } from "vitest";
import { Simulation, setEngineCore } from "../src/physics/simulation";
import { readTrace, replayTrace, traceText } from "../src/physics/trace";
import { WasmEngine } from "../src/physics/wasm";

const DIR = new URL("./golden/", import.meta.url);
const FILES = readdirSync(DIR)
  .filter((f) => f.endsWith(".json"))
  .sort();

const wasm = (
  setup: ConstructorParameters<typeof WasmEngine>[0],
  atoms: ConstructorParameters<typeof WasmEngine>[1],
) => new WasmEngine(setup, atoms);

describe("the WebAssembly core replays the golden traces", () => {
  beforeAll(() => setEngineCore(wasm));
  afterAll(() => setEngineCore(null));

  it("is the engine in use", () => {
    const sim = Simulation.classic(1);
    expect((sim as unknown as { engine: unknown }).engine).toBeInstanceOf(WasmEngine);
  });

  for (const file of FILES)
    it(`${file}: the same text, bit for bit`, () => {
      const text = readFileSync(new URL(file, DIR), "utf8");
      const mine = replayTrace(readTrace(text));
      expect(traceText(mine)).toBe(text);
    });
});

/** A run's events and end state as text, on the engine core given. */
function run(core: typeof wasm | null, make: () => Simulation, frames: number): string {
  setEngineCore(core);
  try {
    const sim = make();
    const lines: string[] = [];
    for (let f = 0; f < frames; f++) {
      sim.advance(1);
      if (f === frames >> 1) sim.trapHeight = 0.6 * sim.trapHeight;
    }
    for (let k = 0; k < sim.eventCount; k++) lines.push(JSON.stringify(sim.eventAt(k)));
    lines.push(JSON.stringify(sim.toState()));
    lines.push(JSON.stringify(sim.engineStats));
    return lines.join("\n");
  } finally {
    setEngineCore(null);
  }
}

describe("the WebAssembly core beside the TypeScript engine", () => {
  const cases: [string, () => Simulation, number][] = [
    [
      "2 000 atoms, renumbered many times",
      () =>
        new Simulation({ nAtoms: 2000, radius: 2, seed: 3, trapHeight: 450, recordEvents: true }),
      60,
    ],
    [
      "400 atoms, the knife",
      () =>
        new Simulation({ nAtoms: 400, radius: 3, seed: 5, escape: "knife", recordEvents: true }),
      120,
    ],
    [
      "20 000 atoms, the next events' rows asked for ahead",
      () =>
        new Simulation({
          nAtoms: 20_000,
          radius: 0.7,
          seed: 2,
          trapHeight: 450,
          recordEvents: true,
        }),
      4,
    ],
    ["the classic start to the win", () => Simulation.classic(7, { recordEvents: true }), 1500],
  ];
  for (const [name, make, frames] of cases)
    it(`${name}: the same events, state and statistics`, () => {
      const ts = run(null, make, frames);
      const mine = run(wasm, make, frames);
      expect(mine.length).toBeGreaterThan(1000);
      expect(mine === ts).toBe(true);
    });
});
