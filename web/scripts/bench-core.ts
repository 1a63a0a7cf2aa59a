/**
 * The web engine's benchmark figures, the same in Node and in a browser page (issues 11, 32):
 * the WebAssembly core's (core/*.c) physics time per frame at the classic start, collisions
 * per second at 10 000 atoms, and the scaling table at constant packing (1 000, 10 000 and
 * 100 000 atoms). The methods are those of `evapcool bench --only fast`
 * (src/evapcool/bench/fast.py): H = 450, a warm-up frame, radius = sqrt(10 000 / N),
 * interleaved repeats and medians.
 */
import { Simulation } from "../src/physics/index";

export interface Throughput {
  n: number;
  radius: number;
  frames: number;
  collisions: number;
  events: number;
  /** Collisions (pair + wall) per second of CPU time (wall time without a CPU clock). */
  collPerS: number;
  eventsPerS: number;
  msPerFrame: number;
}

/** The core's figures. */
export interface CoreReport {
  classic: { frames: number; medianMs: number; p95Ms: number; block: number };
  big: Throughput;
  scaling: { n: number; runs: Throughput[]; medianCollPerS: number; medianEventsPerS: number }[];
  maxOverMin: number;
}

export interface BenchReport {
  clock: string;
  core: CoreReport;
}

function median(xs: number[]): number {
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : 0.5 * (s[m - 1] + s[m]);
}

function quantile(xs: number[], q: number): number {
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.floor(q * s.length))];
}

/** A simulation of n atoms at constant packing (radius sqrt(10 000 / N)), H = 450, one frame in. */
export function prepare(n: number, seed = 1): Simulation {
  const sim = new Simulation({ nAtoms: n, radius: Math.sqrt(10_000 / n), seed, trapHeight: 450 });
  sim.advance(1);
  return sim;
}

/** Advance `frames` frames; the collisions and events (with crossings and stale pops) done. */
export function work(sim: Simulation, frames: number): { collisions: number; events: number } {
  const s0 = sim.engineStats;
  const c0 = sim.collisionCount;
  sim.advance(frames);
  const s1 = sim.engineStats;
  const collisions = sim.collisionCount - c0;
  return { collisions, events: collisions + (s1.crossings - s0.crossings) + (s1.stale - s0.stale) };
}

/** Physics time per frame of advance(1) at the classic start (49 atoms, R = 12, H = 450), ms. */
export function classicTimes(frames: number, now: () => number): number[] {
  const sim = new Simulation({ nAtoms: 49, radius: 12, seed: 1, trapHeight: 450 });
  sim.advance(1);
  const times: number[] = [];
  for (let f = 0; f < frames; f++) {
    const t = now();
    sim.advance(1);
    times.push(now() - t);
  }
  return times;
}

/** The warm-up: the core compiled by the WebAssembly tiers, every hot path run (the knife's too). */
export function warmUp(): void {
  new Simulation({ nAtoms: 400, radius: 3, seed: 0, escape: "knife" }).advance(20);
  work(prepare(10_000), 3);
}

/** Where the figures are measured: here (Node) or in a page (driven from Node). */
export interface Runner {
  clock: string;
  warmUp(): Promise<void>;
  /** Collisions, events and the milliseconds (CPU time where known) of `frames` frames. */
  throughput(
    n: number,
    frames: number,
  ): Promise<{ collisions: number; events: number; ms: number }>;
  classicTimes(frames: number): Promise<number[]>;
}

async function measure(runner: Runner, n: number, frames: number): Promise<Throughput> {
  const r = await runner.throughput(n, frames);
  return {
    n,
    radius: Math.sqrt(10_000 / n),
    frames,
    collisions: r.collisions,
    events: r.events,
    collPerS: r.collisions / (r.ms / 1000),
    eventsPerS: r.events / (r.ms / 1000),
    msPerFrame: r.ms / frames,
  };
}

/**
 * Every figure, the sizes interleaved (each repeat runs every size once); quick: fewer frames
 * and one run of the table.
 */
export async function runAll(runner: Runner, quick = false): Promise<BenchReport> {
  await runner.warmUp();
  const frames = quick ? 10 : 30;
  const sizes = [1_000, 10_000, 100_000];
  const repeats = quick ? 1 : 3;
  const big = await measure(runner, 10_000, frames);
  const runs = new Map<number, Throughput[]>(sizes.map((n) => [n, []]));
  for (let r = 0; r < repeats; r++)
    for (const n of sizes)
      runs.get(n)!.push(await measure(runner, n, Math.max(2, Math.floor((frames * 10_000) / n))));
  const nf = quick ? 300 : 900;
  const times: number[] = [];
  for (let r = 0; r < 3; r++) times.push(...(await runner.classicTimes(nf / 3)));
  const scaling = sizes.map((n) => {
    const rs = runs.get(n)!;
    return {
      n,
      runs: rs,
      medianCollPerS: median(rs.map((x) => x.collPerS)),
      medianEventsPerS: median(rs.map((x) => x.eventsPerS)),
    };
  });
  const rates = scaling.map((x) => x.medianCollPerS);
  const core: CoreReport = {
    classic: { frames: nf, medianMs: median(times), p95Ms: quantile(times, 0.95), block: 1 },
    big,
    scaling,
    maxOverMin: Math.max(...rates) / Math.min(...rates),
  };
  return { clock: runner.clock, core };
}

/** The report as text lines. */
export function describe(where: string, report: BenchReport): string[] {
  return [`[${where}] timing: ${report.clock}`, ...describeCore(report.core)];
}

function describeCore(r: CoreReport): string[] {
  const M = (x: number) => (x / 1e6).toFixed(3) + " M";
  const out = [
    ` the WebAssembly core (core/*.c):`,
    `  classic start (49 atoms, R = 12, H = 450): median ${r.classic.medianMs.toFixed(4)} ms, ` +
      `p95 ${r.classic.p95Ms.toFixed(4)} ms physics per frame over ${r.classic.frames} frames` +
      "",
    `  10 000 atoms, R = 1, H = 450: ${r.big.collisions.toLocaleString("en")} collisions in frames ` +
      `1-${r.big.frames + 1}: ${Math.round(r.big.collPerS).toLocaleString("en")} collisions/s, ` +
      `${Math.round(r.big.eventsPerS).toLocaleString("en")} events/s, ${r.big.msPerFrame.toFixed(1)} ms per frame`,
    `  scaling at constant packing (radius = sqrt(10000 / N)), median of ${r.scaling[0].runs.length} interleaved runs:`,
    `     atoms  radius frames   collisions/s     events/s  runs (collisions/s)`,
  ];
  for (const s of r.scaling) {
    const f = s.runs[0];
    out.push(
      `  ${f.n.toLocaleString("en").padStart(8)} ${f.radius.toFixed(3).padStart(7)} ${String(f.frames).padStart(6)} ` +
        `${Math.round(s.medianCollPerS).toLocaleString("en").padStart(14)} ` +
        `${Math.round(s.medianEventsPerS).toLocaleString("en").padStart(12)}  ` +
        s.runs.map((x) => M(x.collPerS)).join(", "),
    );
  }
  out.push(`  max / min collisions/s across the table (medians): ${r.maxOverMin.toFixed(2)}`);
  return out;
}
