/** Vitest runs the unit tests (Node); the browser tests under test/e2e run with node --test. */
import { defineConfig } from "vitest/config";
import { wasmCore } from "./scripts/wasm-plugin.mjs";
import { catalogs } from "./scripts/catalogs-plugin.mjs";

export default defineConfig({
  plugins: [wasmCore(), catalogs({ allKeys: true })],
  test: {
    include: ["test/**/*.test.ts"],
    exclude: ["test/e2e/**", "node_modules/**"],
  },
});
