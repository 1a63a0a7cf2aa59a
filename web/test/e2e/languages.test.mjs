// The page in other languages: every word from the message catalogs, chosen from the
// browser's languages, then ?lang=, then the settings screen's saved choice. Real Chromium.
// EVAPCOOL_DOCS_SHOTS=1 also writes docs/web-<tag>-{help,win}.png (1280x720).
import assert from "node:assert/strict";
import { existsSync, readFileSync } from "node:fs";
import { resolve } from "node:path";
import { after, before, describe, test } from "node:test";
import { chromium } from "playwright-core";
import { CHROMIUM, PAGE, PAGE_URL } from "./browser.mjs";

const LOCALES = resolve(import.meta.dirname, "../../../src/evapcool/locales");
const DOCS = resolve(import.meta.dirname, "../../../docs");
const SHOTS = process.env.EVAPCOOL_DOCS_SHOTS === "1";
const VIEWPORT = { width: 1280, height: 720 };
// Copied from FONT_FAMILY in web/src/view/text.ts: the family the canvas draws with.
const FONT_FAMILY =
  "EvapSans, 'Liberation Sans', Arial, Helvetica, 'Noto Sans CJK SC', 'PingFang SC', " +
  "'Microsoft YaHei', 'Hiragino Sans', 'Yu Gothic', 'Malgun Gothic', 'Noto Sans Arabic', " +
  "'Noto Naskh Arabic', Tahoma, sans-serif";

/** The catalog's messages: the expected words come from the same files the page is built from. */
const catalog = (tag) => JSON.parse(readFileSync(resolve(LOCALES, `${tag}.json`), "utf8")).messages;
const EN_TITLE = catalog("en")["page.doc_title"];

// launch() in browser.mjs gives one persistent context (shared localStorage, no locale);
// the browser's language and a clean store need contexts of their own, so a plain browser.
let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"],
  });
});
after(async () => browser?.close());

/** A context whose navigator.languages comes from `locale` (Chromium's own behaviour). */
const newContext = (locale = "en-US") => browser.newContext({ locale, viewport: VIEWPORT });

/** Opens the page in `context`; page errors are collected (a missing key may throw). */
async function open(context, query = "") {
  const page = await context.newPage();
  const errors = [];
  page.on("pageerror", (e) => errors.push(e.message));
  await page.goto(PAGE_URL + query);
  await page.waitForFunction(() => window.evapcool !== undefined);
  return { page, errors };
}

const state = (page) => page.evaluate(() => window.evapcool.state());
const spoken = (page) => page.evaluate(() => document.getElementById("live").textContent);
const shot = async (page, name) => {
  if (SHOTS) await page.screenshot({ path: resolve(DOCS, `web-${name}.png`) });
};

/** The literal start of a message, before its first placeholder (word order differs). */
const literalStart = (message) => message.slice(0, message.indexOf("{")).trim();

describe("a language from ?lang= (browser en-US)", () => {
  for (const tag of ["de", "ja", "ar"]) {
    test(`${tag}: words, direction, speech and the win all in ${tag}`, async () => {
      const m = catalog(tag);
      const context = await newContext();
      const { page, errors } = await open(context, `?lang=${tag}&seed=3`);
      let s = await state(page);
      assert.equal(s.locale, tag);
      assert.equal(s.direction, tag === "ar" ? "rtl" : "ltr");
      assert.equal(await page.evaluate(() => document.documentElement.lang), tag);
      // The document's direction, which the name box and the spoken lines inherit.
      const dir = tag === "ar" ? "rtl" : "ltr";
      const directions = await page.evaluate(() => [
        document.documentElement.dir,
        ...["name", "live", "status"].map(
          (id) => getComputedStyle(document.getElementById(id)).direction,
        ),
      ]);
      assert.deepEqual(directions, [dir, dir, dir, dir]);
      const title = await page.title();
      assert.notEqual(title, EN_TITLE, "the tab's title is translated");
      assert.equal(title, m["page.doc_title"]);

      await page.keyboard.press("Space");
      assert.equal(await spoken(page), m["page.playing"]);
      await page.keyboard.press("h");
      assert.equal((await state(page)).overlay, "help");
      assert.equal(await spoken(page), m["page.panel_shown"].replace("{panel}", m["help.title"]));
      // The button names the action it would do: Pause while playing, Play while paused.
      s = await state(page);
      const label = await page.getAttribute('[data-control="pause"]', "aria-label");
      assert.equal(label, s.paused ? m["control.play"] : m["control.pause"]);
      await page.evaluate(() => window.evapcool.runFrames(2));
      await shot(page, `${tag}-help`);

      await page.keyboard.press("h"); // help away, so the win screen is what is seen
      assert.equal((await state(page)).overlay, null);
      await page.evaluate(() => window.evapcool.forceWin());
      await page.evaluate(() => window.evapcool.runFrames(3));
      await page.waitForFunction(() => window.evapcool.state().wonAt !== null);
      s = await state(page);
      assert.equal(s.won, true);
      const said = await spoken(page);
      assert.ok(
        said.startsWith(literalStart(m["page.won_spoken"])),
        `win spoken as "${said}", expected it to start "${literalStart(m["page.won_spoken"])}"`,
      );
      assert.deepEqual(s.missingKeys, [], "every key the page asked for is in the catalog");
      await page.evaluate(() => window.evapcool.runFrames(2));
      await shot(page, `${tag}-win`);
      assert.deepEqual(errors, []);
      await context.close();
    });
  }
});

