// The page as students and lecturers use it (issue 27): every control by touch, nothing
// lost, legible. Real Chromium, driven by a finger (DevTools touch events), a mouse and the
// keyboard alone, as a person would.
import assert from "node:assert/strict";
import { existsSync } from "node:fs";
import { after, before, describe, test } from "node:test";
import { launch, openPage, PAGE } from "./browser.mjs";
import { decodePng } from "./png.mjs";

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

const PHONE = { viewport: { width: 390, height: 844 }, scale: 3, touch: true };
const LANDSCAPE = { viewport: { width: 844, height: 390 }, scale: 3, touch: true };
const state = (page) => page.evaluate(() => window.evapcool.state());
const spoken = (page) => page.evaluate(() => document.getElementById("live").textContent);
const saved = (page) =>
  page.evaluate(() => JSON.parse(localStorage.getItem("evapcool.settings") ?? "null"));

async function box(page, selector) {
  const b = await page.locator(selector).boundingBox();
  assert.ok(b, `${selector} is on the page`);
  return b;
}

async function touch(cdp, type, x, y) {
  await cdp.send("Input.dispatchTouchEvent", {
    type,
    touchPoints: type === "touchEnd" ? [] : [{ x, y }],
  });
}

/** A finger's tap on a control's centre. */
async function tapControl(page, cdp, name) {
  const b = await box(page, `[data-control="${name}"]`);
  await touch(cdp, "touchStart", b.x + b.width / 2, b.y + b.height / 2);
  await touch(cdp, "touchEnd", b.x + b.width / 2, b.y + b.height / 2);
}

describe("27.1 settings are never thrown away", () => {
  test("Enter saves with the focus on a button; Esc with changes says they were dropped", async () => {
    const { page, log } = await openPage(browser, { query: "?seed=2" });
    // Keyboard only: Tab to the gear, Enter opens it (the button's own press).
    let focused = "";
    for (let k = 0; k < 12 && focused !== "settings"; k++) {
      await page.keyboard.press("Tab");
      focused = await page.evaluate(() => document.activeElement?.dataset.control ?? "");
    }
    assert.equal(focused, "settings");
    await page.keyboard.press("Enter");
    assert.equal((await state(page)).overlay, "settings");
    await page.keyboard.press("ArrowRight"); // atoms 49 -> 54
    await page.keyboard.press("Enter"); // the focus is still on the gear button
    let s = await state(page);
    assert.equal(s.overlay, null);
    assert.equal((await saved(page))?.n_atoms, 54, "Enter saved, whatever had the focus");
    assert.ok(
      s.notices.some((n) => n.startsWith("Settings saved")),
      s.notices.join(" | "),
    );
    // A click on the gear opens; a change; a click on the gear again keeps it and says so.
    const gear = await box(page, '[data-control="settings"]');
    await page.mouse.click(gear.x + gear.width / 2, gear.y + gear.height / 2);
    await page.keyboard.press("ArrowRight"); // 54 -> 59
    await page.mouse.click(gear.x + gear.width / 2, gear.y + gear.height / 2);
    assert.equal((await saved(page))?.n_atoms, 59);
    // Esc drops a change, and says so.
    await page.keyboard.press("o");
    await page.keyboard.press("ArrowRight");
    await page.keyboard.press("Escape");
    s = await state(page);
    assert.equal((await saved(page))?.n_atoms, 59);
    assert.ok(
      s.notices.some((n) => n.includes("not saved")),
      s.notices.join(" | "),
    );
    // Opening the help over the settings also drops them out loud.
    await page.keyboard.press("o");
    await page.keyboard.press("ArrowRight");
    const help = await box(page, '[data-control="help"]');
    await page.mouse.click(help.x + help.width / 2, help.y + help.height / 2);
    s = await state(page);
    assert.equal(s.overlay, "help");
    assert.equal(s.notices.filter((n) => n.includes("not saved")).length, 2);
    assert.deepEqual(log.errors, []);
    await page.close();
  });
});

