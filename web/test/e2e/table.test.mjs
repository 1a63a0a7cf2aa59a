// The score table in headless Chromium (issue 27.8): whatever the name box accepts shows whole.
// A stored table with a 16-letter name with an umlaut, 16 CJK characters and a 12-digit score
// is opened by key T on a projector-size screen and on a phone; every word of every row is drawn
// whole (its text as stored, no clip) and ends before the next column begins.
import assert from "node:assert/strict";
import { existsSync } from "node:fs";
import { after, before, describe, test } from "node:test";
import { launch, openPage, PAGE } from "./browser.mjs";

const KEY = "evapcool.highscores.49-r12-seed-rim";
const ROWS = [
  { name: "ALEXANDRA MÜLLER", score: 999999999999, seconds: 5999.9, date: "2026-11-25 08:00:00" },
  {
    name: "量子気体の蒸発冷却実験第一番目で",
    score: 31,
    seconds: 41.5,
    date: "2026-11-24 10:11:12",
  },
  { name: "WWWWWWWWWWWWWWWW", score: 30, seconds: 61.2, date: "2026-11-23 09:00:00" },
];

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

describe("the score table shows every accepted name whole", () => {
  for (const viewport of [
    { width: 1920, height: 1080 },
    { width: 390, height: 844 },
  ])
    test(`${viewport.width} x ${viewport.height}`, async () => {
      const { page, log } = await openPage(browser, { viewport, query: "?seed=1" });
      await page.evaluate(
        ([k, rows]) => localStorage.setItem(k, JSON.stringify({ entries: rows })),
        [KEY, ROWS],
      );
      await page.reload();
      await page.waitForFunction(() => window.evapcool !== undefined);
      await page.keyboard.press("t");
      await page.waitForFunction(() => window.evapcool.app.panels.tableCells.length > 0);
      const cells = await page.evaluate(() => window.evapcool.app.panels.tableCells);
      assert.equal(cells.length, 5 * ROWS.length);
      // The stored order is best first: the 12-digit score, then 31, then 30.
      const names = [1, 6, 11].map((k) => cells[k].text);
      assert.deepEqual(
        names,
        ROWS.map((r) => r.name),
      );
      assert.equal(cells[2].text, "999,999,999,999"); // grouped as English writes numbers
      for (let row = 0; row < ROWS.length; row++) {
        const line = cells.slice(5 * row, 5 * row + 5);
        for (let c = 0; c + 1 < line.length; c++)
          assert.ok(
            line[c].rect.x + line[c].rect.w <= line[c + 1].rect.x,
            `row ${row}: "${line[c].text}" runs into "${line[c + 1].text}"`,
          );
        // Every row's columns start where the headers' do: one column each.
        assert.deepEqual(
          line.map((cell) => cell.rect.x),
          cells.slice(0, 5).map((cell) => cell.rect.x),
        );
      }
      const s = await page.evaluate(() => window.evapcool.state());
      assert.deepEqual(
        s.table.map((e) => e.name),
        ROWS.map((r) => r.name),
      );
      assert.deepEqual(log.errors, []);
      await page.close();
    });
});
