// A class competition in real Chromium (issue 22): a real `evapcool class` server started
// on 127.0.0.1; six phones (touch, 390 x 844) open the students' link, join with a name and
// play scripted games in class mode; each win's code is replayed by the server, and the
// projector page, open the whole time, shows them live, best first.
import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { existsSync, mkdtempSync, rmSync } from "node:fs";
import { createServer } from "node:net";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { after, before, test } from "node:test";
import { chromium } from "playwright-core";
import { CHROMIUM } from "./browser.mjs";

const PYTHON =
  process.env.EVAPCOOL_PYTHON ?? resolve(import.meta.dirname, "../../../.venv/bin/python");
const SKIP = !existsSync(PYTHON) && "no Python with evapcool (set EVAPCOOL_PYTHON)";
const SEED = 77;

let server;
let browser;
let dir;

async function freePort() {
  const s = createServer();
  await new Promise((ok) => s.listen(0, "127.0.0.1", ok));
  const { port } = s.address();
  await new Promise((ok) => s.close(ok));
  return port;
}

/** `evapcool class` on a fresh data file; resolves with its base address and lecturer token. */
async function startServer() {
  dir = mkdtempSync(join(tmpdir(), "evapcool-class-"));
  const port = await freePort();
  const proc = spawn(
    PYTHON,
    ["-m", "evapcool", "class", "--port", String(port), "--data", join(dir, "c.sqlite")],
    {
      env: { ...process.env, LANG: "C.UTF-8", LANGUAGE: "en" },
      stdio: ["ignore", "pipe", "pipe"],
      detached: true, // its own process group: stopping it reaches its workers too
    },
  );
  let out = "";
  proc.stdout.on("data", (d) => (out += d));
  proc.stderr.on("data", (d) => (out += d));
  const base = `http://127.0.0.1:${port}`;
  for (let k = 0; k < 150; k++) {
    const token = /token=(\S+)/.exec(out)?.[1];
    if (token) {
      try {
        if ((await fetch(`${base}/api/leaderboard`)).ok) return { proc, base, token };
      } catch {
        /* not listening yet */
      }
    }
    await new Promise((r) => setTimeout(r, 200));
  }
  proc.kill("SIGKILL");
  throw new Error(`the class server did not start: ${out}`);
}

before(async () => {
  if (SKIP) return;
  server = await startServer();
  browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: ["--no-sandbox", "--disable-gpu"],
  });
});

after(async () => {
  await browser?.close();
  if (server) {
    server.proc.kill("SIGTERM");
    await new Promise((r) => setTimeout(r, 1500));
    try {
      process.kill(-server.proc.pid, "SIGKILL"); // anything of its group still there
    } catch {
      /* all gone */
    }
  }
  if (dir) rmSync(dir, { recursive: true, force: true });
});

/** Join from a phone with this name, then win with a ramp to `floor` (scores differ). */
async function student(name, floor) {
  const context = await browser.newContext({
    viewport: { width: 390, height: 844 },
    deviceScaleFactor: 3,
    isMobile: true,
    hasTouch: true,
  });
  const page = await context.newPage();
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  await page.goto(`${server.base}/`);
  await page.waitForFunction(() => window.evapcool !== undefined);
  await page.waitForSelector("#join input");
  await page.fill("#join input", name);
  await page.tap("#join button");
  await page.waitForFunction(() => document.getElementById("join") === null);
  const state = () => page.evaluate(() => window.evapcool.state());
  await page.waitForFunction(() => window.evapcool.app.play.fixedSeed !== null);
  let s = await state();
  assert.equal(await page.evaluate(() => window.evapcool.app.play.fixedSeed), SEED);
  for (let k = 0; k < 300 && s.wonAt === null; k++) {
    if (s.trapHeight > floor) await page.keyboard.press("ArrowDown");
    await page.evaluate(() => window.evapcool.runFrames(25));
    s = await state();
  }
  assert.equal(s.won, true, `${name} won`);
  await page.waitForFunction(
    () => window.evapcool.stateNow().notices.some((n) => n.includes("verified")),
    null,
    { timeout: 30_000 },
  );
  const said = (await state()).notices.join(" | ");
  assert.match(said, new RegExp(`verified, ${s.score} atoms, place \\d`));
  assert.deepEqual(errors, []);
  await context.close();
  return { name, score: s.score };
}

