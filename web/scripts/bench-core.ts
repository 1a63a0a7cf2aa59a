/**
 * The web engine's benchmark figures, the same in Node and in a browser page (issue 11):
 * the classic start's physics time per frame, collisions per second at 10 000 atoms, and
 * the scaling table at constant packing. The methods are those of `evapcool bench --only
 * fast` (src/evapcool/bench/fast.py): H = 450, a warm-up frame, radius = sqrt(10 000 / N),
 * interleaved repeats and medians.
 */
import { Simulation } from "../src/physics/index";

/** Time sources, ms: wall clock, and the process's CPU time where there is one (Node). */
export interface Clock {
  now(): number;
  cpu?: () => number;
  /** What the clocks are, for the report. */
  name: string;
}

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

export interface BenchReport {
  clock: string;
  classic: { frames: number; medianMs: number; p95Ms: number; block: number };
  big: Throughput;
  scaling: { n: number; runs: Throughput[]; medianCollPerS: number; medianEventsPerS: number }[];
  maxOverMin: number;
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

/** Collisions and events per second over `frames` frames after a 1-frame warm-up. */
export function throughput(n: number, frames: number, clock: Clock, seed = 1): Throughput {
  const radius = Math.sqrt(10_000 / n);
  const sim = new Simulation({ nAtoms: n, radius, seed, trapHeight: 450 });
  sim.advance(1);
  const s0 = sim.engineStats;
  const c0 = sim.collisionCount;
  const read = clock.cpu ?? clock.now;
  const t0 = read();
  sim.advance(frames);
  const ms = read() - t0;
  const s1 = sim.engineStats;
  const collisions = sim.collisionCount - c0;
  const events = collisions + (s1.crossings - s0.crossings) + (s1.stale - s0.stale);
  return {
    n,
    radius,
    frames,
    collisions,
    events,
    collPerS: collisions / (ms / 1000),
    eventsPerS: events / (ms / 1000),
    msPerFrame: ms / frames,
  };
}

/**
 * The classic start (49 atoms, R = 12, H = 450): physics time per frame of advance(1),
 * median and 95th percentile. With a coarse clock, blocks of `block` frames are timed
 * and divided.
 */
export function classicFrame(frames: number, clock: Clock, block = 1): BenchReport["classic"] {
  const sim = new Simulation({ nAtoms: 49, radius: 12, seed: 1, trapHeight: 450 });
  sim.advance(1);
  const times: number[] = [];
  for (let f = 0; f < frames; f += block) {
    const t = clock.now();
    for (let k = 0; k < block; k++) sim.advance(1);
    times.push((clock.now() - t) / block);
  }
  return { frames, medianMs: median(times), p95Ms: quantile(times, 0.95), block };
}

/** Every figure; quick: fewer frames and one run of the table. */
export function runAll(clock: Clock, quick = false, block = 1): BenchReport {
  // Warm-up: the JIT compiles the hot paths (the knife's too).
  new Simulation({ nAtoms: 400, radius: 3, seed: 0, escape: "knife" }).advance(20);
  const frames = quick ? 10 : 30;
  const big = throughput(10_000, frames, clock);
  const sizes = [1_000, 10_000, 100_000];
  const repeats = quick ? 1 : 3;
  const runs = new Map<number, Throughput[]>(sizes.map((n) => [n, []]));
  for (let r = 0; r < repeats; r++) {
    for (const n of sizes) {
      const fr = Math.max(2, Math.floor((frames * 10_000) / n));
      runs.get(n)!.push(throughput(n, fr, clock));
    }
  }
  const scaling = sizes.map((n) => ({
    n,
    runs: runs.get(n)!,
    medianCollPerS: median(runs.get(n)!.map((r) => r.collPerS)),
    medianEventsPerS: median(runs.get(n)!.map((r) => r.eventsPerS)),
  }));
  const rates = scaling.map((s) => s.medianCollPerS);
  const classic = classicFrame(quick ? 300 : 900, clock, block);
  return {
    clock: clock.name,
    classic,
    big,
    scaling,
    maxOverMin: Math.max(...rates) / Math.min(...rates),
  };
}

/** The report as text lines. */
export function describe(where: string, r: BenchReport): string[] {
  const M = (x: number) => (x / 1e6).toFixed(3) + " M";
  const out = [
    `[${where}] timing: ${r.clock}`,
    `  classic start (49 atoms, R = 12, H = 450): median ${r.classic.medianMs.toFixed(4)} ms, ` +
      `p95 ${r.classic.p95Ms.toFixed(4)} ms physics per frame over ${r.classic.frames} frames` +
      (r.classic.block > 1 ? ` (timed in blocks of ${r.classic.block})` : ""),
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
