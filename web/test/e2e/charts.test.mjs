// The charts in headless Chromium (issue 27.7): as the trap is lowered step by step, the energy
// chart's cut line (and every bar and curve of both charts) stays inside the plot, and every
// word (legend, live readout) lies in the header above it: no word's box meets the plot, and
// no pixel of the cut line's red lies inside a word's box, checked on the canvas's own pixels.
// Frames are counted, never timed.
import assert from "node:assert/strict";
import { existsSync } from "node:fs";
import { after, before, describe, test } from "node:test";
import { launch, openPage, PAGE } from "./browser.mjs";

/** The cut line's red (205, 25, 25), also where anti-aliasing blends it into the tint. */
const REDDISH = { rMin: 140, gMax: 100, bMax: 100 };

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

const frames = (page, n) =>
  page.evaluate(
    (n) =>
      new Promise((ok) => {
        const next = (k) => (k === 0 ? ok() : requestAnimationFrame(() => next(k - 1)));
        next(n);
      }),
    n,
  );

/** The panel's plot and words, and how many cut-red pixels lie in the plot and in the words. */
function inspect(red) {
  // The page's own canvas is read back here (the test's, not the page's, readback).
  const app = window.evapcool.app;
  const l = app.layout;
  const dpr = app.screen.dpr;
  const ctx = document.getElementById("scene").getContext("2d");
  const count = (r) => {
    const x = Math.floor((l.offsetX + r.x * l.scale) * dpr);
    const y = Math.floor((l.offsetY + r.y * l.scale) * dpr);
    const w = Math.max(1, Math.ceil(r.w * l.scale * dpr));
    const h = Math.max(1, Math.ceil(r.h * l.scale * dpr));
    const px = ctx.getImageData(x, y, w, h).data;
    let n = 0;
    for (let k = 0; k < px.length; k += 4)
      if (px[k] >= red.rMin && px[k + 1] <= red.gMax && px[k + 2] <= red.bMax) n++;
    return n;
  };
  const out = {};
  for (const name of ["energy", "path"]) {
    const d = app.charts[name].drawn;
    if (!d) continue;
    out[name] = {
      plot: d.plot,
      words: d.words,
      redInPlot: count(d.plot),
      redInWords: d.words.map(count),
    };
  }
  return out;
}

const meets = (a, b) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;

describe("no line crosses a word in the charts", () => {
  for (const viewport of [
    { width: 1600, height: 900 },
    { width: 390, height: 844 },
  ])
    test(`the cut line and the legend as the trap falls (${viewport.width} x ${viewport.height})`, async () => {
      const { page, log } = await openPage(browser, { viewport, query: "?seed=1" });
      await page.keyboard.press("e");
      await page.keyboard.press("g");
      await page.keyboard.press("Space");
      let checked = 0;
      let heights = [];
      for (let step = 0; step < 16; step++) {
        for (let k = 0; k < 3; k++) await page.keyboard.press("ArrowDown");
        await frames(page, 4);
        const s = await page.evaluate(() => window.evapcool.state());
        heights.push(s.trapHeight);
        const seen = await page.evaluate(inspect, REDDISH);
        for (const [name, d] of Object.entries(seen)) {
          assert.ok(d.words.length >= 4, `${name}: the legend and the readout are drawn`);
          for (const w of d.words)
            assert.ok(!meets(w, d.plot), `${name}: a word at ${JSON.stringify(w)} meets the plot`);
          assert.deepEqual(
            d.redInWords,
            d.words.map(() => 0),
            `${name}: red inside a word at H = ${s.trapHeight}`,
          );
          checked++;
        }
        // The energy chart's cut line is drawn (so the pixel check sees red where it is).
        if (seen.energy) assert.ok(seen.energy.redInPlot > 0, `no cut line at H = ${s.trapHeight}`);
      }
      assert.ok(checked >= 20, `only ${checked} checks`);
      assert.ok(heights[0] > heights[heights.length - 1], `the trap fell: ${heights}`);
      // Chromium's hint about this test's own pixel readback is not the page's.
      assert.deepEqual(
        log.errors.filter((e) => !e.includes("willReadFrequently")),
        [],
      );
      await page.close();
    });
});
