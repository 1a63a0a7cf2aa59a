// The sound's default where the page can know there is no audio output (issue 48): no Web
// Audio at all, a context that cannot be made, or one still not running after a key press
// (the gesture browsers wait for). There the sound is off, the settings say so, and M
// leaves it muted. Where a context runs (this Chromium), the default stays on. A device's mute switch is
// beyond what a page can read (docs/teach.md).
import assert from "node:assert/strict";
import { existsSync } from "node:fs";
import { after, before, test } from "node:test";
import { launch, openPage, PAGE, state } from "./browser.mjs";

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

const VIEW = { viewport: { width: 1000, height: 720 } };
/** The settings screen's sound row's value, as drawn. */
const soundRow = (page) =>
  page.evaluate(() => {
    const app = window.evapcool.app;
    return app.options.rows()[6][1];
  });
const live = (page) => page.locator("#live").textContent();

/** Scripts run before the page's own: each takes away what a browser without output lacks. */
const NO_OUTPUT = {
  "no Web Audio": () => {
    delete window.AudioContext;
    delete window.webkitAudioContext;
  },
  "a context that cannot be made": () => {
    window.AudioContext = class {
      constructor() {
        throw new DOMException("no audio device", "NotSupportedError");
      }
    };
  },
  "a context that stays suspended after a key": () => {
    const Real = window.AudioContext;
    window.AudioContext = class extends Real {
      get state() {
        return "suspended";
      }
      resume() {
        return Promise.resolve();
      }
    };
  },
};

for (const [what, initScript] of Object.entries(NO_OUTPUT)) {
  test(`${what}: sound off by default, the settings say off, M keeps it muted`, async () => {
    const { page, log } = await openPage(browser, { ...VIEW, initScript });
    await page.keyboard.press("q"); // no key of the game; a gesture: the page tries its sound now
    await page.waitForFunction(() => !window.evapcool.app.teaching.sound.on);
    assert.equal((await state(page)).soundOn, false);
    assert.equal(await soundRow(page), "muted");
    await page.keyboard.press("m");
    assert.equal(await live(page), "Sound muted");
    assert.equal((await state(page)).soundOn, false);
    // The link written from the screen carries the sound as it is: off.
    assert.match(await page.evaluate(() => window.evapcool.link()), /[?&]sound=off\b/);
    assert.deepEqual(log.errors, []);
    await page.close();
  });
}

test("where a context runs after a key, the sound stays on (this Chromium)", async () => {
  const { page, log } = await openPage(browser, VIEW);
  await page.keyboard.press("q");
  await page.waitForFunction(() => window.evapcool.app.teaching.sound.attached);
  const ctxState = await page.evaluate(async () => {
    const sound = window.evapcool.app.teaching.sound;
    await sound.master.context.resume();
    return sound.master.context.state;
  });
  assert.equal(ctxState, "running");
  assert.equal((await state(page)).soundOn, true);
  assert.equal(await soundRow(page), "playing");
  await page.keyboard.press("m");
  assert.equal(await live(page), "Sound muted");
  assert.deepEqual(log.errors, []);
  await page.close();
});