test("six phones join, play and are ranked live on the projector", { skip: SKIP }, async () => {
  const opened = await fetch(`${server.base}/api/challenge`, {
    method: "POST",
    headers: { authorization: `Bearer ${server.token}`, "content-type": "application/json" },
    body: JSON.stringify({ n_atoms: 49, radius: 12, escape: "rim", seed: SEED }),
  });
  assert.equal(opened.status, 200, await opened.text());
  const projector = await browser.newPage({ viewport: { width: 1920, height: 1080 } });
  await projector.goto(`${server.base}/projector`);
  await projector.waitForSelector("#qr svg");
  const results = [];
  // Two at a time: six phones in one test run, on two cores.
  const floors = [100, 140, 80, 120, 160, 90];
  for (let k = 0; k < 6; k += 2) {
    const pair = await Promise.all([
      student(`Student ${k + 1}`, floors[k]),
      student(`<b>Student ${k + 2}</b>`, floors[k + 1]),
    ]);
    results.push(...pair);
  }
  // The projector, never reloaded: every name, best score first.
  await projector.waitForFunction(() => document.querySelectorAll("#board tr").length === 7, null, {
    timeout: 20_000,
  });
  const rows = await projector.evaluate(() =>
    [...document.querySelectorAll("#board tr")].slice(1).map((tr) => {
      const cells = [...tr.querySelectorAll("td")].map((td) => td.textContent);
      return { name: cells[1], score: Number(cells[2]) };
    }),
  );
  const scores = rows.map((r) => r.score);
  assert.deepEqual(
    scores,
    [...scores].sort((a, b) => b - a),
  );
  assert.deepEqual(
    [...rows.map((r) => r.name)].sort(),
    results.map((r) => r.name).sort(),
    "every student, names as typed (markup shown as text)",
  );
  assert.equal(await projector.locator("#board b").count(), 0, "no name is markup");
  await projector.close();
});

test(
  "the lecturer hides a student and shows a replay on the keyed projector",
  { skip: SKIP },
  async () => {
    const errors = [];
    const watch = (page) => {
      page.on("pageerror", (e) => errors.push(e.message));
      page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
    };
    const lecturer = await browser.newPage();
    watch(lecturer);
    await lecturer.goto(`${server.base}/lecturer?token=${server.token}`);
    await lecturer.waitForFunction(() => document.querySelectorAll("#entries tr").length === 7);
    const link = await lecturer.getAttribute("#projector", "href");
    assert.match(link, /^\/projector\?key=[0-9a-f]{32}$/);
    const projector = await browser.newPage({ viewport: { width: 1920, height: 1080 } });
    watch(projector);
    await projector.goto(`${server.base}${link}`);
    await projector.waitForFunction(() => document.querySelectorAll("#board tr").length === 7);
    await lecturer.getByRole("button", { name: "Replay on the projector" }).first().click();
    await projector.waitForSelector("#replay:not([hidden])");
    const watchLink = await projector.getAttribute("#replay-link", "href");
    assert.match(watchLink, /^\/\?replay=EC1\./, "the keyed projector links the replay");
    assert.equal(await projector.textContent("#replay-code"), "", "no code on screen while open");
    await lecturer.getByRole("button", { name: "Hide student" }).first().click();
    await projector.waitForFunction(() => document.querySelectorAll("#board tr").length === 6);
    await lecturer.waitForSelector("#entries tr.hidden");
    assert.deepEqual(errors, [], "no script error, nothing the pages' policies blocked");
    await projector.close();
    await lecturer.close();
  },
);