describe("27.2 every control by touch, hints in the device's words", () => {
  test("a phone: every control 44 px or more, step, speed, path chart and the autopilot by tap", async () => {
    const { page, cdp, log } = await openPage(browser, { ...PHONE, query: "?seed=4" });
    const names = ["pause", "restart", "step", "slower", "faster", "autopilot", "chart", "path"];
    names.push("help", "table", "settings", "fullscreen");
    for (const name of names) {
      const b = await box(page, `[data-control="${name}"]`);
      assert.ok(b.width >= 44 && b.height >= 44, `${name}: ${b.width} x ${b.height}`);
      assert.ok(b.x >= 0 && b.x + b.width <= 390 && b.y + b.height <= 844, `${name} on screen`);
    }
    await tapControl(page, cdp, "step");
    assert.equal((await state(page)).time, 1, "one frame forward");
    await tapControl(page, cdp, "faster");
    assert.equal((await state(page)).speed, 2);
    assert.equal(await spoken(page), "Speed 2x");
    await tapControl(page, cdp, "slower");
    await tapControl(page, cdp, "slower");
    assert.equal((await state(page)).speed, 0.5);
    assert.equal(await spoken(page), "Speed 0.5x");
    await tapControl(page, cdp, "path");
    assert.equal((await state(page)).showPath, true);
    await tapControl(page, cdp, "path");
    // The autopilot takes the trap: the demo's start height, then it moves the trap in play.
    await tapControl(page, cdp, "restart");
    await tapControl(page, cdp, "autopilot");
    let s = await state(page);
    assert.equal(s.autopilot, true);
    assert.ok(
      s.notices.some((n) => n.includes("the wheel to hand back")),
      s.notices.join("|"),
    );
    assert.notEqual(s.trapHeight, 400, "the demo sets its own start height");
    await page.evaluate(() => window.evapcool.runFrames(300));
    const h1 = (await state(page)).trapHeight;
    await page.evaluate(() => window.evapcool.runFrames(300));
    assert.ok((await state(page)).trapHeight < h1, "the autopilot lowers the trap");
    // A finger on the slider takes over.
    const slider = await box(page, ".slider");
    await touch(cdp, "touchStart", slider.x + 30, slider.y + slider.height / 2);
    await touch(cdp, "touchEnd", slider.x + 30, slider.y + slider.height / 2);
    s = await state(page);
    assert.equal(s.autopilot, false);
    assert.ok(
      s.notices.some((n) => n.includes("Tap the wheel")),
      s.notices.join("|"),
    );
    assert.deepEqual(log.errors, []);
    await page.close();
  });

  test("key A: the demo autopilot plays a whole game to a win; its score is not a player's", async () => {
    const { page, log } = await openPage(browser, { query: "?seed=7&speed=4" });
    await page.evaluate(() => localStorage.clear());
    await page.keyboard.press("a");
    assert.equal((await state(page)).autopilot, true);
    let s = await state(page);
    for (let k = 0; k < 40 && s.wonAt === null; k++) {
      await page.evaluate(() => window.evapcool.runFrames(25));
      s = await state(page);
    }
    assert.equal(s.won, true, `the demo won (t = ${s.time} frames)`);
    assert.ok(s.score > 10, `score ${s.score}`);
    assert.equal(s.nameBox, false, "no name asked: the autopilot played");
    assert.ok(
      s.notices.some((n) => n.startsWith("Autopilot (demo) won")),
      s.notices.join("|"),
    );
    assert.deepEqual(s.table, []);
    assert.deepEqual(log.errors, []);
    await page.close();
  });

  test("hints name what the device has: taps on a phone, keys on a keyboard", async () => {
    const tooFew = "?seed=1&atoms=20";
    for (const [opts, want, not] of [
      [PHONE, /Tap restart to try again/, /Press R/],
      [{}, /Press R to try again/, /Tap restart/],
    ]) {
      const { page, cdp } = await openPage(browser, { ...opts, query: tooFew });
      // Everything the live region says, in order (a later line may replace an earlier one).
      await page.evaluate(() => {
        window.__said = [];
        const live = document.getElementById("live");
        new MutationObserver(() => window.__said.push(live.textContent)).observe(live, {
          childList: true,
          characterData: true,
          subtree: true,
        });
      });
      // Drop the trap to the floor: nearly every atom escapes, too few are left to condense.
      if (opts.touch) {
        const slider = await box(page, ".slider");
        await touch(cdp, "touchStart", slider.x + 2, slider.y + slider.height / 2);
        await touch(cdp, "touchEnd", slider.x + 2, slider.y + slider.height / 2);
      } else {
        await page.keyboard.press("End");
        for (let k = 0; k < 90; k++) await page.keyboard.press("ArrowDown");
      }
      let said = "";
      for (let k = 0; k < 40 && !/Too few/.test(said); k++) {
        await page.evaluate(() => window.evapcool.runFrames(30));
        await page.waitForTimeout(30);
        said = (await page.evaluate(() => window.__said)).find((s) => /Too few/.test(s)) ?? "";
      }
      assert.match(said, want);
      assert.doesNotMatch(said, not);
      await page.close();
    }
  });
});

