// Runs a TypeScript script of web/scripts with Vite's module runner (Node 20 cannot strip
// types): node scripts/run.mjs scripts/NAME.ts ARGS... calls the script's main(ARGS).
import { runnerImport } from "vite";
import { resolve } from "node:path";

const [script, ...args] = process.argv.slice(2);
if (!script) {
  console.error("usage: node scripts/run.mjs scripts/NAME.ts [ARGS...]");
  process.exit(2);
}
const { module } = await runnerImport(resolve(script), { logLevel: "error", configFile: false });
process.exitCode = await module.main(args);
