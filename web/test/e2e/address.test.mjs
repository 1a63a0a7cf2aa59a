// The page's address options as a person types them (issues 25.6, 27.10): every bad option
// named with what was typed (shortened), hex and repeats refused, no internal names, and
// every notice shown, page by page, with the ones still to come counted.
import assert from "node:assert/strict";
import { existsSync } from "node:fs";
import { after, before, test } from "node:test";
import { launch, openPage, PAGE } from "./browser.mjs";

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

const notices = (page) => page.evaluate(async () => (await window.evapcool.state()).notices);

test("seven bad options: every one is shown, four at a time, the rest counted", async () => {
  const long = "y".repeat(3000);
  const query = `?radius=abc&atoms=0x20&seed=-1&speed=9&tc-law=box&escape=door&${long}=2`;
  const { page } = await openPage(browser, { viewport: { width: 1280, height: 720 }, query });
  const first = await notices(page);
  assert.equal(first.length, 5);
  assert.equal(first[4], "…and 3 more");
  assert.ok(first.some((n) => n.includes('(got "abc")')));
  assert.ok(first.some((n) => n.includes('"yyyyyyyyyyyyyyyyyyyy…" (3,000 characters)')));
  // The unknown option's notice lists the 13 known ones (link-options.json, issue 48).
  assert.ok(
    first.every((n) => n.length < 180),
    "every notice fits a few lines",
  );
  // The next page comes when the first has been read (8 s of the applet's clock).
  let second = first;
  for (let k = 0; k < 60 && second[0] === first[0]; k++) {
    await page.waitForTimeout(250);
    second = await notices(page);
  }
  assert.deepEqual(second, [
    'Address: escape must be one of rim, knife (got "door"); ignored.',
    'Address: seed must be a whole number from 0 to 9007199254740991 (got "-1"); ignored.',
    'Address: speed must be a number from 0.25 to 4 (got "9"); ignored.',
  ]);
  await page.close();
});

test("a count that does not fit names the option as typed, never nAtoms", async () => {
  const { page } = await openPage(browser, {
    viewport: { width: 1280, height: 720 },
    query: "?atoms=5000",
  });
  const [line] = await notices(page);
  assert.match(line, /^Address: atoms: 5000 atoms of radius 12 do not fit in the cup/);
  assert.ok(!line.includes("nAtoms"));
  await page.close();
});

test("hex, words, a 5 000-digit count and a repeated option are refused by name", async () => {
  const digits = "9".repeat(5000);
  const { page } = await openPage(browser, {
    viewport: { width: 1280, height: 720 },
    query: `?atoms=${digits}&radius=abc&seed=0x10&speed=2&speed=3`,
  });
  const all = await notices(page);
  assert.deepEqual(all, [
    "Address: speed is given 2 times; give it once. Ignored.",
    'Address: radius must be a number from 0.01 to 1000 px (got "abc"); ignored.',
    'Address: atoms must be a whole number from 1 to 100000 (got "99999999999999999999…" (5,000 characters)); ignored.',
    'Address: seed must be a whole number from 0 to 9007199254740991 (got "0x10"); ignored.',
  ]);
  const s = await page.evaluate(async () => await window.evapcool.state());
  assert.equal(s.nAtoms ?? s.nTrapped, 49);
  await page.close();
});
