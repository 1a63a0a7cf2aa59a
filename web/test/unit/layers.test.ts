import { readdirSync, readFileSync } from "node:fs";
import { join, resolve } from "node:path";
import { expect, test } from "vitest";

const SRC = resolve(import.meta.dirname, "../../src");
const ORDER = ["physics", "game", "view", "app"];

test("web/src layers import one way: physics <- game <- view <- app", () => {
  for (const layer of ORDER) {
    const allowed = new Set(ORDER.slice(0, ORDER.indexOf(layer) + 1));
    for (const file of readdirSync(join(SRC, layer), { recursive: true }) as string[]) {
      if (!file.endsWith(".ts")) continue;
      const text = readFileSync(join(SRC, layer, file), "utf8");
      for (const m of text.matchAll(/from\s+"\.\.\/(\w+)\//g)) {
        expect(allowed.has(m[1]), `${layer}/${file} imports ${m[1]}`).toBe(true);
      }
    }
  }
});

test("only game/engine.ts opens the physics to the game, view and app", () => {
  for (const layer of ["game", "view", "app"]) {
    for (const file of readdirSync(join(SRC, layer), { recursive: true }) as string[]) {
      const text = readFileSync(join(SRC, layer, file), "utf8");
      if (/from\s+"\.\.\/physics\//.test(text)) expect(`${layer}/${file}`).toBe("game/engine.ts");
    }
  }
});
