// `npm run screenshots:class`: the classroom guide's pictures of a class competition into
// docs/ (the projector page during a round, a phone in class mode after a verified win),
// from a real `evapcool class` on 127.0.0.1 and the built page in headless Chromium.
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { chromium } from "playwright-core";
import { CHROMIUM } from "./browser.mjs";

const DOCS = resolve(import.meta.dirname, "../../../docs");
const PYTHON =
  process.env.EVAPCOOL_PYTHON ?? resolve(import.meta.dirname, "../../../.venv/bin/python");
const PORT = 8799;
const BASE = `http://127.0.0.1:${PORT}`;
const dir = mkdtempSync(join(tmpdir(), "evapcool-class-shots-"));
const server = spawn(
  PYTHON,
  ["-m", "evapcool", "class", "--port", String(PORT), "--data", join(dir, "c.sqlite")],
  { env: { ...process.env, LANGUAGE: "en" }, stdio: ["ignore", "pipe", "inherit"] },
);
let out = "";
server.stdout.on("data", (d) => (out += d));
const browser = await chromium.launch({ executablePath: CHROMIUM, args: ["--no-sandbox"] });
try {
  let token = null;
  for (let k = 0; k < 100 && !token; k++) {
    await new Promise((r) => setTimeout(r, 200));
    token = /token=(\S+)/.exec(out)?.[1] ?? null;
  }
  for (let k = 0; k < 50; k++) {
    try {
      if ((await fetch(`${BASE}/api/leaderboard`)).ok) break;
    } catch {
      await new Promise((r) => setTimeout(r, 200));
    }
  }
  await fetch(`${BASE}/api/challenge`, {
    method: "POST",
    headers: { authorization: `Bearer ${token}`, "content-type": "application/json" },
    body: JSON.stringify({ n_atoms: 49, radius: 12, escape: "rim", seed: 7, minutes: 20 }),
  });
  const projector = await browser.newPage({ viewport: { width: 1920, height: 1080 } });
  await projector.goto(`${BASE}/projector`);
  const names = ["Ada", "Bose", "Curie", "Dirac"];
  let phone = null;
  for (const [k, name] of names.entries()) {
    const context = await browser.newContext({
      viewport: { width: 390, height: 844 },
      deviceScaleFactor: 2,
      isMobile: true,
      hasTouch: true,
    });
    const page = await context.newPage();
    await page.goto(`${BASE}/`);
    await page.waitForFunction(() => window.evapcool !== undefined);
    await page.fill("#join input", name);
    await page.tap("#join button");
    await page.waitForFunction(() => window.evapcool.app.play.fixedSeed === 7);
    await page.keyboard.press("Space");
    let s = await page.evaluate(() => window.evapcool.state());
    for (let i = 0; i < 300 && s.wonAt === null; i++) {
      if (s.trapHeight > 80 + 20 * k) await page.keyboard.press("ArrowDown");
      await page.evaluate(() => window.evapcool.runFrames(25));
      s = await page.evaluate(() => window.evapcool.state());
    }
    await page.waitForFunction(() =>
      window.evapcool.stateNow().notices.some((n) => n.includes("verified")),
    );
    await page.evaluate(() => window.evapcool.runFrames(60));
    if (phone) await phone.context().close();
    phone = page;
  }
  await phone.screenshot({ path: `${DOCS}/class-phone.png` });
  await projector.waitForFunction(() => document.querySelectorAll("#board tr").length === 5);
  await projector.screenshot({ path: `${DOCS}/class-projector.png` });
  console.log(`wrote ${DOCS}/class-projector.png, class-phone.png`);
} finally {
  await browser.close();
  server.kill("SIGTERM");
  rmSync(dir, { recursive: true, force: true });
}
