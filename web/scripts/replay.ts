/**
 * npm run replay -- STATE.json --events N   the web engine's trace of any state (stdout)
 * npm run replay -- TRACE.json              replay a trace's start and steps: stdout gets
 *                                           this engine's trace, stderr whether it matches
 *
 * The text is the Python script's (scripts/golden_traces.py run STATE.json --events N), so
 * `diff` compares the two engines. Paths are relative to where npm was started.
 */
import { readFileSync } from "node:fs";
import { basename, resolve } from "node:path";
import { makeTrace, readTrace, replayTrace, traceText, TRACE_FORMAT } from "../src/physics/trace";

const USAGE = "usage: npm run replay -- STATE.json --events N | npm run replay -- TRACE.json";

export async function main(args: string[]): Promise<number> {
  let path: string | undefined;
  let events = 2000;
  for (let k = 0; k < args.length; k++) {
    const a = args[k];
    if (a === "--events") {
      const v = Number(args[++k]);
      if (!Number.isSafeInteger(v) || v < 1) {
        console.error(`replay: --events must be a whole number >= 1 (got ${args[k]})`);
        return 2;
      }
      events = v;
    } else if (a === "-h" || a === "--help") {
      console.log(USAGE);
      return 0;
    } else if (path === undefined && !a.startsWith("-")) {
      path = a;
    } else {
      console.error(`replay: unknown argument ${a}\n${USAGE}`);
      return 2;
    }
  }
  if (path === undefined) {
    console.error(USAGE);
    return 2;
  }
  const file = resolve(process.env.INIT_CWD ?? process.cwd(), path);
  let doc: unknown;
  try {
    doc = JSON.parse(readFileSync(file, "utf8"));
  } catch (e) {
    console.error(`replay: ${path}: ${(e as Error).message}`);
    return 2;
  }
  try {
    if ((doc as { format?: unknown }).format === TRACE_FORMAT) {
      const text = readFileSync(file, "utf8");
      const mine = traceText(replayTrace(readTrace(text)));
      process.stdout.write(mine);
      const same = mine === text;
      console.error(
        `replay: ${path}: ${same ? "the same events and end state, bit for bit" : "DIFFERS"}`,
      );
      return same ? 0 : 1;
    }
    const name = basename(file).replace(/\.json$/, "");
    process.stdout.write(
      traceText(makeTrace(name, `${events} events from ${basename(file)}`, doc as never, events)),
    );
    return 0;
  } catch (e) {
    if (e instanceof RangeError) {
      console.error(`replay: ${path}: ${e.message}`);
      return 2;
    }
    throw e;
  }
}
