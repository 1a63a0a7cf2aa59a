// Every control by keyboard, named in the reader's language (issue 48): in each shipped
// locale, Chromium's accessibility tree names every button and the slider with the catalog's
// words; Tab visits every control once and Shift+Tab the same in reverse, each with a visible
// focus ring.
import assert from "node:assert/strict";
import { existsSync, readdirSync, readFileSync } from "node:fs";
import { resolve } from "node:path";
import { after, before, test } from "node:test";
import { launch, openPage, PAGE } from "./browser.mjs";

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

const LOCALES = resolve(import.meta.dirname, "../../../src/evapcool/locales");
const TAGS = readdirSync(LOCALES)
  .filter((f) => f.endsWith(".json"))
  .map((f) => f.slice(0, -5));
/** Each control's catalog key (app/controls.ts's LABELS, the game paused). */
const KEYS = {
  pause: "control.play",
  restart: "status.restart",
  chart: "controls.energy_chart",
  help: "help.title",
  table: "control.table",
  settings: "settings.title",
  fullscreen: "controls.full_screen",
  step: "control.step",
  slower: "control.slower",
  faster: "control.faster",
  path: "control.path",
  autopilot: "control.autopilot",
  slider: "controls.trap_height",
};

/** What has the focus: a control's name, or the element's id or tag. */
const focused = (page) =>
  page.evaluate(() => {
    const el = document.activeElement;
    if (!el || el === document.body) return "body";
    const name =
      el.dataset.control ?? (el.classList.contains("slider") ? "slider" : el.id || el.tagName);
    const style = getComputedStyle(el);
    return { name, ring: style.outlineStyle !== "none" && parseFloat(style.outlineWidth) >= 3 };
  });

test("Tab and Shift+Tab visit every control, each with a visible focus ring", async () => {
  const { page } = await openPage(browser, { viewport: { width: 1000, height: 720 } });
  const forward = [];
  for (let k = 0; k < 30; k++) {
    await page.keyboard.press("Tab");
    const f = await focused(page);
    if (f === "body") continue;
    if (forward.length && f.name === forward[0].name) break;
    forward.push(f);
  }
  const names = forward.map((f) => f.name);
  for (const name of Object.keys(KEYS))
    assert.ok(names.includes(name), `${name} not reached: ${names}`);
  assert.equal(new Set(names).size, names.length, "each once");
  assert.deepEqual(
    forward.filter((f) => !f.ring).map((f) => f.name),
    [],
    "focus rings",
  );
  // Back from the first: Shift+Tab walks the same cycle in reverse (the page itself,
  // between the last and the first, is not a control).
  const backward = [];
  for (let k = 0; k < 40 && backward.length < names.length - 1; k++) {
    await page.keyboard.press("Shift+Tab");
    const f = await focused(page);
    if (f !== "body") backward.push(f.name);
  }
  assert.deepEqual(backward, [...names.slice(1)].reverse());
  await page.close();
});

for (const tag of TAGS) {
  test(`${tag}: every control has its accessible name in the reader's language`, async () => {
    const { page, cdp } = await openPage(browser, {
      viewport: { width: 1000, height: 720 },
      query: `?lang=${tag}`,
    });
    const messages = JSON.parse(readFileSync(`${LOCALES}/${tag}.json`, "utf8")).messages;
    const { nodes } = await cdp.send("Accessibility.getFullAXTree");
    const controls = nodes.filter(
      (n) => !n.ignored && ["button", "slider"].includes(n.role?.value),
    );
    const names = controls.map((n) => n.name?.value ?? "");
    assert.ok(controls.length >= 13, `${controls.length} controls in the tree`);
    assert.deepEqual(
      names.filter((n) => !n.trim()),
      [],
      "each has a name",
    );
    for (const [control, key] of Object.entries(KEYS)) {
      const want = messages[key];
      if (want.includes("{")) continue; // a message with a number: its words are checked by key
      assert.ok(
        names.includes(want),
        `${tag}: ${control} should be named "${want}": ${names.join(" | ")}`,
      );
    }
    await page.close();
  });
}
