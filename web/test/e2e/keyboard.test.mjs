// Every control by keyboard, named in the reader's language (issue 48): in each shipped
// locale, Chromium's accessibility tree names every button and the slider with the catalog's
// words; Tab visits every control once and Shift+Tab the same in reverse, each with a visible
// focus ring. The panels drawn on the canvas (settings, help, scores) the same way: each
// target an element in the Tab order, named from the catalog, ringed on the canvas.
import assert from "node:assert/strict";
import { existsSync, readdirSync, readFileSync } from "node:fs";
import { resolve } from "node:path";
import { after, before, test } from "node:test";
import { launch, openPage, PAGE, state, winGame } from "./browser.mjs";
import { decodePng, pixel } from "./png.mjs";

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

/** Two animation frames: the page has drawn (and its panel's elements followed) since. */
const drawn = (page) =>
  page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
/** The control (data-control) that has the focus once the page has drawn. */
const focusedControl = async (page) => {
  await drawn(page);
  return page.evaluate(() => document.activeElement?.dataset.control);
};
/** The focused element's panel target (data-action), or "" when the focus is elsewhere. */
const action = (page) => page.evaluate(() => document.activeElement?.dataset.action ?? "");
/** The panel's targets that have words, in their drawn order (the Tab order wanted). */
const panelTargets = (page) =>
  page.evaluate(() => window.evapcool.app.targets.filter((x) => x.label).map((x) => x.action));

/** Keyboard only: Tab to the gear, Enter; the focus is in the settings screen once drawn. */
async function openSettings(page) {
  for (let k = 0; k < 16; k++) {
    await page.keyboard.press("Tab");
    if ((await page.evaluate(() => document.activeElement?.dataset.control)) === "settings") break;
  }
  await page.keyboard.press("Enter");
  await page.waitForFunction(() => document.activeElement?.dataset.action === "row:0");
}

/** Tab (or Shift+Tab) from where the focus is until it leaves the panel: the actions met. */
async function walk(page, key, onEach = async () => {}) {
  const met = [];
  for (let k = 0; k < 40; k++) {
    const a = await action(page);
    if (!a) break;
    met.push(a);
    await onEach(a);
    await page.keyboard.press(key);
  }
  return met;
}

/** The focused element as Chromium's accessibility tree has it: role, name, checked. */
async function focusedNode(cdp) {
  const { result } = await cdp.send("Runtime.evaluate", { expression: "document.activeElement" });
  const { nodes } = await cdp.send("Accessibility.getPartialAXTree", {
    objectId: result.objectId,
    fetchRelatives: false,
  });
  const n = nodes[0];
  const checked = n.properties?.find((p) => p.name === "checked")?.value.value;
  return { role: n.role?.value, name: n.name?.value ?? "", checked };
}

/** Pixels of the canvas's focus ring (rgb(40,140,255)) in a band around the element. */
async function ringPixels(page, selector) {
  await drawn(page);
  const b = await page.locator(selector).boundingBox();
  const img = decodePng(await page.screenshot());
  let n = 0;
  for (let y = Math.floor(b.y - 10); y <= b.y + b.height + 10; y++)
    for (let x = Math.floor(b.x - 10); x <= b.x + b.width + 10; x++) {
      const inside = x > b.x + 1 && x < b.x + b.width - 1 && y > b.y + 1 && y < b.y + b.height - 1;
      const [r, g, bl] = pixel(img, x, y);
      if (!inside && Math.abs(r - 40) < 40 && Math.abs(g - 140) < 40 && bl > 215) n++;
    }
  return n;
}

