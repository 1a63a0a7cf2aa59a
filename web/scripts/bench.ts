/**
 * npm run bench [-- --quick] [-- --numba] [-- --node-only | --browser-only]
 *
 * The web engine's figures (scripts/bench-core.ts) in Node, then in headless Chromium
 * (/usr/bin/chromium through playwright-core, a fresh profile, the page served with
 * cross-origin isolation so performance.now() is fine-grained). --numba also measures the
 * Numba engine in this session (the project's .venv, or EVAPCOOL_PYTHON) for the ratio.
 */
import { spawnSync } from "node:child_process";
import { existsSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";
import { build } from "vite";
import { describe, runAll, type BenchReport, type Clock } from "./bench-core";

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
const NUMBA_SNIPPET = `
import json
from evapcool import Simulation
from evapcool.bench.fast import throughput
Simulation(n_atoms=50, radius=3.0, seed=0, engine="fast", escape="knife").advance(2.0)
print(json.dumps(throughput(10_000, FRAMES)))
`;

function nodeClock(): Clock {
  return {
    now: () => performance.now(),
    cpu: () => {
      const u = process.cpuUsage();
      return (u.user + u.system) / 1000;
    },
    name: `Node ${process.version}; rates per second of process CPU time, frames by the wall clock`,
  };
}

async function browserReport(quick: boolean): Promise<{ report: BenchReport; version: string }> {
  const out = await build({
    configFile: false,
    logLevel: "error",
    root: WEB,
    build: {
      write: false,
      minify: false,
      lib: {
        entry: resolve(WEB, "scripts/bench-core.ts"),
        name: "EvapcoolBench",
        formats: ["iife"],
        fileName: "bench",
      },
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
    await page.addScriptTag({ content: code });
    const isolated = await page.evaluate(
      () => (globalThis as { crossOriginIsolated?: boolean }).crossOriginIsolated === true,
    );
    const report = await page.evaluate(
      ({ quick, isolated }) => {
        const bench = (globalThis as unknown as { EvapcoolBench: { runAll: typeof runAll } })
          .EvapcoolBench;
        const clock = {
          now: () => performance.now(),
          name:
            "headless Chromium, wall clock (performance.now, " +
            (isolated ? "cross-origin isolated: 5 us steps)" : "coarse: 100 us steps)"),
        };
        return bench.runAll(clock, quick, isolated ? 1 : 10);
      },
      { quick, isolated },
    );
    return { report, version: context.browser()?.version() ?? "?" };
  } finally {
    await context.close();
    rmSync(profile, { recursive: true, force: true });
  }
}

function numbaCollisionsPerS(frames: number): number | null {
  const python =
    process.env.EVAPCOOL_PYTHON ??
    [resolve(WEB, "../.venv/bin/python"), "python3"].find((p) => p === "python3" || existsSync(p))!;
  const run = spawnSync(python, ["-c", NUMBA_SNIPPET.replace("FRAMES", String(frames))], {
    encoding: "utf8",
  });
  if (run.status !== 0) {
    console.error(`[numba] could not run the Numba engine with ${python}:\n${run.stderr.trim()}`);
    return null;
  }
  const r = JSON.parse(run.stdout.trim().split("\n").pop()!) as {
    coll_per_s: number;
    collisions: number;
  };
  console.log(
    `[numba] same session, ${python}: 10 000 atoms, R = 1, H = 450: ${Math.round(r.coll_per_s).toLocaleString("en")} collisions/s (process CPU time)`,
  );
  return r.coll_per_s;
}

export async function main(args: string[]): Promise<number> {
  const known = new Set(["--quick", "--numba", "--node-only", "--browser-only"]);
  for (const a of args)
    if (!known.has(a)) {
      console.error(`bench: unknown argument ${a} (known: ${[...known].join(", ")})`);
      return 2;
    }
  const quick = args.includes("--quick");
  const rates: [string, number][] = [];
  if (!args.includes("--browser-only")) {
    const r = runAll(nodeClock(), quick);
    for (const line of describe("node", r)) console.log(line);
    rates.push(["node", r.big.collPerS]);
  }
  const numba = args.includes("--numba") ? numbaCollisionsPerS(quick ? 10 : 30) : null;
  if (!args.includes("--node-only")) {
    if (!existsSync(CHROMIUM)) {
      console.error(
        `bench: ${CHROMIUM} not found: install Debian's chromium, or run with --node-only`,
      );
      return 1;
    }
    const { report, version } = await browserReport(quick);
    for (const line of describe(`chromium ${version}`, report)) console.log(line);
    rates.push(["chromium", report.big.collPerS]);
  }
  if (numba !== null)
    for (const [where, rate] of rates)
      console.log(
        `  ${where} / numba at 10 000 atoms: ${(rate / numba).toFixed(2)} (target >= 0.5)`,
      );
  return 0;
}
