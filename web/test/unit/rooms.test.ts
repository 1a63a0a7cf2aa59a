// The web physics pairs with the Python physics by name (issue 26), and its engine is the one
// core in C (issue 32): no TypeScript engine rooms remain, the core's rooms live in core/ at
// the top of the repository, and the interface wasm.ts calls the core through
// (core-exports.ts, generated from core/evapcool_core.h) is exactly what the core exports.
import { readdirSync, readFileSync } from "node:fs";
import { resolve } from "node:path";
import { expect, test } from "vitest";
import { coreBytes } from "../../src/physics/instance";

const WEB = resolve(import.meta.dirname, "../../src/physics");
const PY = resolve(import.meta.dirname, "../../../src/evapcool/physics");
const CORE = resolve(import.meta.dirname, "../../../core");

/** Web files with no Python twin of the same stem, and why. */
const NO_TWIN: Record<string, string> = {
  "index.ts": "the package's entry (Python's physics/__init__.py)",
  "constants.ts":
    "the applet's constants; Python keeps them in constants.py, world.py and limits.py",
  "wasm.ts": "the core's WebAssembly wrapper (Python's native one is physics/core.py)",
  "instance.ts":
    "the core's WebAssembly module and instances, and its engine-free calls (Python: core.py)",
  "wasm-core.d.ts": "the type of the core the build inlines (web/scripts/wasm-plugin.mjs)",
  "core-exports.ts": "the core's exports, generated from core/evapcool_core.h (Python's _core.pyi)",
  "snapshot.ts":
    "the atoms read out of the core's tables, summed as NumPy sums (Python reads World's arrays)",
};

/** The TypeScript engine's rooms, retired for the core's (issue 32). */
const RETIRED = ["tables", "calendar", "grid", "predict", "events", "driver", "engine", "kernels"];

function stems(dir: string, ext: string): Set<string> {
  return new Set(
    readdirSync(dir)
      .filter((f) => f.endsWith(ext) && !f.startsWith("_"))
      .map((f) => f.slice(0, -ext.length)),
  );
}

test("every web physics file has a Python twin of the same stem", () => {
  const python = stems(PY, ".py");
  const web = readdirSync(WEB).filter((f) => f.endsWith(".ts"));
  const orphans = web.filter((f) => !(f in NO_TWIN) && !python.has(f.slice(0, -3)));
  expect(orphans).toEqual([]);
  for (const file of Object.keys(NO_TWIN)) expect(web, `${file} is still there`).toContain(file);
});

test("the engine's rooms are C files of the core, none TypeScript", () => {
  const web = stems(WEB, ".ts");
  for (const room of RETIRED) expect(web.has(room), `${room}.ts in web/src/physics`).toBe(false);
  const core = readdirSync(CORE);
  for (const room of RETIRED.filter((r) => r !== "engine"))
    expect(core, `core/${room}.c`).toContain(`${room}.c`);
  expect(core).toContain("tables.h");
});

test("core-exports.ts declares exactly the entry points the compiled core exports", () => {
  const text = readFileSync(resolve(WEB, "core-exports.ts"), "utf8");
  const block = text.slice(
    text.indexOf("interface CoreExports"),
    text.indexOf("\n}\n", text.indexOf("interface CoreExports")),
  );
  const called = [...block.matchAll(/^\s+(core_\w+)\(/gm)].map((m) => m[1]).sort();
  const exported = WebAssembly.Module.exports(new WebAssembly.Module(coreBytes()))
    .filter((e) => e.kind === "function")
    .map((e) => e.name)
    .sort();
  expect(called.length).toBeGreaterThan(25);
  expect(called).toEqual(exported);
  // every entry point takes the engine's Core first, but the one that makes it, the
  // start's functions of no engine (core/start.c) and the overlap check (core/overlap.c)
  const noEngine = [
    "core_new",
    "core_load_cup",
    "core_cup_capacity",
    "core_power",
    "core_contraction_probe",
    "core_first_overlap",
  ];
  for (const m of block.matchAll(/^\s+(core_\w+)\(([^)]*)\)/gm))
    if (!noEngine.includes(m[1])) expect(m[2], m[1]).toMatch(/^\s*core: Core/);
});

test("no web physics file over 400 lines (issue 47's budget)", () => {
  const long = readdirSync(WEB)
    .filter((f) => f.endsWith(".ts"))
    .map((f) => [f, readFileSync(resolve(WEB, f), "utf8").split("\n").length - 1] as const)
    .filter(([, n]) => n > 400);
  expect(long).toEqual([]);
});
