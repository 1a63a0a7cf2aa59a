/**
 * The Python with evapcool that the browser tests drive (the class server, the desktop's
 * replays and screenshots), and the one way a browser test may skip.
 *
 * The Python is EVAPCOOL_PYTHON (scripts/test-all.sh sets it to the Python that runs it),
 * else the clone's `.venv`, else `python3` on the PATH (an active virtual environment's).
 * One that cannot import evapcool fails the test file that needs it, saying which it
 * tried: a browser test never skips for want of Python.
 */
import { spawnSync } from "node:child_process";
import { appendFileSync, existsSync } from "node:fs";
import { resolve } from "node:path";

const VENV = resolve(import.meta.dirname, "../../../.venv/bin/python");

/** Which Python to use, and where it came from. */
function candidate() {
  const given = process.env.EVAPCOOL_PYTHON;
  if (given) return { python: given, from: "EVAPCOOL_PYTHON" };
  if (existsSync(VENV)) return { python: VENV, from: "the clone's .venv" };
  return { python: "python3", from: "the PATH" };
}

/**
 * The Python with evapcool, or an Error naming the one tried and how to give another.
 * Checked once per test file (a second's start-up at most).
 */
export function pythonWithEvapcool() {
  const { python, from } = candidate();
  const run = spawnSync(python, ["-c", "import evapcool"], { encoding: "utf-8" });
  if (run.error || run.status !== 0) {
    const why = run.error ? run.error.message : run.stderr.trim().split("\n").pop();
    throw new Error(
      `no Python with evapcool: ${python} (from ${from}) ${why ? `failed: ${why}` : "failed"}; ` +
        "activate the environment where evapcool is installed, or set EVAPCOOL_PYTHON",
    );
  }
  return python;
}

/**
 * Skip for an optional part the README names (the proxies): returns the reason for
 * node:test's `skip`, and notes it in EVAPCOOL_SKIP_LOG so that scripts/test-all.sh says
 * in its last line what was skipped.
 */
export function optional(reason) {
  const log = process.env.EVAPCOOL_SKIP_LOG;
  if (log) appendFileSync(log, `${reason}\n`);
  return reason;
}
