import { mkdirSync, mkdtempSync, readdirSync, readFileSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, relative, resolve, sep } from "node:path";
import { expect, test } from "vitest";

const SRC = resolve(import.meta.dirname, "../../src");
// classroom/: the class server's pages, above the app (nothing below imports them).
const ORDER = ["physics", "game", "view", "app", "classroom"];

// Every form a module names another in: static imports (type-only too), side-effect
// imports, re-exports (`export ... from`), dynamic `import()` and `typeof import()` types.
const FROM = /\b(?:import|export)\b[^;]*?\bfrom\s*["']([^"']+)["']/g;
const BARE = /\bimport\s*["']([^"']+)["']/g;
const DYNAMIC = /\bimport\s*\(\s*["']([^"']+)["']\s*\)/g;

/** The specifiers a TypeScript source imports, in any form (comments ignored). */
function specifiers(text: string): string[] {
  const code = text.replace(/\/\*[\s\S]*?\*\//g, "").replace(/(^|[^:])\/\/.*$/gm, "$1");
  return [FROM, BARE, DYNAMIC].flatMap((re) => [...code.matchAll(re)].map((m) => m[1]));
}

/** Every .ts file under root, as paths relative to it. */
function sources(root: string): string[] {
  return (readdirSync(root, { recursive: true }) as string[]).filter((f) => f.endsWith(".ts"));
}

/** "a/b.ts imports c/d" for each import that leaves a layer for one it may not use. */
function violations(root: string, order: string[]): string[] {
  const bad: string[] = [];
  for (const file of sources(root)) {
    const layer = file.split(sep)[0];
    const allowed = new Set(order.slice(0, order.indexOf(layer) + 1));
    for (const spec of specifiers(readFileSync(join(root, file), "utf8"))) {
      if (!spec.startsWith(".")) continue; // a package, not a layer
      const target = relative(root, resolve(dirname(join(root, file)), spec));
      const other = target.split(sep)[0];
      if (order.includes(other) && !allowed.has(other)) bad.push(`${file} imports ${target}`);
    }
  }
  return bad;
}

/** The files outside physics that import from it (any form). */
function physicsOpeners(root: string): string[] {
  return sources(root).filter((file) => {
    if (file.startsWith(`physics${sep}`)) return false;
    return specifiers(readFileSync(join(root, file), "utf8")).some((spec) => {
      const target = relative(root, resolve(dirname(join(root, file)), spec));
      return spec.startsWith(".") && target.split(sep)[0] === "physics";
    });
  });
}

function tree(files: Record<string, string>): string {
  const root = mkdtempSync(join(tmpdir(), "layers-"));
  for (const [name, text] of Object.entries(files)) {
    mkdirSync(dirname(join(root, name)), { recursive: true });
    writeFileSync(join(root, name), text);
  }
  return root;
}

const FORMS = [
  'import { draw } from "../view/draw";',
  'import type { Pen } from "../view/draw";',
  'import {\n  draw,\n  type Pen,\n} from "../view/draw";',
  'import "../view/draw";',
  'export { draw } from "../view/draw";',
  'export * from "../view/draw";',
  'export type { Pen } from "../view/draw";',
  'const m = await import("../view/draw");',
  'let p: typeof import("../view/draw").draw;',
  'import { x } from "./util/../../view/draw";',
];

test.each(FORMS)("the checker sees a wrong-way import written as: %s", (form) => {
  const root = tree({
    "physics/model.ts": `${form}\n`,
    "physics/util/x.ts": "export const x = 1;\n",
    "view/draw.ts": 'import { x } from "../physics/util/x";\nexport const draw = x;\n',
  });
  expect(violations(root, ORDER)).toEqual([`physics${sep}model.ts imports view${sep}draw`]);
  expect(physicsOpeners(root)).toEqual([`view${sep}draw.ts`]);
});

test("comments and one-way imports are not violations", () => {
  const root = tree({
    "physics/model.ts": '// import { draw } from "../view/draw";\n/* import("../view/x") */\n',
    "game/rules.ts": 'import { model } from "../physics/model";\nimport "pkg";\n',
  });
  expect(violations(root, ORDER)).toEqual([]);
});

test("web/src layers import one way: physics <- game <- view <- app", () => {
  expect(sources(SRC).length).toBeGreaterThan(20);
  expect(violations(SRC, ORDER)).toEqual([]);
});

test("only game/engine.ts opens the physics to the game, view and app", () => {
  expect(physicsOpeners(SRC)).toEqual([join("game", "engine.ts")]);
});

/** The app layer's module graph: each file to the app files it imports (any form). */
function appGraph(root: string): Map<string, string[]> {
  const dir = join(root, "app");
  const graph = new Map<string, string[]>();
  for (const file of readdirSync(dir).filter((f) => f.endsWith(".ts"))) {
    const text = readFileSync(join(dir, file), "utf8");
    const targets = specifiers(text)
      .filter((spec) => spec.startsWith("./"))
      .map((spec) => `${spec.slice(2).split("?")[0]}.ts`);
    graph.set(file, targets);
  }
  return graph;
}

/** A cycle in the graph as "a -> b -> a", or null. */
function cycle(graph: Map<string, string[]>): string | null {
  const state = new Map<string, "open" | "done">();
  const path: string[] = [];
  const visit = (node: string): string | null => {
    if (state.get(node) === "done") return null;
    if (state.get(node) === "open") return [...path.slice(path.indexOf(node)), node].join(" -> ");
    state.set(node, "open");
    path.push(node);
    for (const next of graph.get(node) ?? []) {
      const found = visit(next);
      if (found) return found;
    }
    path.pop();
    state.set(node, "done");
    return null;
  };
  for (const node of graph.keys()) {
    const found = visit(node);
    if (found) return found;
  }
  return null;
}

test("the checker finds a room calling back into its owner (a cycle, type imports too)", () => {
  const root = tree({
    "app/app.ts": 'import { Controls } from "./controls";\n',
    "app/controls.ts": 'import type { App } from "./app";\n',
  });
  expect(cycle(appGraph(root))).toBe("app.ts -> controls.ts -> app.ts");
});

test("the page's rooms never import their owner: app.ts is imported by main and api only", () => {
  const graph = appGraph(SRC);
  expect(cycle(graph)).toBeNull();
  const owners = [...graph].filter(([, targets]) => targets.includes("app.ts")).map(([f]) => f);
  expect(owners.sort()).toEqual(["api.ts", "main.ts"]);
});
