/**
 * npm run bench [-- --quick] [-- --native] [-- --node-only | --browser-only]
 *
 * The web engine's figures (scripts/bench-core.ts), the WebAssembly core's: in Node, then in
 * headless Chromium (/usr/bin/chromium through playwright-core, a fresh profile, the page
 * served with cross-origin isolation so performance.now() is fine-grained). Rates are per
 * second of CPU time in both (the machine is shared), frame times by the wall clock.
 * --native also measures the same C built natively, the Python package's engine "fast", in
 * this session (the project's .venv, or EVAPCOOL_PYTHON) at 1 000, 10 000 and 100 000 atoms
 * for the ratios.
 */
import { spawnSync } from "node:child_process";
import { existsSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";
import { build } from "vite";
import {
  classicTimes,
  describe,
  prepare,
  runAll,
  warmUp,
  work,
  type BenchReport,
  type Runner,
} from "./bench-core";
import { wasmCore } from "./wasm-plugin.mjs";

const WEB = process.env.EVAPCOOL_WEB ?? fileURLToPath(new URL("..", import.meta.url));
const CHROMIUM = "/usr/bin/chromium";
const CHROMIUM_FLAGS = [
  "--headless",
  "--no-sandbox",
  "--disable-gpu",
  "--disable-quic",
  "--no-first-run",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
];
const NATIVE_SNIPPET = `
import json, statistics
from evapcool import Simulation
from evapcool.bench.fast import throughput
Simulation(n_atoms=50, radius=3.0, seed=0, engine="fast", escape="knife").advance(2.0)
runs = {n: [] for n in SIZES}
for _ in range(REPEATS):
    for n in SIZES:
        runs[n].append(throughput(n, max(2, FRAMES * 10_000 // n))["coll_per_s"])
print(json.dumps([statistics.median(runs[n]) for n in SIZES]))
`;
/** The native core's sizes: the scaling table's. */
const NATIVE_SIZES = [1_000, 10_000, 100_000];

/** Node: rates per second of this process's CPU time, frame times by the wall clock. */
function nodeRunner(): Runner {
  const cpu = () => {
    const u = process.cpuUsage();
    return (u.user + u.system) / 1000;
  };
  return {
    clock: `Node ${process.version}; rates per second of process CPU time, frames by the wall clock`,
    warmUp: async () => warmUp(),
    throughput: async (n, frames) => {
      const sim = prepare(n);
      const t0 = cpu();
      const r = work(sim, frames);
      return { ...r, ms: cpu() - t0 };
    },
    classicTimes: async (frames) => classicTimes(frames, () => performance.now()),
  };
}

type BenchGlobal = { EvapcoolBench: typeof import("./bench-core"); benchSim?: unknown };

/**
 * Headless Chromium: the engine bundled into a page; each measurement driven from here and
 * timed by the page's main-thread CPU time (DevTools protocol, Performance.getMetrics'
 * ThreadTime), so a busy machine does not count; frame times by performance.now().
 */
async function browserReport(quick: boolean): Promise<{ report: BenchReport; version: string }> {
  // A module (the core's bytes are unpacked by a top-level await) that hands bench-core's
  // functions to the page as globalThis.EvapcoolBench.
  const entry = "\0evapcool-bench";
  const out = await build({
    configFile: false,
    logLevel: "error",
    root: WEB,
    plugins: [
      wasmCore(),
      {
        name: "evapcool-bench-entry",
        resolveId: (id) => (id === entry ? entry : null),
        load: (id) =>
          id === entry
            ? `import * as bench from ${JSON.stringify(resolve(WEB, "scripts/bench-core.ts"))};\n` +
              "globalThis.EvapcoolBench = bench;"
            : null,
      },
    ],
    build: {
      write: false,
      minify: false,
      rollupOptions: { input: entry, output: { format: "es" } },
    },
  });
  const result = Array.isArray(out) ? out[0] : out;
  const code = (result as { output: { code?: string }[] }).output[0].code ?? "";
  const profile = mkdtempSync(join(tmpdir(), "evapcool-bench-"));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    args: CHROMIUM_FLAGS,
  });
  try {
    const page = await context.newPage();
    const url = "http://localhost:9/bench.html"; // localhost: a secure context, never fetched
    await page.route(url, (route) =>
      route.fulfill({
        contentType: "text/html",
        headers: {
          "Cross-Origin-Opener-Policy": "same-origin",
          "Cross-Origin-Embedder-Policy": "require-corp",
        },
        body: "<!doctype html><title>evapcool bench</title><body></body>",
      }),
    );
    await page.goto(url);
    await page.addScriptTag({ content: code, type: "module" });
    await page.waitForFunction(() => "EvapcoolBench" in globalThis);
    const cdp = await context.newCDPSession(page);
    await cdp.send("Performance.enable");
    const threadMs = async (): Promise<number> => {
      const { metrics } = await cdp.send("Performance.getMetrics");
      return 1000 * (metrics.find((m) => m.name === "ThreadTime")?.value ?? NaN);
    };
    const runner: Runner = {
      clock:
        "headless Chromium; rates per second of the page's main-thread CPU time " +
        "(DevTools ThreadTime), frames by performance.now() (cross-origin isolated)",
      warmUp: () =>
        page.evaluate(() => (globalThis as unknown as BenchGlobal).EvapcoolBench.warmUp()),
      throughput: async (n, frames) => {
        await page.evaluate((n) => {
          const g = globalThis as unknown as BenchGlobal;
          g.benchSim = g.EvapcoolBench.prepare(n);
        }, n);
        const t0 = await threadMs();
        const r = await page.evaluate((frames) => {
          const g = globalThis as unknown as BenchGlobal;
          return g.EvapcoolBench.work(g.benchSim as never, frames);
        }, frames);
        const ms = (await threadMs()) - t0;
        return { ...r, ms };
      },
      classicTimes: (frames) =>
        page.evaluate((frames) => {
          const bench = (globalThis as unknown as BenchGlobal).EvapcoolBench;
          return bench.classicTimes(frames, () => performance.now());
        }, frames),
    };
    const report = await runAll(runner, quick);
    return { report, version: context.browser()?.version() ?? "?" };
  } finally {
    await context.close();
    rmSync(profile, { recursive: true, force: true });
  }
}