describe("27.3 the landscape phone's slider", () => {
  test("upright along the screen; a tap beside the knob does not jump; a drag moves it", async () => {
    const { page, cdp, log } = await openPage(browser, { ...LANDSCAPE, query: "?seed=2" });
    const s0 = await state(page);
    assert.equal(s0.layout, "side");
    const slider = await box(page, ".slider");
    assert.ok(slider.height > 250, `slider ${slider.height} CSS px long`);
    const l = await page.evaluate(() => window.evapcool.app.layout.slider);
    const top = s0.scale * l.y + (await page.evaluate(() => window.evapcool.app.layout.offsetY));
    const bar = l.h * s0.scale;
    const knobY = top + (1 - (400 - 25) / 425) * bar;
    const x = slider.x + slider.width / 2;
    // A tap 6 px beside the knob: the knob is taken where it is.
    await touch(cdp, "touchStart", x, knobY + 6);
    await touch(cdp, "touchEnd", x, knobY + 6);
    assert.equal((await state(page)).trapHeight, 400);
    // A drag down by half the bar lowers the trap by half its range.
    await touch(cdp, "touchStart", x, knobY - 4);
    for (let k = 1; k <= 6; k++) await touch(cdp, "touchMove", x, knobY - 4 + (bar / 2) * (k / 6));
    await touch(cdp, "touchEnd", x, knobY - 4 + bar / 2);
    const h = (await state(page)).trapHeight;
    assert.ok(Math.abs(h - (400 - 425 / 2)) < 2, `the trap at ${h}`);
    // Tab order: the slider, then the button grid row by row (as drawn).
    const order = await page.evaluate(() =>
      [...document.querySelectorAll(".controls > *")].map((e) => e.dataset.control ?? "slider"),
    );
    assert.deepEqual(order.slice(0, 4), ["slider", "pause", "restart", "step"]);
    assert.deepEqual(order.slice(-3), ["table", "settings", "fullscreen"]);
    assert.deepEqual(log.errors, []);
    await page.close();
  });
});

describe("27.4-27.6 legible words", () => {
  test("speeds as people write them, spoken and drawn clear of the title", async () => {
    const { page } = await openPage(browser, { query: "?speed=0.3&seed=1" });
    await page.keyboard.press("+");
    assert.equal(await spoken(page), "Speed 0.6x");
    await page.keyboard.press("-");
    await page.keyboard.press("-");
    assert.equal(await spoken(page), "Speed 0.15x".replace("0.15", "0.25"), "clamped at 0.25x");
    // The speed line ends before the title starts (the top border between them is bare).
    const img = decodePng(await page.screenshot());
    const l = await page.evaluate(() => window.evapcool.app.layout);
    const y0 = Math.round(l.offsetY + 10 * l.scale);
    let bare = true;
    for (let x = Math.round(l.offsetX + 172 * l.scale); x < l.offsetX + 182 * l.scale; x++)
      for (let y = y0; y < y0 + 30 * l.scale; y++) {
        const i = (y * img.width + x) * 4;
        if (Math.abs(img.data[i] - 79) > 30) bare = false;
      }
    assert.ok(bare, "no letters between the speed line and the title");
    await page.close();
  });

  test("the help: the display rate while playing, the game's pace; large on a projector", async () => {
    const { page } = await openPage(browser, {
      viewport: { width: 1920, height: 1080 },
      query: "?seed=1",
    });
    await page.keyboard.press("Space");
    await page.waitForTimeout(1500);
    await page.keyboard.press("Space"); // paused: the help must not count idle redraws
    await page.waitForTimeout(800);
    await page.keyboard.press("h");
    await page.waitForTimeout(200);
    const lines = await page.evaluate(() => window.evapcool.app.panels.rateLines());
    const fps = Number(/^(\d+) fps while playing/.exec(lines[0])?.[1]);
    assert.ok(fps >= 20, `display rate ${lines[0]}`);
    assert.match(lines[1], /real time/);
    const s = await state(page);
    assert.ok(s.helpSize * s.scale >= 30, `help rows ${s.helpSize * s.scale} CSS px at 1080p`);
    await page.close();
    for (const opts of [PHONE, LANDSCAPE]) {
      const { page: p } = await openPage(browser, { ...opts, query: "?seed=1" });
      await p.keyboard.press("h");
      await p.waitForTimeout(200);
      const st = await state(p);
      assert.ok(st.helpSize * st.scale >= 15.99, `${st.layout}: ${st.helpSize * st.scale} px`);
      await p.close();
    }
  });

  test("a phone: speed and slider words 16 CSS px or more; pinch-zoom allowed", async () => {
    const { page } = await openPage(browser, { ...PHONE, query: "?seed=1" });
    const touchAction = await page.evaluate(
      () => getComputedStyle(document.getElementById("app")).touchAction,
    );
    assert.equal(touchAction, "pinch-zoom");
    const meta = await page.evaluate(() => document.querySelector("meta[name=viewport]").content);
    assert.doesNotMatch(meta, /user-scalable=no|maximum-scale=1/);
    // The speed line's letters: measured on screen, rows of non-border pixels.
    const img = decodePng(await page.screenshot());
    const l = await page.evaluate(() => window.evapcool.app.layout);
    const rows = [];
    for (let y = 0; y < 48 * l.scale * 3; y++)
      for (let x = 3 * 3; x < 120 * 3; x++) {
        const i = (y * img.width + x) * 4;
        if (img.data[i] > 140) {
          rows.push(y);
          break;
        }
      }
    const height = (Math.max(...rows) - Math.min(...rows) + 1) / 3; // CSS px
    // "speed 1x": ascender to descender of p, about 0.9 of the font size.
    assert.ok(height >= 14, `speed line letters ${height} CSS px high`);
    await page.close();
  });
});

