// The page's inputs as the fuzz of issue 37 found them, each in real Chromium: the page
// answers within a second (a bounded wait, not a timing), says no in one short line, and
// keeps the other options of the address.
import assert from "node:assert/strict";
import { existsSync, readFileSync } from "node:fs";
import { resolve } from "node:path";
import { deflateSync, crc32 } from "node:zlib";
import { after, before, describe, test } from "node:test";
import { launch, openPage, PAGE, PAGE_URL, state, verifyButtonAt, winGame } from "./browser.mjs";

/** The page must answer within this (ms): a bounded wait, the test fails past it. */
const ANSWER_MS = 1000;
/** A refusal is one line: at most this many characters. */
const SHORT = 200;
const VERSION = JSON.parse(
  readFileSync(resolve(import.meta.dirname, "../../package.json"), "utf-8"),
).version;

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

/** A replay code of a JSON text (bytes), made as both editions make them. */
function codeOf(json) {
  const payload = deflateSync(Buffer.isBuffer(json) ? json : Buffer.from(json)).toString(
    "base64url",
  );
  return `EC1.${payload}.${crc32(payload).toString(16).padStart(8, "0")}`;
}

/** A recording's JSON: a game that does not win (its claim is what a replay gives). */
function recording({ atoms = 49, radius = 12, frames = 10, height = 400 } = {}) {
  return {
    settings: { n_atoms: atoms, radius, escape: "rim", tc_exponent: 2 / 3 },
    seed: 1,
    moves: [[height, frames]],
    won: false,
    score: 0,
    frames,
    edition: "web",
    version: VERSION,
    start_generator: 1,
    format: 1,
  };
}

/** Resolves to fn's value in the page, or rejects if the page takes longer than ANSWER_MS. */
async function answers(page, fn, arg) {
  let timer;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`no answer in ${ANSWER_MS} ms`)), ANSWER_MS);
  });
  try {
    return await Promise.race([page.evaluate(fn, arg), late]);
  } finally {
    clearTimeout(timer);
  }
}

/** Open the page with a query and wait (bounded) until a notice matches. */
async function openWith(query, pattern) {
  const page = await browser.context.newPage();
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  await page.setViewportSize({ width: 1280, height: 720 });
  await page.goto(PAGE_URL + query, { waitUntil: "domcontentloaded" });
  await page.waitForFunction(() => window.evapcool !== undefined, null, { timeout: 10_000 });
  const notices = await page.waitForFunction(
    (source) =>
      window.evapcool.stateNow().notices.filter((n) => new RegExp(source).test(n)).length > 0 &&
      window.evapcool.stateNow().notices,
    pattern.source,
    { timeout: ANSWER_MS },
  );
  return { page, errors, notices: await notices.jsonValue() };
}

