// Real headless Chromium (Debian's /usr/bin/chromium) driven by playwright-core, and the
// built single page opened from file://. Shared by the end-to-end tests and the page bench.
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { pathToFileURL } from "node:url";
import { chromium } from "playwright-core";

export const CHROMIUM = process.env.CHROMIUM ?? "/usr/bin/chromium";
export const PAGE = resolve(import.meta.dirname, "../../dist/evapcool.html");
export const PAGE_URL = pathToFileURL(PAGE).href;
const FLAGS = [
  "--headless",
  "--no-sandbox",
  "--disable-gpu",
  "--disable-quic",
  "--no-first-run",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
];

/** A browser with a fresh user data dir; close() removes the dir too. */
export async function launch() {
  const dir = mkdtempSync(join(tmpdir(), "evapcool-chromium-"));
  const context = await chromium.launchPersistentContext(dir, {
    executablePath: CHROMIUM,
    headless: true,
    args: FLAGS,
    ignoreDefaultArgs: ["--enable-automation"],
    viewport: null,
  });
  return {
    context,
    async close() {
      await context.close();
      rmSync(dir, { recursive: true, force: true });
    },
  };
}

/**
 * A new page (own context options) that records console errors, page errors and every
 * request that is not the page file itself.
 */
export async function openPage(
  browser,
  {
    viewport = { width: 800, height: 700 },
    scale = 1,
    touch = false,
    query = "",
    reducedMotion,
    initScript,
  } = {},
) {
  const page = await browser.context.newPage();
  // Runs before the page's own script (e.g. to take Worker away).
  if (initScript) await page.addInitScript(initScript);
  await page.setViewportSize(viewport);
  const cdp = await browser.context.newCDPSession(page);
  await cdp.send("Emulation.setDeviceMetricsOverride", {
    width: viewport.width,
    height: viewport.height,
    deviceScaleFactor: scale,
    mobile: touch,
  });
  if (touch)
    await cdp.send("Emulation.setTouchEmulationEnabled", { enabled: true, maxTouchPoints: 5 });
  if (reducedMotion) await page.emulateMedia({ reducedMotion });
  const log = { errors: [], requests: [] };
  page.on("console", (m) => {
    if (m.type() === "error" || m.type() === "warning") log.errors.push(`${m.type()}: ${m.text()}`);
  });
  page.on("pageerror", (e) => log.errors.push(`pageerror: ${e.message}`));
  page.on("request", (r) => {
    // A blob: URL (the physics worker made from the page's own code) is not a request.
    if (r.url() !== PAGE_URL + query && !r.url().startsWith("blob:")) log.requests.push(r.url());
  });
  await page.goto(PAGE_URL + query);
  await page.waitForFunction(() => window.evapcool !== undefined);
  return { page, log, cdp };
}

/** The page's state (window.evapcool.state()). */
export const state = (page) => page.evaluate(() => window.evapcool.state());

/** Press Space, then lower the trap 5 px every 25 frames (real key presses) down to 100,
 * until the win's frame is counted (at most 5 000 frames). Returns the state then. */
export async function rampToWin(page) {
  await page.keyboard.press("Space");
  let s = await state(page);
  for (let k = 0; k < 200 && s.wonAt === null; k++) {
    if (s.trapHeight > 100) await page.keyboard.press("ArrowDown");
    await page.evaluate(() => window.evapcool.runFrames(25));
    s = await state(page);
  }
  return s;
}

/** Win with the scripted ramp on an empty table, so the name box opens; the state then. */
export async function winGame(page) {
  await page.evaluate(() => localStorage.clear());
  const s = await rampToWin(page);
  if (s.nameBox !== true) throw new Error("the win did not open the name box");
  await page.evaluate(() => window.evapcool.runFrames(2));
  return state(page);
}

/** Where the verify panel's Verify button is drawn, in the page's CSS pixels. */
export function verifyButtonAt(page) {
  return page.evaluate(() => {
    const app = window.evapcool.app;
    const t = app.targets.find((x) => x.action === "verifyrun");
    const z = app.overlayZoom();
    const l = app.layout;
    const x = z.x + (t.rect.x + t.rect.w / 2 - z.cx) * z.k;
    const y = z.y + (t.rect.y + t.rect.h / 2 - z.cy) * z.k;
    return [l.offsetX + x * l.scale, l.offsetY + y * l.scale];
  });
}