/** The native core's collisions/s at NATIVE_SIZES (process CPU time; medians), or null. */
function nativeCollisionsPerS(frames: number, repeats: number): number[] | null {
  const python =
    process.env.EVAPCOOL_PYTHON ??
    [resolve(WEB, "../.venv/bin/python"), "python3"].find((p) => p === "python3" || existsSync(p))!;
  const code = NATIVE_SNIPPET.replace("FRAMES", String(frames))
    .replace("REPEATS", String(repeats))
    .replaceAll("SIZES", JSON.stringify(NATIVE_SIZES));
  const run = spawnSync(python, ["-c", code], { encoding: "utf8" });
  if (run.status !== 0) {
    console.error(`[native] could not run the native core with ${python}:\n${run.stderr.trim()}`);
    return null;
  }
  const rs = JSON.parse(run.stdout.trim().split("\n").pop()!) as number[];
  const text = rs.map(
    (r, k) => `${NATIVE_SIZES[k].toLocaleString("en")}: ${Math.round(r).toLocaleString("en")}`,
  );
  console.log(
    `[native] same session, ${python}, engine "fast": collisions/s (process CPU time, median of ${repeats}) at constant packing, atoms ${text.join(", ")}`,
  );
  return rs;
}

export async function main(args: string[]): Promise<number> {
  const known = new Set(["--quick", "--native", "--node-only", "--browser-only"]);
  for (const a of args)
    if (!known.has(a)) {
      console.error(`bench: unknown argument ${a} (known: ${[...known].join(", ")})`);
      return 2;
    }
  const quick = args.includes("--quick");
  // where, collisions/s at 10 000 atoms, the scaling table's medians
  const rates: [string, number, number[]][] = [];
  const note = (where: string, r: BenchReport) => {
    for (const line of describe(where, r)) console.log(line);
    const c = r.core;
    rates.push([`${where} wasm`, c.big.collPerS, c.scaling.map((x) => x.medianCollPerS)]);
  };
  if (!args.includes("--browser-only")) note("node", await runAll(nodeRunner(), quick));
  const native = args.includes("--native")
    ? nativeCollisionsPerS(quick ? 10 : 30, quick ? 1 : 3)
    : null;
  if (!args.includes("--node-only")) {
    if (!existsSync(CHROMIUM)) {
      console.error(
        `bench: ${CHROMIUM} not found: install Debian's chromium, or run with --node-only`,
      );
      return 1;
    }
    const { report, version } = await browserReport(quick);
    note(`chromium ${version}`, report);
  }
  if (native !== null)
    for (const [where, rate, table] of rates) {
      const each = table.map((x, k) => (x / native[k]).toFixed(2)).join(" / ");
      console.log(
        `  ${where} / native at 10 000 atoms: ${(rate / native[1]).toFixed(2)}; ` +
          `the table's 1 000 / 10 000 / 100 000 atoms: ${each}`,
      );
    }
  return 0;
}
