// The tools that print JSON (issue 37): `npm run replay` and `node scripts/run.mjs` write
// the JSON they exist to print on stdout and nothing else (the build's figures and the
// verdict go to stderr), so a program can read their output as it is.
import assert from "node:assert/strict";
import { spawnSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { test } from "node:test";

const WEB = resolve(import.meta.dirname, "../..");
const run = (cmd, args) =>
  spawnSync(cmd, args, { cwd: WEB, encoding: "utf-8", maxBuffer: 64 << 20 });

test("node scripts/run.mjs scripts/replay.ts TRACE: stdout is the trace as JSON", () => {
  const out = run("node", ["scripts/run.mjs", "scripts/replay.ts", "test/golden/knife.json"]);
  assert.equal(out.status, 0, out.stderr);
  const doc = JSON.parse(out.stdout);
  assert.equal(doc.format, "evapcool-trace");
  assert.equal(doc.case, "knife");
  assert.match(out.stderr, /bit for bit/, "the verdict is on stderr");
});

test("npm run -s replay -- STATE --events N: stdout is a trace of N events as JSON", () => {
  const dir = mkdtempSync(join(tmpdir(), "evapcool-tools-"));
  try {
    const trace = JSON.parse(readFileSync(join(WEB, "test/golden/classic-1.json"), "utf-8"));
    const state = join(dir, "start.json");
    writeFileSync(state, JSON.stringify(trace.start));
    const out = run("npm", ["run", "-s", "replay", "--", state, "--events", "40"]);
    assert.equal(out.status, 0, out.stderr);
    const doc = JSON.parse(out.stdout);
    assert.equal(doc.format, "evapcool-trace");
    assert.equal(doc.events_requested, 40);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
