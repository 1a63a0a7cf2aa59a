// The projector's side of `python scripts/bench_class.py --debrief` (issue 36): opens the
// projector (1920 x 1080, Chromium) at BASE with the projector's KEY while the challenge is
// open, prints "ready" once it shows the board, then waits for the debrief the close brings
// and prints the first draw's time (ms since the epoch, this machine's clock) as JSON.
//   node test/e2e/bench-debrief.mjs BASE KEY
import { chromium } from "playwright-core";
import { CHROMIUM } from "./browser.mjs";

const [base, key] = process.argv.slice(2);
const browser = await chromium.launch({ executablePath: CHROMIUM, args: ["--no-sandbox"] });
try {
  const page = await browser.newPage({ viewport: { width: 1920, height: 1080 } });
  await page.goto(`${base}/projector?key=${key}`);
  await page.waitForFunction(() => document.querySelectorAll("#board tr").length > 1);
  console.log("ready");
  await page.waitForFunction(() => document.getElementById("debrief")?.dataset.drawnAt, null, {
    timeout: 120_000,
    polling: "raf",
  });
  const got = await page.evaluate(() => {
    const root = document.getElementById("debrief");
    return {
      drawn_at: Number(root.dataset.drawnAt),
      curves: document.getElementById("debrief-paths").dataset.curves.split(",").length,
    };
  });
  console.log(JSON.stringify(got));
} finally {
  await browser.close();
}
