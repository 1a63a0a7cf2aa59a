/**
 * A real `evapcool class` for the Chromium tests of the class pages: started on a free port
 * of 127.0.0.1 with a fresh data file, answered once its link is printed and it serves.
 */
import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { createServer } from "node:net";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { chromium } from "playwright-core";
import { CHROMIUM } from "./browser.mjs";

/** A TCP port of 127.0.0.1 free a moment ago. */
export async function freePort() {
  const s = createServer();
  await new Promise((ok) => s.listen(0, "127.0.0.1", ok));
  const { port } = s.address();
  await new Promise((ok) => s.close(ok));
  return port;
}

/**
 * Start the server with `python`: `args` after `class`, the token read from its output by
 * `token` (a pattern with one group), ready once `readyPath` answers 200. Returns its
 * process, base address, token, data folder and everything it printed so far.
 */
export async function startClassServer(python, { prefix, args = [], token, readyPath, tries }) {
  const dir = mkdtempSync(join(tmpdir(), prefix));
  const port = await freePort();
  const command = ["-m", "evapcool", "class", ...args, "--port", String(port)];
  const proc = spawn(python, [...command, "--data", join(dir, "c.sqlite")], {
    env: { ...process.env, LANG: "C.UTF-8", LANGUAGE: "en" },
    stdio: ["ignore", "pipe", "pipe"],
    detached: true, // its own process group: stopping it reaches its workers too
  });
  let out = "";
  proc.stdout.on("data", (d) => (out += d));
  proc.stderr.on("data", (d) => (out += d));
  const base = `http://127.0.0.1:${port}`;
  for (let k = 0; k < tries; k++) {
    const found = token.exec(out)?.[1];
    if (found) {
      try {
        if ((await fetch(base + readyPath)).ok)
          return { proc, base, token: found, dir, output: () => out };
      } catch {
        /* not listening yet */
      }
    }
    await new Promise((r) => setTimeout(r, 200));
  }
  proc.kill("SIGKILL");
  throw new Error(`the class server did not start: ${out}`);
}

/** Stop a server of startClassServer (its whole process group) and remove its data folder. */
export async function stopClassServer(server) {
  if (!server) return;
  server.proc.kill("SIGTERM");
  await new Promise((r) => setTimeout(r, 1500));
  try {
    process.kill(-server.proc.pid, "SIGKILL"); // anything of its group still there
  } catch {
    /* all gone */
  }
  rmSync(server.dir, { recursive: true, force: true });
}

/** POST `body` as JSON to the server with a bearer token; the answer's JSON (200 asserted). */
export async function postJson(server, path, token, body) {
  const r = await fetch(server.base + path, {
    method: "POST",
    headers: { Authorization: `Bearer ${token}`, "Content-Type": "application/json" },
    body: JSON.stringify(body),
  });
  assert.equal(r.status, 200, await r.clone().text());
  return r.json();
}

/** Play one game with a ramp down to `floor`; its state at the win (or after the budget). */
export async function play(page, floor) {
  await page.keyboard.press("r");
  let s = await page.evaluate(() => window.evapcool.state());
  for (let k = 0; k < 300 && s.wonAt === null; k++) {
    if (s.trapHeight > floor) await page.keyboard.press("ArrowDown");
    await page.evaluate(() => window.evapcool.runFrames(25));
    s = await page.evaluate(() => window.evapcool.state());
  }
  return s;
}

/** A function that has a page report its script and console errors into `errors`. */
export function watchErrors(errors) {
  return (page) => {
    page.on("pageerror", (e) => errors.push(e.message));
    page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
    return page;
  };
}

/** A department's new lecturer (Ada) and class (Optics), made by the administrator's calls. */
export async function departmentClass(server) {
  const lecturerToken = (
    await postJson(server, "/api/admin/lecturers", server.token, { name: "Ada" })
  ).token;
  const room = await postJson(server, "/api/classes", lecturerToken, { name: "Optics" });
  return { lecturerToken, room, base: `/c/${room.code}` };
}

/** A server on a fresh data file (a department's with `department`) and a headless
 * Chromium, for one test file's `before`; `closeServerAndBrowser` ends both in its `after`. */
export async function startServerAndBrowser(
  python,
  prefix,
  { department = false, tries = 150 } = {},
) {
  const how = department
    ? { args: ["--department"], token: /admin\?token=(\S+)/, readyPath: "/" }
    : { args: [], token: /token=(\S+)/, readyPath: "/api/leaderboard" };
  const server = await startClassServer(python, { prefix, tries, ...how });
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: ["--no-sandbox", "--disable-gpu"],
  });
  return { server, browser };
}

export async function closeServerAndBrowser({ server, browser }) {
  await browser?.close();
  await stopClassServer(server);
}
