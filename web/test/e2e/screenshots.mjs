// `npm run screenshots`: the README's pictures of the browser edition into docs/ (the classic
// start, a win, a phone upright and on its side, the help on a 1080p projector), from the built
// page in headless Chromium. The same pictures every run (but for the condensate's glow).
import { resolve } from "node:path";
import { launch, openPage } from "./browser.mjs";

const DOCS = resolve(import.meta.dirname, "../../../docs");

/** Only `runFrames` plays from here: the page's own loop would add frames of wall clock
 * between the script's calls, as many as the machine's load allows, and the pictures would
 * differ from run to run. */
async function scripted(page) {
  await page.waitForFunction(() => window.evapcool.stateNow().engine === "worker");
  await page.evaluate(() => window.evapcool.app.loop.stop());
  await page.evaluate(() => window.evapcool.state()); // the worker has every input so far
}
const browser = await launch();
try {
  let { page } = await openPage(browser, {
    viewport: { width: 640, height: 672 },
    query: "?seed=1",
  });
  await page.screenshot({ path: `${DOCS}/web-start.png` });
  await scripted(page);
  // A ramp that wins: 5 px lower every 25 frames down to 100, then wait for the condensate.
  await page.keyboard.press("Space");
  for (let k = 0; k < 200; k++) {
    const s = await page.evaluate(() => window.evapcool.state());
    if (s.wonAt !== null) break; // the win counted (at the frame's end)
    if (s.trapHeight > 100) await page.keyboard.press("ArrowDown");
    await page.evaluate(() => window.evapcool.runFrames(25));
  }
  await page.keyboard.type("Marie");
  await page.evaluate(() => window.evapcool.runFrames(150));
  await page.screenshot({ path: `${DOCS}/web-win.png` });
  await page.close();
  ({ page } = await openPage(browser, {
    viewport: { width: 390, height: 844 },
    scale: 2,
    touch: true,
    query: "?seed=2",
  }));
  await scripted(page);
  await page.evaluate(() => {
    window.evapcool.app.game.setTrapHeight(250);
    return window.evapcool.runFrames(90); // awaited: the picture after all 90 frames
  });
  await page.screenshot({ path: `${DOCS}/web-phone.png` });
  await page.close();
  // Issue 27: the phone on its side (the upright slider, every control a button) and a
  // 1080p projector with the help over the whole screen.
  ({ page } = await openPage(browser, {
    viewport: { width: 844, height: 390 },
    scale: 2,
    touch: true,
    query: "?seed=2",
  }));
  await scripted(page);
  await page.evaluate(() => {
    window.evapcool.app.game.setTrapHeight(250);
    return window.evapcool.runFrames(90); // awaited: the picture after all 90 frames
  });
  await page.screenshot({ path: `${DOCS}/web-landscape.png` });
  await page.close();
  ({ page } = await openPage(browser, {
    viewport: { width: 1920, height: 1080 },
    query: "?seed=2",
  }));
  // The help before any play: after some, its last line is the display rate this machine
  // kept, which on a busy one says "too slow" (a picture of the machine, not of the page).
  await page.keyboard.press("h");
  await page.waitForTimeout(300);
  await page.screenshot({ path: `${DOCS}/web-projector-help.png` });
  await page.close();
} finally {
  await browser.close();
}
console.log(
  `wrote ${DOCS}/web-start.png, web-win.png, web-phone.png, web-landscape.png, web-projector-help.png`,
);
