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

/** Win with a scripted ramp (the page's own keys: Space, then ArrowDown every 25 frames);
 * the win's frame counted, the name box open. Returns the state then. */
export async function winGame(page) {
  await page.evaluate(() => localStorage.clear());
  await page.keyboard.press("Space");
  let s = await state(page);
  for (let k = 0; k < 200 && s.wonAt === null; k++) {
    if (s.trapHeight > 100) await page.keyboard.press("ArrowDown");
    await page.evaluate(() => window.evapcool.runFrames(25));
    s = await state(page);
  }
  if (s.nameBox !== true) throw new Error("the win did not open the name box");
  await page.evaluate(() => window.evapcool.runFrames(2));
  return state(page);
}