describe("27.9, 27.11, 27.12 name box, stored rows, focus", () => {
  test("the phone's name box types at 16 px or more; focus goes to restart, not the screen", async () => {
    const { page } = await openPage(browser, { ...PHONE, query: "?seed=1" });
    await page.evaluate(() => localStorage.clear());
    await page.evaluate(() => window.evapcool.forceWin());
    await page.evaluate(() => window.evapcool.runFrames(2));
    assert.equal((await state(page)).nameBox, true);
    const size = await page.evaluate(() =>
      parseFloat(getComputedStyle(document.getElementById("name")).fontSize),
    );
    assert.ok(size >= 16, `name box font ${size} px`);
    await page.keyboard.type("ADA");
    await page.keyboard.press("Enter");
    const focused = await page.evaluate(
      () => document.activeElement?.dataset.control ?? document.activeElement?.id,
    );
    assert.equal(focused, "restart", "the ring frames one button, not the whole screen");
    await page.close();
  });

  test("one bad stored row: the good rows stay in the table, only it is set aside", async () => {
    const { page } = await openPage(browser, { query: "?seed=1" });
    const key = "evapcool.highscores.49-r12-seed-rim";
    const row = (name, score) => ({ name, score, seconds: 50, date: "2026-11-20 10:00:00" });
    await page.evaluate(() => localStorage.clear());
    await page.evaluate(
      ([k, v]) => localStorage.setItem(k, v),
      [key, JSON.stringify({ version: 1, entries: [row("ANN", 30), row("", 25), row("BO", 20)] })],
    );
    await page.reload();
    await page.waitForFunction(() => window.evapcool !== undefined);
    const s = await state(page);
    assert.deepEqual(
      s.table.map((e) => e.name),
      ["ANN", "BO"],
    );
    assert.ok(
      s.notices.some((n) => n.includes("1 damaged row")),
      s.notices.join("|"),
    );
    const aside = await page.evaluate(() =>
      Object.keys(localStorage)
        .filter((k) => k.includes("corrupt"))
        .map((k) => localStorage.getItem(k)),
    );
    assert.equal(aside.length, 1);
    assert.deepEqual(JSON.parse(aside[0]).entries, [row("", 25)]);
    await page.close();
  });

  test("the slider's focus ring stays clear of its label", async () => {
    for (const viewport of [
      { width: 800, height: 700 },
      { width: 1280, height: 720 },
    ]) {
      const { page } = await openPage(browser, { viewport, query: "?seed=1" });
      const s = await box(page, ".slider");
      const l = await page.evaluate(() => window.evapcool.app.layout);
      const labelTop = l.offsetY + (l.slider.y + l.slider.h + l.knobRadius + 4) * l.scale;
      // The ring: 3 px outline 2 px out, and a 6 px halo: 6 CSS px below the box at most.
      assert.ok(s.y + s.height + 6 <= labelTop + 0.5, `ring ${s.y + s.height + 6} > ${labelTop}`);
      await page.close();
    }
  });
});
