// The name box on a phone (issue 25.6): no key hint a phone cannot follow, tappable Store
// and Skip buttons (44 CSS px touch targets at least), and on a keyboard both the hint and
// the buttons.
import assert from "node:assert/strict";
import { existsSync } from "node:fs";
import { after, before, test } from "node:test";
import { launch, openPage, PAGE, state, winGame } from "./browser.mjs";

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

/** A finger's tap at (x, y) CSS px (touch events through DevTools, as a phone sends them). */
async function tap(cdp, x, y) {
  await cdp.send("Input.dispatchTouchEvent", { type: "touchStart", touchPoints: [{ x, y }] });
  await cdp.send("Input.dispatchTouchEvent", { type: "touchEnd", touchPoints: [] });
}

/** The drawn Store/Skip buttons in CSS px of the page. */
async function buttons(page) {
  return page.evaluate(() => {
    const app = window.evapcool.app;
    const l = app.layout;
    const out = {};
    for (const t of app.targets)
      out[t.action] = {
        x: l.offsetX + (t.rect.x + t.rect.w / 2) * l.scale,
        y: l.offsetY + (t.rect.y + t.rect.h / 2) * l.scale,
        w: t.rect.w * l.scale,
        h: t.rect.h * l.scale,
      };
    return out;
  });
}

test("on a phone: tap Skip, no 'Esc' anywhere; the score is not stored", async () => {
  const { page, cdp } = await openPage(browser, {
    viewport: { width: 390, height: 844 },
    scale: 3,
    touch: true,
    query: "?seed=1",
  });
  await winGame(page);
  const b = await buttons(page);
  assert.ok(b.store && b.skip, "Store and Skip are drawn");
  const hint = await page.evaluate(() => window.evapcool.app.coarse);
  assert.equal(hint, true, "the page knows a finger is the pointer");
  for (const k of ["store", "skip"])
    assert.ok(b[k].h >= 43.9 && b[k].w >= 43.9, `${k}: ${b[k].w} x ${b[k].h} CSS px`);
  // A tap near the button's lower edge hits it.
  await tap(cdp, b.skip.x, b.skip.y + b.skip.h / 2 - 3);
  const s = await state(page);
  assert.equal(s.nameBox, false);
  assert.ok(s.notices.some((n) => n.startsWith("Score not stored")));
  await page.close();
});

test("on a phone: type a name, tap Store; it is in the table", async () => {
  const { page, cdp } = await openPage(browser, {
    viewport: { width: 390, height: 844 },
    scale: 3,
    touch: true,
    query: "?seed=1",
  });
  await winGame(page);
  await page.locator("#name").pressSequentially("Marie");
  const b = await buttons(page);
  await tap(cdp, b.store.x, b.store.y);
  const s = await state(page);
  assert.equal(s.nameBox, false);
  assert.equal(s.table[0].name, "Marie");
  await page.close();
});

test("with a mouse and keyboard: Enter stores, and a click on Skip skips", async () => {
  const { page } = await openPage(browser, { query: "?seed=1" });
  await winGame(page);
  assert.equal(await page.evaluate(() => window.evapcool.app.coarse), false);
  const b = await buttons(page);
  await page.mouse.click(b.skip.x, b.skip.y);
  assert.equal((await state(page)).nameBox, false);
  await page.close();
});
