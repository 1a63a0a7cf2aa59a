import {
  existsSync,
  mkdirSync,
  mkdtempSync,
  readdirSync,
  readFileSync,
  writeFileSync,
} from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, relative, resolve, sep } from "node:path";
import { expect, test } from "vitest";

const SRC = resolve(import.meta.dirname, "../../src");
/**
 * Each layer and the layers it may import: physics <- game <- view <- app, with runtime/ (the
 * physics worker, its protocol, the game the page mirrors) beside view: above the game, below
 * the app, and neither of the two imports the other. classroom/: the class server's pages,
 * above the app (nothing below imports them). Files beside the layers (limits, i18n) are
 * everyone's.
 */
const LAYERS: Record<string, string[]> = {
  physics: [],
  game: ["physics"],
  view: ["game", "physics"],
  runtime: ["game", "physics"],
  app: ["view", "runtime", "game", "physics"],
  classroom: ["app", "view", "runtime", "game", "physics"],
};

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
function violations(root: string, layers: Record<string, string[]>): string[] {
  const bad: string[] = [];
  for (const file of sources(root)) {
    const layer = file.split(sep)[0];
    const allowed = new Set([layer, ...(layers[layer] ?? Object.keys(layers))]);
    for (const spec of specifiers(readFileSync(join(root, file), "utf8"))) {
      if (!spec.startsWith(".")) continue; // a package, not a layer
      const target = relative(root, resolve(dirname(join(root, file)), spec));
      const other = target.split(sep)[0];
      if (other in layers && !allowed.has(other)) bad.push(`${file} imports ${target}`);
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
  expect(violations(root, LAYERS)).toEqual([`physics${sep}model.ts imports view${sep}draw`]);
  expect(physicsOpeners(root)).toEqual([`view${sep}draw.ts`]);
});

test("comments and one-way imports are not violations", () => {
  const root = tree({
    "physics/model.ts": '// import { draw } from "../view/draw";\n/* import("../view/x") */\n',
    "game/rules.ts": 'import { model } from "../physics/model";\nimport "pkg";\n',
  });
  expect(violations(root, LAYERS)).toEqual([]);
});

test("the checker sees the runtime and the view import each other", () => {
  const root = tree({
    "runtime/remote.ts": 'import type { Pen } from "../view/pen";\n',
    "view/pen.ts": 'import { remote } from "../runtime/remote";\n',
  });
  expect(violations(root, LAYERS).sort()).toEqual([
    `runtime${sep}remote.ts imports view${sep}pen`,
    `view${sep}pen.ts imports runtime${sep}remote`,
  ]);
});

test("web/src layers import one way: physics <- game <- view, runtime <- app", () => {
  expect(sources(SRC).filter((f) => f.startsWith(`runtime${sep}`)).length).toBeGreaterThan(2);
  expect(sources(SRC).length).toBeGreaterThan(20);
  expect(violations(SRC, LAYERS)).toEqual([]);
});

test("only game/engine.ts opens the physics to the game, view and app", () => {
  expect(physicsOpeners(SRC)).toEqual([join("game", "engine.ts")]);
});

/** The module graph under root: each file to the files it imports (any form, types too). */
function moduleGraph(root: string): Map<string, string[]> {
  const graph = new Map<string, string[]>();
  for (const file of sources(root)) {
    const targets: string[] = [];
    for (const spec of specifiers(readFileSync(join(root, file), "utf8"))) {
      if (!spec.startsWith(".")) continue;
      const base = resolve(dirname(join(root, file)), spec.split("?")[0]);
      const found = [`${base}.ts`, join(base, "index.ts")].find((f) => existsSync(f));
      if (found) targets.push(relative(root, found));
    }
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
  const [app, controls] = [join("app", "app.ts"), join("app", "controls.ts")];
  expect(cycle(moduleGraph(root))).toBe(`${app} -> ${controls} -> ${app}`);
});

test("the checker finds a cycle across folders and through an index", () => {
  const root = tree({
    "game/rules.ts": 'import type { Sim } from "./sim?raw";\n',
    "game/sim.ts": 'export type { Door } from "../physics";\n',
    "physics/index.ts": 'import type { Rules } from "../game/rules";\n',
  });
  const found = cycle(moduleGraph(root));
  expect(found).toBe(
    [join("game", "rules.ts"), join("game", "sim.ts"), join("physics", "index.ts")]
      .concat(join("game", "rules.ts"))
      .join(" -> "),
  );
});

test("no import cycle anywhere in web/src (type-only imports count)", () => {
  const graph = moduleGraph(SRC);
  expect(graph.size).toBeGreaterThan(60);
  expect(cycle(graph) ?? "none").toBe("none");
});

test("the page's rooms never import their owner: app.ts is imported by main and api only", () => {
  const graph = moduleGraph(SRC);
  const app = join("app", "app.ts");
  const owners = [...graph].filter(([, targets]) => targets.includes(app)).map(([f]) => f);
  expect(owners.sort()).toEqual([join("app", "api.ts"), join("app", "main.ts")]);
});

test("the game layer never branches on the engine's name (one engine: the core's frame)", () => {
  const branch = /\bengine\.name\b|\bname\s*[!=]==?\s*["'](?:fast|reference|wasm)["']/;
  const game = sources(SRC).filter((f) => f.startsWith(`game${sep}`));
  expect(game.length).toBeGreaterThan(5);
  expect(game.filter((f) => branch.test(readFileSync(join(SRC, f), "utf8")))).toEqual([]);
  expect(branch.test('if (this.sim.engine.name === "fast") step();')).toBe(true);
});
