// The page's sound (issue 48) rendered for real: its graph (the same Sound class, fed the game
// as it plays) in Chromium's OfflineAudioContext. Ticks are present where atoms left, the
// rest of the time only the quiet approach tone; muted, silence; M mutes, D describes.
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
/** The largest |sample| in [t0, t1) s. */
const peak = (r, t0, t1) => {
  let m = 0;
  for (
    let i = Math.max(0, Math.floor(t0 * r.rate));
    i < Math.min(r.samples.length, t1 * r.rate);
    i++
  )
    m = Math.max(m, Math.abs(r.samples[i]));
  return m;
};

test("ticks where atoms left, quiet between; muted: silence", async () => {
  const { page, log } = await openPage(browser, { ...VIEW, query: "?seed=11&trap=150&sound=on" });
  const r = await page.evaluate(() => window.evapcool.renderSound(120, 4.2));
  assert.ok(r.left.length >= 3, `atoms left in ${r.left.length} frames`);
  for (const t of r.left) assert.ok(peak(r, t, t + 0.03) > 0.08, `a tick at ${t} s`);
  // Windows 0.15 s clear of any departure hold no tick: far quieter than the ticks.
  const quiet = [];
  for (let t = 0; t < 4; t += 0.05)
    if (r.left.every((s) => t + 0.05 < s || t > s + 0.15)) quiet.push(peak(r, t, t + 0.05));
  assert.ok(quiet.length > 5, `${quiet.length} quiet windows`);
  assert.ok(Math.max(...quiet) < 0.05, `quiet windows peak at ${Math.max(...quiet)}`);
  await page.close();
  const muted = await openPage(browser, { ...VIEW, query: "?seed=11&trap=150&sound=off" });
  const m = await muted.page.evaluate(() => window.evapcool.renderSound(120, 4.2));
  assert.ok(m.left.length >= 3, "atoms left while muted too");
  assert.equal(peak(m, 0, 4.2), 0);
  assert.deepEqual([...log.errors, ...muted.log.errors], []);
  await muted.page.close();
});

test("the condensate's chord and a lost game's falling tone sound", async () => {
  const { page } = await openPage(browser, { ...VIEW, query: "?seed=2&sound=on" });
  const r = await page.evaluate(async () => {
    const ctx = new OfflineAudioContext(1, 22050 * 4, 22050);
    const app = window.evapcool.app;
    const s = app.teaching.sound.constructor;
    const sound = new s(true, 1);
    sound.attach(ctx);
    sound.chord(0.2);
    sound.fall(2.2);
    const b = await ctx.startRendering();
    return { rate: 22050, samples: Array.from(b.getChannelData(0)) };
  });
  assert.ok(peak(r, 0.25, 1.5) > 0.1, "the chord");
  assert.ok(peak(r, 2.25, 3.3) > 0.05, "the falling tone");
  assert.ok(peak(r, 0, 0.19) === 0, "nothing before");
  await page.close();
});

test("sound is off by default in class mode only; M mutes and unmutes; D says the scene", async () => {
  const { page } = await openPage(browser, { ...VIEW, query: "?trap=300" });
  assert.equal((await state(page)).soundOn, true);
  await page.keyboard.press("m");
  assert.equal((await state(page)).soundOn, false);
  await page.keyboard.press("m");
  assert.equal((await state(page)).soundOn, true);
  await page.keyboard.press("d");
  const live = await page.locator("#live").textContent();
  assert.match(live, /^Atoms in the cup: 49; T [\d.]+, Tc [\d.]+; trap height 300 px; paused\.$/);
  await page.evaluate(() => window.evapcool.runFrames(60));
  await page.keyboard.press("d");
  const after = await page.locator("#live").textContent();
  assert.match(after, /atoms leaving|no atom leaving now|close to condensing/);
  await page.close();
});
