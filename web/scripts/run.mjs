// Runs a TypeScript script of web/scripts (Node 20 cannot strip types): Vite bundles it for
// Node into node_modules/.cache/evapcool-scripts/ (packages stay external), then
// node scripts/run.mjs scripts/NAME.ts ARGS... calls the script's main(ARGS).
import { build } from "vite";
import { wasmCore } from "./wasm-plugin.mjs";
import { catalogs } from "./catalogs-plugin.mjs";
import { basename, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const [script, ...args] = process.argv.slice(2);
if (!script) {
  console.error("usage: node scripts/run.mjs scripts/NAME.ts [ARGS...]");
  process.exit(2);
}
const web = fileURLToPath(new URL("..", import.meta.url));
const outDir = resolve(web, "node_modules/.cache/evapcool-scripts");
const name = basename(script).replace(/\.ts$/, "");
// The build's own lines (the plugins' "inlined: ..." figures) are diagnostics: they go to
// stderr, so the script's stdout is what it prints and nothing else (a JSON trace, say).
const log = console.log;
console.log = console.error;
try {
  await build({
    configFile: false,
    logLevel: "error",
    root: web,
    plugins: [wasmCore(), catalogs()],
    build: {
      ssr: resolve(web, script),
      outDir,
      emptyOutDir: false,
      minify: false,
      target: "node20",
      rollupOptions: { output: { format: "es", entryFileNames: `${name}.mjs` } },
    },
  });
} finally {
  console.log = log;
}
process.env.EVAPCOOL_WEB = web; // the scripts' own folder, wherever the bundle runs
const module = await import(pathToFileURL(resolve(outDir, `${name}.mjs`)).href);
process.exitCode = await module.main(args);
