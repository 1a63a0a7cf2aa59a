// The shared start generator in a real browser (issue 22.1): the page in headless Chromium,
// with and without its physics worker, starts the classic game from a seed with the atoms the
// Python edition places (web/test/golden/starts.json): the initial temperature, a sum over
// every atom's position and speed, is the same double, bit for bit.
import assert from "node:assert/strict";
import { existsSync, readFileSync } from "node:fs";
import { resolve } from "node:path";
import { after, before, describe, test } from "node:test";
import { launch, openPage, PAGE, PAGE_URL } from "./browser.mjs";

const STARTS = JSON.parse(
  readFileSync(resolve(import.meta.dirname, "../golden/starts.json"), "utf8"),
).cases.filter((c) => c.atoms === 49 && c.radius === 12);
const NO_WORKER = () => {
  delete window.Worker;
};

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

describe("the same start in the browser as on the desktop", () => {
  for (const [where, initScript] of [
    ["worker", undefined],
    ["page", NO_WORKER],
  ])
    test(`from each golden seed, in the ${where}`, async () => {
      assert.ok(STARTS.length >= 4);
      for (const c of STARTS) {
        const { page, log } = await openPage(browser, { query: `?seed=${c.seed}`, initScript });
        const s = await page.evaluate(() => window.evapcool.state());
        assert.equal(s.engine, where);
        assert.equal(s.nAtoms, 49);
        assert.equal(s.initialTemperature, c.initial_temperature, `seed ${c.seed}`);
        assert.equal(s.criticalTemperature, c.critical_temperature, `seed ${c.seed}`);
        assert.deepEqual(log.errors, []);
        await page.close();
      }
    });
});

describe("a browser that cannot compile the core", () => {
  test("says in one line what it lacks, and plays nothing", async () => {
    // As a browser without WebAssembly's SIMD (older than the page's baseline) answers.
    const page = await browser.context.newPage();
    await page.addInitScript(() => {
      WebAssembly.validate = () => false;
    });
    await page.goto(PAGE_URL);
    const fatal = page.locator("#fatal");
    await fatal.waitFor({ state: "visible" });
    const text = await fatal.textContent();
    assert.match(text, /^evapcool could not start: this browser cannot run the physics: /);
    assert.match(text, /DecompressionStream or WebAssembly's SIMD/);
    assert.equal(await page.evaluate(() => window.evapcool), undefined);
    await page.close();
  });
});