test("the settings screen by keyboard: every row and button in both orders, ringed, saved", async () => {
  const { page, log } = await openPage(browser, { viewport: { width: 1000, height: 720 } });
  await page.evaluate(() => localStorage.clear());
  await openSettings(page);
  const wanted = await panelTargets(page);
  assert.equal(wanted.filter((a) => a.startsWith("row:")).length, 9, wanted.join());
  for (const b of ["save", "cancel", "copylink", "saverun"]) assert.ok(wanted.includes(b), b);
  // Tab: every target once, in the drawn order; the last Tab leaves for the scene's controls.
  const rings = [];
  const forward = await walk(page, "Tab", async (a) => {
    if (a === "row:1" || a === "save")
      rings.push([a, await ringPixels(page, `[data-action="${a}"]`)]);
  });
  assert.deepEqual(forward, wanted);
  // Shift+Tab from the controls back into the panel walks the same targets in reverse.
  await page.keyboard.press("Shift+Tab");
  assert.deepEqual(await walk(page, "Shift+Tab"), [...wanted].reverse());
  // The ring is drawn on the canvas around the focused target, and only there.
  for (const [a, n] of rings) assert.ok(n > 100, `${a}: ${n} ring pixels`);
  await page.keyboard.press("Tab"); // back onto row 0
  assert.equal(await action(page), "row:0");
  assert.equal(await ringPixels(page, '[data-action="save"]'), 0, "no ring on save now");
  // The arrows change the focused row's value, as the keys do; the element says the value.
  await page.keyboard.press("Tab"); // row 1: the radius
  await page.keyboard.press("Tab"); // row 2 ...
  await page.keyboard.press("Shift+Tab");
  await page.keyboard.press("Shift+Tab"); // ... and back to row 0: the atoms
  const value = () => page.locator('[data-action="row:0"]').getAttribute("aria-valuetext");
  assert.match(await value(), /^49\b/);
  await page.keyboard.press("ArrowRight");
  await drawn(page);
  assert.match(await value(), /^54\b/);
  // ArrowDown selects the next row and the focus follows it.
  await page.keyboard.press("ArrowDown");
  await drawn(page);
  assert.equal(await action(page), "row:1");
  // Space turns the sound's box over; Tab to Save and Enter presses it.
  while ((await action(page)) !== "row:6") await page.keyboard.press("Tab");
  const box = page.locator('[data-action="row:6"]');
  assert.equal(await box.getAttribute("aria-checked"), "true");
  await page.keyboard.press("Space");
  await drawn(page);
  assert.equal(await box.getAttribute("aria-checked"), "false");
  while ((await action(page)) !== "save") await page.keyboard.press("Tab");
  await page.keyboard.press("Enter");
  const s = await state(page);
  assert.equal(s.overlay, null);
  assert.equal(s.soundOn, false);
  const stored = await page.evaluate(() => JSON.parse(localStorage.getItem("evapcool.settings")));
  assert.equal(stored.n_atoms, 54);
  // The focus is back on the gear that opened the screen; Cancel by Space drops a change.
  assert.equal(await focusedControl(page), "settings");
  await page.keyboard.press("Enter");
  await page.waitForFunction(() => document.activeElement?.dataset.action === "row:0");
  await page.keyboard.press("ArrowRight");
  while ((await action(page)) !== "cancel") await page.keyboard.press("Tab");
  await page.keyboard.press("Space");
  assert.equal((await state(page)).overlay, null);
  const again = await page.evaluate(() => JSON.parse(localStorage.getItem("evapcool.settings")));
  assert.equal(again.n_atoms, 54, "Cancel kept the saved value");
  assert.deepEqual(log.errors, []);
  await page.close();
});

/** A catalog key as it would show if a message were missing. */
const RAW_KEY = /^[a-z_]+(\.[a-z_0-9]+)+$/;

for (const tag of TAGS) {
  test(`${tag}: the settings screen's rows and buttons named in the reader's language`, async () => {
    const { page, cdp } = await openPage(browser, {
      viewport: { width: 1000, height: 720 },
      query: `?lang=${tag}`,
    });
    const messages = JSON.parse(readFileSync(`${LOCALES}/${tag}.json`, "utf8")).messages;
    const keys = new Set(Object.keys(messages));
    await openSettings(page);
    const names = new Map();
    const read = async (a) => {
      const n = await focusedNode(cdp);
      assert.ok(n.name.trim(), `${tag} ${a}: no name`);
      assert.ok(!RAW_KEY.test(n.name) && !keys.has(n.name), `${tag} ${a}: named "${n.name}"`);
      const role = a.startsWith("row:") ? (a === "row:6" ? "checkbox" : "spinbutton") : "button";
      assert.equal(n.role, role, `${tag} ${a}`);
      if (role === "checkbox") assert.ok(["true", "false"].includes(String(n.checked)), tag);
      names.set(a, n.name);
    };
    const forward = await walk(page, "Tab", read);
    await page.keyboard.press("Shift+Tab");
    const backward = await walk(page, "Shift+Tab", read);
    assert.equal(forward.length, 13, forward.join());
    assert.deepEqual(backward, [...forward].reverse());
    const words = {
      save: "button.save",
      cancel: "button.cancel",
      copylink: "link.copy",
      saverun: "run.save",
      "row:4": "settings.language",
      "row:5": "theme.row",
      "row:6": "sound.row",
      "row:7": "sound.volume",
      "row:8": "run.rows",
    };
    for (const [a, key] of Object.entries(words)) assert.equal(names.get(a), messages[key], a);
    // Every row says its value as drawn.
    const values = await page.evaluate(() =>
      [...document.querySelectorAll('[role="spinbutton"]')].map((e) => e.ariaValueText ?? ""),
    );
    const drawn = await page.evaluate(() => window.evapcool.app.options.rows().map(([, v]) => v));
    assert.deepEqual(values, [...drawn.slice(0, 6), ...drawn.slice(7)]);
    await page.close();
  });
}