describe("?replay= codes", () => {
  test("a 190 KB code unpacking to 140 MB: refused in one short line, the rest kept", async () => {
    const json = Buffer.concat([
      Buffer.from('{"format":1,"pad":"'),
      Buffer.alloc(140_000_000, 32),
      Buffer.from('"}'),
    ]);
    const bomb = codeOf(json);
    assert.ok(bomb.length > 150_000 && bomb.length < 200_000, `${bomb.length} characters`);
    const { page, errors, notices } = await openWith(
      `?atoms=30&seed=7&replay=${bomb}`,
      /Replay|replay/,
    );
    const line = notices.find((n) => /unpacks to more than/.test(n));
    assert.ok(line, notices.join(" | "));
    assert.ok(line.length < SHORT, line);
    const s = await answers(page, () => window.evapcool.stateNow());
    assert.equal(s.nAtoms, 30);
    assert.equal(await page.evaluate(() => window.evapcool.app.game.config.seed), 7);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test("a field of a million characters is quoted shortened", async () => {
    const doc = { ...recording(), version: "v".repeat(1_000_000) };
    const { page, errors, notices } = await openWith(
      `?speed=2&replay=${codeOf(JSON.stringify(doc))}`,
      /other version/,
    );
    const line = notices.find((n) => /other version/.test(n));
    assert.ok(line.length < SHORT, `${line.length} characters`);
    assert.equal((await state(page)).speed, 2);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test("a valid recording padded to 140 MB is refused, the same unpadded is watched", async () => {
    const text = JSON.stringify(recording());
    const padded = Buffer.concat([
      Buffer.from(text.slice(0, -1)),
      Buffer.alloc(140_000_000, 32),
      Buffer.from("}"),
    ]);
    const bad = await openWith(`?replay=${codeOf(padded)}`, /unpacks to more than/);
    assert.deepEqual(bad.errors, []);
    await bad.page.close();
    const good = await openWith(`?replay=${codeOf(text)}`, /^Watching a replay/);
    await good.page.close();
  });
});

describe("the verify panel", () => {
  /** Open the panel, paste text, press its Verify button as drawn. */
  async function verify(page, text) {
    await page.keyboard.press("v");
    await page.waitForSelector("#codes:not([hidden])");
    await page.evaluate((t) => {
      const area = document.getElementById("codes");
      area.value = t; // a paste of megabytes: typing it would take hours
      area.dispatchEvent(new Event("input"));
    }, text);
    const at = await verifyButtonAt(page);
    await page.mouse.click(at[0], at[1]);
  }

  test("a 36 000-frame game replays while the page answers; closing stops it", async () => {
    const code = codeOf(JSON.stringify(recording({ atoms: 400, radius: 3, frames: 36_000 })));
    const { page, log } = await openPage(browser, {
      viewport: { width: 1280, height: 720 },
      // Count the workers ended (closing the panel must end the one replaying).
      initScript: () => {
        window.__ended = 0;
        const end = Worker.prototype.terminate;
        Worker.prototype.terminate = function () {
          window.__ended += 1;
          return end.call(this);
        };
      },
    });
    await verify(page, code);
    await page.waitForFunction(() => window.evapcool.app.verifier.busy);
    for (let k = 0; k < 5; k++) {
      const busy = await answers(
        page,
        () =>
          new Promise((done) =>
            requestAnimationFrame(() => done(window.evapcool.app.verifier.busy)),
          ),
      );
      assert.equal(busy, true, "still replaying: the page drew a frame meanwhile");
    }
    await page.keyboard.press("Escape"); // leaves the paste box
    await page.keyboard.press("Escape"); // closes the panel
    await page.waitForFunction(() => window.evapcool.app.overlay === null);
    await page.evaluate(() => window.evapcool.runFrames(1)); // a frame drawn without the panel
    const after = await page.evaluate(() => ({
      busy: window.evapcool.app.verifier.busy,
      ended: window.__ended,
    }));
    assert.deepEqual(after, { busy: false, ended: 1 });
    await page.waitForTimeout(300);
    assert.deepEqual(await page.evaluate(() => window.evapcool.app.verifier.results), []);
    assert.deepEqual(log.errors, []);
    await page.close();
  });

  test("5 MB of pasted words: the first 100 are checked, and a notice says so", async () => {
    const words = Array.from({ length: 655_000 }, (_, k) => `w${k}`).join(" ");
    assert.ok(words.length > 4_000_000);
    const { page, log } = await openPage(browser, { viewport: { width: 1280, height: 720 } });
    await verify(page, words);
    await page.waitForFunction(
      () => {
        const v = window.evapcool.app.verifier;
        return !v.busy && v.results.length > 0;
      },
      null,
      { timeout: 10_000 },
    );
    const s = await state(page);
    assert.equal(await page.evaluate(() => window.evapcool.app.verifier.results.length), 100);
    assert.ok(s.notices.includes("Only the first 100 codes are checked."), s.notices.join(" | "));
    assert.deepEqual(log.errors, []);
    await page.close();
  });
});

describe("the address", () => {
  for (const law of ["toString", "constructor", "__proto__", "valueOf", "hasOwnProperty"])
    test(`?tc-law=${law} is refused by name; the other options stay`, async () => {
      const { page, errors, notices } = await openWith(`?atoms=30&tc-law=${law}&speed=2`, /tc-law/);
      assert.deepEqual(notices, [
        `Address: tc-law must be one of seed, cup (got "${law}"); ignored.`,
      ]);
      const s = await state(page);
      assert.equal(s.nAtoms, 30);
      assert.equal(s.speed, 2);
      assert.deepEqual(errors, []);
      await page.close();
    });

  test("?lang=de&lang=fr: refused like any repeated option; the page stays in English", async () => {
    const { page, notices } = await openWith("?lang=de&lang=fr&speed=2", /lang/);
    assert.deepEqual(notices, ["Address: lang is given 2 times; give it once. Ignored."]);
    const s = await state(page);
    assert.equal(s.locale, "en");
    assert.equal(s.speed, 2);
    await page.close();
  });

  test("101 unknown options: the first is shown first, the rest counted", async () => {
    const query = "?" + Array.from({ length: 101 }, (_, k) => `x${k}=1`).join("&");
    const { page, notices } = await openWith(query, /x0/);
    assert.match(notices[0], /unknown option "x0"/);
    assert.equal(notices.at(-1), "…and 97 more");
    await page.close();
  });
});

describe("stored scores", () => {
  const KEY = "evapcool.highscores.49-r12-seed-rim";
  const GOOD = { name: "Ada", score: 30, seconds: 61.5, date: "2026-01-02 10:00:00" };
  test("1e308 atoms, 1e308 seconds and the year 0 are set aside; the good row stays", async () => {
    const { page, log } = await openPage(browser, { viewport: { width: 1280, height: 720 } });
    const rows = [
      GOOD,
      { ...GOOD, name: "Big", score: 1e308 },
      { ...GOOD, name: "Slow", seconds: 1e308 },
      { ...GOOD, name: "Old", date: "0000-01-01 00:00:00" },
      { ...GOOD, name: "👨‍👩‍👧 Ann" },
    ];
    await page.evaluate(
      ([k, r]) => localStorage.setItem(k, JSON.stringify({ version: 1, entries: r })),
      [KEY, rows],
    );
    await page.reload();
    await page.waitForFunction(() => window.evapcool !== undefined);
    const s = await state(page);
    assert.deepEqual(
      s.table.map((e) => e.name),
      ["Ada", "👨‍👩‍👧 Ann"],
    );
    const line = s.notices.find((n) => n.includes("3 damaged rows"));
    console.log(s.notices);
    assert.ok(line && line.length < SHORT, s.notices.join(" | "));
    assert.deepEqual(log.errors, []);
    await page.close();
  });
});

describe("names", () => {
  test("typed in the name box: cut at 16 whole characters, the family's joiners kept", async () => {
    const { page, log } = await openPage(browser, { query: "?seed=1" });
    await winGame(page);
    const family = "👨‍👩‍👧";
    const kept = `${family}${"a".repeat(14)}e\u0301`; // 16 characters, 23 code points
    await page.focus("#name");
    await page.keyboard.insertText(`${kept}xyz`);
    assert.equal(await page.inputValue("#name"), kept);
    await page.keyboard.press("Enter");
    const table = (await state(page)).table;
    assert.deepEqual(
      table.map((e) => e.name),
      [kept],
    );
    assert.deepEqual(log.errors, []);
    await page.close();
  });
});
