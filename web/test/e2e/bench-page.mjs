// `npm run bench:page`: the browser edition's figures in headless Chromium (medians):
// time to the first frame of the file, frame work (physics + drawing) for 49 atoms,
// thousands of atoms, and the page's size. Build first (npm run build).
import { statSync } from "node:fs";
import { launch, openPage, PAGE } from "./browser.mjs";

const seconds = Number(process.env.BENCH_SECONDS ?? 10);
const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
};

const browser = await launch();
try {
  const first = [];
  for (let k = 0; k < 7; k++) {
    const { page } = await openPage(browser, { query: `?seed=${k}` });
    await page.waitForFunction(
      () => performance.getEntriesByName("evapcool-first-frame").length > 0,
    );
    first.push(
      await page.evaluate(() => performance.getEntriesByName("evapcool-first-frame")[0].startTime),
    );
    await page.close();
  }
  console.log(`page size: ${statSync(PAGE).size} bytes`);
  console.log(
    `time to first frame (file://, 7 loads): median ${median(first).toFixed(0)} ms (${first.map((t) => t.toFixed(0)).join(", ")})`,
  );
  for (const [atoms, radius, scale] of [
    [49, 12, 1],
    [49, 12, 2],
    [5000, 1, 1],
    [10000, 1, 1],
  ]) {
    const { page, log } = await openPage(browser, {
      viewport: { width: 1280, height: 720 },
      scale,
      query: `?atoms=${atoms}&radius=${radius}&seed=1`,
    });
    await page.keyboard.press("Space");
    await page.waitForTimeout(500);
    await page.evaluate(() => window.evapcool.resetStats());
    await page.waitForTimeout(seconds * 1000);
    const st = await page.evaluate(() => window.evapcool.frameStats(100000));
    const s = await page.evaluate(() => window.evapcool.state());
    console.log(
      `${atoms} atoms (radius ${radius}), 1280 x 720 at ${scale}x, ${seconds} s: frame work median ${st.medianMs.toFixed(2)} ms, ` +
        `p95 ${st.p95Ms.toFixed(2)} ms, ${st.fps.toFixed(1)} frames/s shown, ` +
        `play ${(s.time / 30).toFixed(1)} s of ${seconds + 0.5} s, ${s.nTrapped} trapped` +
        (log.errors.length ? `, errors: ${log.errors.join("; ")}` : ""),
    );
    await page.close();
  }
} finally {
  await browser.close();
}