test("help, the score table and verify by keyboard: focus in, named buttons, focus back", async () => {
  const { page, cdp, log } = await openPage(browser, { viewport: { width: 1000, height: 720 } });
  // H with the focus nowhere: the help's Close has it; closed, it is nowhere again.
  await page.keyboard.press("h");
  await page.waitForFunction(() => document.activeElement?.dataset.action === "close");
  assert.deepEqual(await focusedNode(cdp), { role: "button", name: "Close", checked: undefined });
  await page.keyboard.press("Enter");
  assert.equal((await state(page)).overlay, null);
  assert.equal(await focusedControl(page), undefined);
  // Tab to the help's button, Enter: closed by Space, the focus is back on that button.
  while ((await page.evaluate(() => document.activeElement?.dataset.control)) !== "help")
    await page.keyboard.press("Tab");
  await page.keyboard.press("Enter");
  await page.waitForFunction(() => document.activeElement?.dataset.action === "close");
  await page.keyboard.press("Space");
  assert.equal((await state(page)).overlay, null);
  assert.equal(await focusedControl(page), "help");
  // T from there: the table's buttons in the Tab order, named; closed, back to the help's.
  await page.keyboard.press("t");
  await page.waitForFunction(() => document.activeElement?.dataset.action !== undefined);
  const wanted = await panelTargets(page);
  assert.ok(wanted.length >= 2, wanted.join());
  const met = await walk(page, "Tab", async (a) => {
    const n = await focusedNode(cdp);
    assert.equal(n.role, "button", a);
    assert.ok(n.name.trim() && !RAW_KEY.test(n.name), `${a}: "${n.name}"`);
  });
  assert.deepEqual(met, wanted);
  await page.keyboard.press("Shift+Tab");
  while ((await action(page)) !== "tableclose") await page.keyboard.press("Shift+Tab");
  await page.keyboard.press("Space");
  assert.equal((await state(page)).overlay, null);
  assert.equal(await focusedControl(page), "help");
  // V: the paste box keeps the focus it takes; Tab reaches Verify and Close, named.
  await page.keyboard.press("v");
  await drawn(page);
  assert.equal(await page.evaluate(() => document.activeElement?.tagName), "TEXTAREA");
  await page.keyboard.press("Tab");
  assert.deepEqual(await focusedNode(cdp), { role: "button", name: "Verify", checked: undefined });
  await page.keyboard.press("Tab");
  assert.deepEqual(await focusedNode(cdp), { role: "button", name: "Close", checked: undefined });
  await page.keyboard.press("Enter");
  assert.equal((await state(page)).overlay, null);
  assert.deepEqual(log.errors, []);
  await page.close();
});

test("the win screen's buttons by keyboard: Store and Skip, then Copy replay code", async () => {
  const { page, cdp, log } = await openPage(browser, {
    query: "?seed=1",
    viewport: { width: 1000, height: 720 },
  });
  await winGame(page);
  // Tab to the name box's buttons, each named; Enter on Skip skips.
  const met = new Map();
  for (let k = 0; k < 30 && !met.has("skip"); k++) {
    await page.keyboard.press("Tab");
    const a = await action(page);
    if (a) met.set(a, await focusedNode(cdp));
  }
  assert.deepEqual(met.get("store"), { role: "button", name: "Store", checked: undefined });
  assert.deepEqual(met.get("skip"), { role: "button", name: "Skip", checked: undefined });
  assert.ok((await ringPixels(page, '[data-action="skip"]')) > 40, "Skip ringed");
  await page.keyboard.press("Enter");
  assert.equal((await state(page)).nameBox, false);
  // The code's button: in the Tab order, named, ringed; Enter copies the code.
  await page.waitForFunction(() =>
    window.evapcool.app.targets.some((x) => x.action === "copycode"),
  );
  for (let k = 0; k < 30 && (await action(page)) !== "copycode"; k++)
    await page.keyboard.press("Tab");
  assert.deepEqual(await focusedNode(cdp), {
    role: "button",
    name: "Copy replay code",
    checked: undefined,
  });
  assert.ok((await ringPixels(page, '[data-action="copycode"]')) > 40, "Copy ringed");
  await page.keyboard.press("Enter");
  let notices = [];
  for (
    let look = 0;
    look < 100 && !notices.some((n) => n.startsWith("Replay code copied"));
    look++
  ) {
    notices = (await state(page)).notices;
    await page.waitForTimeout(50);
  }
  assert.ok(
    notices.some((n) => n.startsWith("Replay code copied")),
    notices.join("|"),
  );
  assert.deepEqual(log.errors, []);
  await page.close();
});
