// The engine: the one physics core (core/*.c at the top of the repository) compiled to
// WebAssembly and driven by src/physics/wasm.ts, Simulation's only engine. Every golden trace
// replayed through it, the same text as the Python engines wrote, bit for bit; and runs longer
// than the traces (renumbering, the knife, the win, 20 000 atoms) giving the very events, end
// state the retired TypeScript engine gave (test/cases/retired-engine.json), with sound cells.
import { createHash } from "node:crypto";
import { readdirSync, readFileSync } from "node:fs";
import { describe, expect, it } from "vitest";
import { Simulation } from "../src/physics/simulation";
import { readTrace, replayTrace, traceText } from "../src/physics/trace";
import { WasmEngine } from "../src/physics/wasm";

const DIR = new URL("./golden/", import.meta.url);
// Golden files of other kinds (starts, wins, messages) share the folder.
const FILES = readdirSync(DIR)
  .filter((f) => f.endsWith(".json"))
  .filter((f) => readFileSync(new URL(f, DIR), "utf8").slice(0, 200).includes('"evapcool-trace"'))
  .sort();

/** What the retired TypeScript engine gave on each long run (stats and sha256: its cells'
 * counters too, which the core's cells no longer share; events_sha256: events and end state). */
interface Retired {
  frames: number;
  events: number;
  pairs: number;
  walls: number;
  won: boolean;
  stats: Simulation["engineStats"];
  sha256: string;
  events_sha256: string;
}
type Compared = Pick<Retired, "frames" | "events" | "pairs" | "walls" | "won" | "events_sha256">;
const compared = (r: Retired): Compared => ({
  frames: 0,
  events: r.events,
  pairs: r.pairs,
  walls: r.walls,
  won: r.won,
  events_sha256: r.events_sha256,
});
const RETIRED = JSON.parse(
  readFileSync(new URL("./cases/retired-engine.json", import.meta.url), "utf8"),
).cases as Record<string, Retired>;

const engineOf = (sim: Simulation) => (sim as unknown as { engine: unknown }).engine;

describe("Simulation's engine", () => {
  it("is the WebAssembly core, for a start and for a state", () => {
    expect(engineOf(Simulation.classic(1))).toBeInstanceOf(WasmEngine);
    const golden = readTrace(readFileSync(new URL(FILES[0], DIR), "utf8"));
    expect(engineOf(Simulation.fromState(golden.start))).toBeInstanceOf(WasmEngine);
  });
});

describe("the WebAssembly core replays the golden traces", () => {
  it("finds them", () => expect(FILES.length).toBeGreaterThanOrEqual(14));
  for (const file of FILES)
    it(`${file}: the same text, bit for bit`, () => {
      const text = readFileSync(new URL(file, DIR), "utf8");
      expect(traceText(replayTrace(readTrace(text)))).toBe(text);
    });
});

describe("bad states", () => {
  const start = () =>
    JSON.parse(
      JSON.stringify(readTrace(readFileSync(new URL("classic-1.json", DIR), "utf8")).start),
    );
  const message = (state: unknown): string => {
    try {
      Simulation.fromState(state as Parameters<typeof Simulation.fromState>[0]);
    } catch (e) {
      expect(e).toBeInstanceOf(RangeError);
      return (e as Error).message;
    }
    throw new Error("no RangeError");
  };
  it("a wrong energy sum is refused, checked by the core's sum", () => {
    const s = start();
    const sum = s.energy_sum;
    s.energy_sum *= 1.5;
    expect(message(s)).toMatch(/^state\.energy_sum must be the trapped atoms' energy sum, /);
    expect(message(s)).toContain(`energy sum, ${sum} `); // the core sums the start's own
  });
  it("overlapping atoms are refused", () => {
    const s = start();
    s.atoms.x[1] = s.atoms.x[0];
    s.atoms.y[1] = s.atoms.y[0];
    expect(message(s)).toMatch(/state\.atoms/);
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

/** A run's counts and the digest of its events and end state as text; its cells sound. */
function outcome(sim: Simulation): Compared {
  expect(sim.engineStats.gridErrors).toBe(0);
  const lines: string[] = [];
  for (let k = 0; k < sim.eventCount; k++) lines.push(JSON.stringify(sim.eventAt(k)));
  lines.push(JSON.stringify(sim.toState()));
  return {
    frames: 0,
    events: sim.eventCount,
    pairs: sim.pairCollisionCount,
    walls: sim.wallCollisionCount,
    won: sim.won,
    events_sha256: createHash("sha256").update(lines.join("\n")).digest("hex"),
  };
}

const RUNS: [string, string, () => Simulation][] = [
  [
    "2000-renumbered",
    "2 000 atoms, renumbered many times",
    () => new Simulation({ nAtoms: 2000, radius: 2, seed: 3, trapHeight: 450, recordEvents: true }),
  ],
  [
    "400-knife",
    "400 atoms, the knife",
    () => new Simulation({ nAtoms: 400, radius: 3, seed: 5, escape: "knife", recordEvents: true }),
  ],
  [
    "20000",
    "20 000 atoms",
    () =>
      new Simulation({ nAtoms: 20_000, radius: 0.7, seed: 2, trapHeight: 450, recordEvents: true }),
  ],
  [
    "classic-win",
    "the classic start to the win",
    () => Simulation.classic(7, { recordEvents: true }),
  ],
];

describe("longer runs, as the retired TypeScript engine ran them", () => {
  for (const [key, name, make] of RUNS)
    it(`${name}: the same events and state`, () => {
      const want = RETIRED[key];
      const sim = make();
      lowering(sim, want.frames);
      expect(want.events).toBeGreaterThan(1000);
      expect(outcome(sim)).toEqual(compared(want));
    }, 60_000); // up to 20 000 atoms: seconds on a busy 2-core machine

  it("the classic start reaches the win within the run compared", () => {
    const sim = Simulation.classic(7);
    lowering(sim, RETIRED["classic-win"].frames);
    expect(sim.won).toBe(true);
  });

  it("engines side by side in one process keep their own state", () => {
    const want = RETIRED["400-knife"];
    const make = RUNS[1][2];
    const a = make();
    const b = make();
    const other = Simulation.classic(3, { escape: "knife" });
    const start = a.trapHeight;
    for (let f = 0; f < want.frames; f++)
      for (const sim of [a, other, b]) {
        sim.advance(1);
        sim.trapHeight = start * (1 - 0.8 * Math.min(1, f / 1000));
      }
    expect(outcome(a)).toEqual(compared(want));
    expect(outcome(b)).toEqual(compared(want));
  });
});
