// The two engine cores: the WebAssembly core (web/wasm/, src/physics/wasm.ts; the page's and
// Simulation's default) and the TypeScript engine (src/physics/engine.ts). Every golden trace
// replayed through each, the same text as the Python engines wrote, bit for bit; and the two
// side by side on runs longer than the traces (renumbering, the knife, the win, 20 000 atoms).
import { readdirSync, readFileSync } from "node:fs";
import { afterEach, describe, expect, it } from "vitest";
import { Engine, type EngineAtoms, type EngineSetup } from "../src/physics/engine";
import { Simulation, setEngineCore, type EngineFactory } from "../src/physics/simulation";
import { readTrace, replayTrace, traceText } from "../src/physics/trace";
import { WasmEngine } from "../src/physics/wasm";

const DIR = new URL("./golden/", import.meta.url);
// Golden files of other kinds (starts, wins, messages) share the folder.
const FILES = readdirSync(DIR)
  .filter((f) => f.endsWith(".json"))
  .filter((f) => readFileSync(new URL(f, DIR), "utf8").slice(0, 200).includes('"evapcool-trace"'))
  .sort();

const CORES: [string, EngineFactory, Function][] = [
  ["wasm", (s: EngineSetup, a: EngineAtoms) => new WasmEngine(s, a), WasmEngine],
  ["ts", (s: EngineSetup, a: EngineAtoms) => new Engine(s, a), Engine],
];

afterEach(() => setEngineCore(null));

describe("Simulation's engine core", () => {
  it("is the WebAssembly core unless another is set", () => {
    const engineOf = (sim: Simulation) => (sim as unknown as { engine: unknown }).engine;
    expect(engineOf(Simulation.classic(1))).toBeInstanceOf(WasmEngine);
    setEngineCore(CORES[1][1]);
    expect(engineOf(Simulation.classic(1))).toBeInstanceOf(Engine);
    setEngineCore(null);
    expect(engineOf(Simulation.classic(1))).toBeInstanceOf(WasmEngine);
  });
});

for (const [name, core, kind] of CORES)
  describe(`the ${name} core replays the golden traces`, () => {
    for (const file of FILES)
      it(`${file}: the same text, bit for bit`, () => {
        setEngineCore(core);
        const text = readFileSync(new URL(file, DIR), "utf8");
        const golden = readTrace(text);
        const sim = Simulation.fromState(golden.start);
        expect((sim as unknown as { engine: unknown }).engine).toBeInstanceOf(kind);
        expect(traceText(replayTrace(golden))).toBe(text);
      });
  });

describe("bad states", () => {
  const start = () =>
    JSON.parse(
      JSON.stringify(readTrace(readFileSync(new URL("classic-1.json", DIR), "utf8")).start),
    );
  const message = (core: EngineFactory, state: unknown): string => {
    setEngineCore(core);
    try {
      Simulation.fromState(state as Parameters<typeof Simulation.fromState>[0]);
    } catch (e) {
      expect(e).toBeInstanceOf(RangeError);
      return (e as Error).message;
    }
    throw new Error("no RangeError");
  };
  it("the same RangeError on both cores: a wrong energy sum (checked by the core's sum)", () => {
    const s = start();
    s.energy_sum *= 1.5;
    const m = message(CORES[0][1], s);
    expect(m).toMatch(/state\.energy_sum/);
    expect(message(CORES[1][1], s)).toBe(m);
  });
  it("the same RangeError on both cores: overlapping atoms", () => {
    const s = start();
    s.atoms.x[1] = s.atoms.x[0];
    s.atoms.y[1] = s.atoms.y[0];
    const m = message(CORES[0][1], s);
    expect(m).toMatch(/state\.atoms/);
    expect(message(CORES[1][1], s)).toBe(m);
  });
});

/** Frames of a run with the rim lowered from H to H / 5 over its first 1 000 frames. */
function lowering(sim: Simulation, frames: number): void {
  const start = sim.trapHeight;
  for (let f = 0; f < frames; f++) {
    sim.advance(1);
    sim.trapHeight = start * (1 - 0.8 * Math.min(1, f / 1000));
  }
}

/** A run's events, end state and statistics as text, on the engine core given. */
function run(core: EngineFactory, make: () => Simulation, frames: number): string {
  setEngineCore(core);
  const sim = make();
  lowering(sim, frames);
  const lines: string[] = [];
  for (let k = 0; k < sim.eventCount; k++) lines.push(JSON.stringify(sim.eventAt(k)));
  lines.push(JSON.stringify(sim.toState()));
  lines.push(JSON.stringify(sim.engineStats));
  return lines.join("\n");
}

describe("the two cores side by side", () => {
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
      "20 000 atoms",
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
      const ts = run(CORES[1][1], make, frames);
      const wasm = run(CORES[0][1], make, frames);
      expect(wasm.length).toBeGreaterThan(1000);
      expect(wasm === ts).toBe(true);
    }, 60_000); // two full runs of up to 20 000 atoms: seconds on a busy 2-core machine

  it("the classic start reaches the win within the run compared", () => {
    const sim = Simulation.classic(7);
    lowering(sim, 1500);
    expect(sim.won).toBe(true);
  });
});