describe("which source wins", () => {
  test("?lang= beats the browser's languages; without it the browser's are used", async () => {
    const context = await newContext("ja-JP");
    assert.equal((await state((await open(context, "?lang=de")).page)).locale, "de");
    assert.equal((await state((await open(context)).page)).locale, "ja");
    await context.close();
  });

  test("an unknown ?lang= is refused aloud and the browser's language is used", async () => {
    const context = await newContext("ja-JP");
    const s = await state((await open(context, "?lang=xx")).page);
    assert.equal(s.locale, "ja");
    assert.ok(
      s.notices.some((n) => n.includes("lang")),
      `a notice names lang: ${s.notices.join(" | ")}`,
    );
    await context.close();
  });

  test("the settings Language row: changes on save, survives reload, beats ?lang=", async () => {
    const context = await newContext("en-US");
    const { page } = await open(context);
    assert.equal((await state(page)).locale, "en");
    assert.equal(await page.evaluate(() => document.documentElement.dir), "ltr");
    await page.keyboard.press("o");
    assert.equal((await state(page)).overlay, "settings");
    for (let k = 0; k < 4; k++) await page.keyboard.press("ArrowDown"); // 5th row: Language
    await page.keyboard.press("ArrowRight"); // auto -> the first tag, "ar"
    assert.equal((await state(page)).locale, "en", "only a save changes the language");
    await page.keyboard.press("Enter");
    const s = await state(page);
    assert.equal(s.overlay, null);
    assert.equal(s.locale, "ar");
    assert.equal(s.direction, "rtl");
    assert.equal(await page.evaluate(() => document.documentElement.dir), "rtl");
    assert.equal(await page.evaluate(() => localStorage.getItem("evapcool.lang")), "ar");
    await page.reload();
    await page.waitForFunction(() => window.evapcool !== undefined);
    assert.equal((await state(page)).locale, "ar", "the choice is kept");
    await page.goto(PAGE_URL + "?lang=de");
    await page.waitForFunction(() => window.evapcool !== undefined);
    assert.equal((await state(page)).locale, "ar", "a saved choice beats ?lang=");
    await context.close();
  });
});

describe("CJK and Arabic letters are drawn, not boxes", () => {
  for (const tag of ["ja", "ar"]) {
    test(`${tag}: the help title's letters have glyphs in the canvas font`, async () => {
      const context = await newContext();
      const { page } = await open(context, `?lang=${tag}`);
      const text = catalog(tag)["help.title"];
      const r = await page.evaluate(
        async ({ text, family }) => {
          await document.fonts.ready;
          const ctx = document.createElement("canvas").getContext("2d");
          ctx.canvas.width = 800;
          ctx.canvas.height = 40;
          ctx.font = "700 20px " + family;
          // A noncharacter has no glyph in any font: its width is the fallback box's.
          const box = ctx.measureText("\u{10FFFF}").width;
          const letters = [...text].filter((c) => c.trim() !== "");
          const boxes = letters.filter((c) => ctx.measureText(c).width === box).length;
          ctx.fillText(text, 10, 28);
          const px = ctx.getImageData(0, 0, 800, 40).data;
          let ink = 0;
          for (let i = 3; i < px.length; i += 4) if (px[i] > 0) ink++;
          return { box, boxes, letters: letters.length, ink };
        },
        { text, family: FONT_FAMILY },
      );
      assert.ok(r.ink > 100, `the title leaves ink (${r.ink} px)`);
      assert.ok(
        r.boxes < 0.1 * r.letters,
        `${r.boxes} of ${r.letters} letters are as wide as the box (${r.box} px)`,
      );
      await context.close();
    });
  }
});

test("without JavaScript the page says so in every shipped language", async () => {
  const context = await browser.newContext({ javaScriptEnabled: false, viewport: VIEWPORT });
  const page = await context.newPage();
  await page.goto(PAGE_URL);
  const said = await page.evaluate(() =>
    [...document.querySelectorAll("noscript p")].map((p) => [p.lang, p.textContent]),
  );
  const tags = ["ar", "de", "en", "es", "fr", "it", "ja", "ko", "nl", "pl", "pt-BR", "zh-CN"];
  assert.deepEqual(said.map(([tag]) => tag).sort(), tags);
  for (const [tag, text] of said) assert.equal(text, catalog(tag)["page.noscript"]);
  // Shown, not hidden: the first paragraph has a box on the screen.
  assert.ok(await page.locator("#noscript").isVisible());
  await context.close();
});
