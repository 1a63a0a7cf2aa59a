// A tall phone upright with the charts closed (issue 37): the height between the scene and
// the controls shows the atoms left and the temperature large, not an empty grey band. The
// share of the screen left empty is measured on a screenshot: the longest run of rows of
// one colour across the whole width (a third of the screen before this readout).
import assert from "node:assert/strict";
import { existsSync } from "node:fs";
import { after, before, test } from "node:test";
import { launch, openPage, PAGE } from "./browser.mjs";
import { decodePng, pixel } from "./png.mjs";

/** The longest empty band may take at most this share of the screen's height. */
const EMPTY_MAX = 0.12;

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

/** The longest run of rows that are one colour from edge to edge, as a share of the height. */
function emptyShare(img) {
  let run = 0;
  let longest = 0;
  for (let y = 0; y < img.height; y++) {
    const first = pixel(img, 0, y).join();
    let flat = true;
    for (let x = 1; x < img.width && flat; x++) flat = pixel(img, x, y).join() === first;
    run = flat ? run + 1 : 0;
    longest = Math.max(longest, run);
  }
  return longest / img.height;
}

test("390 x 844 upright: the atoms and temperature fill the band; no third left empty", async () => {
  const { page, log } = await openPage(browser, {
    viewport: { width: 390, height: 844 },
    touch: true,
    query: "?seed=1",
  });
  await page.evaluate(() => window.evapcool.runFrames(2));
  const s = await page.evaluate(() => {
    const app = window.evapcool.app;
    return {
      mode: app.layout.mode,
      charts: app.charts.shown,
      readout: app.layout.readout,
      countCss: app.readoutSize * app.layout.scale,
    };
  });
  assert.equal(s.mode, "tall");
  assert.deepEqual(s.charts, { energy: false, path: false });
  assert.ok(s.readout, "the tall layout has a readout");
  // The atom count at arm's length: text of 40 CSS px or more (the status line's is 13).
  assert.ok(s.countCss >= 40, `the count is drawn ${s.countCss.toFixed(1)} CSS px high`);
  const share = emptyShare(decodePng(await page.screenshot()));
  assert.ok(share < EMPTY_MAX, `an empty band of ${(100 * share).toFixed(1)} % of the screen`);
  assert.deepEqual(log.errors, []);
  await page.close();
});

test("with a chart open the charts take the height, and the readout gives way", async () => {
  const { page } = await openPage(browser, {
    viewport: { width: 390, height: 844 },
    touch: true,
    query: "?seed=1",
  });
  await page.keyboard.press("e");
  await page.evaluate(() => window.evapcool.runFrames(2));
  const s = await page.evaluate(() => ({
    readout: window.evapcool.app.layout.readout,
    energy: window.evapcool.app.layout.charts.energy ?? null,
    size: window.evapcool.app.readoutSize,
  }));
  assert.ok(s.energy, "the energy chart is shown");
  assert.equal(s.readout, null);
  assert.equal(s.size, 0);
  await page.close();
});
