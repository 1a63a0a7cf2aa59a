// A teacher's setup as a link (issue 48): every new option and every lock by real keys and
// taps, one notice per bad option, the link written from what is on screen and opened again
// giving the same setup; "Save this run" read back as evapcool lab's CSV.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { existsSync, readFileSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { after, before, test } from "node:test";
import { launch, openPage, PAGE, state } from "./browser.mjs";
import { pythonWithEvapcool } from "./python.mjs";

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

const VIEW = { viewport: { width: 1000, height: 720 } };
const LOCKS = "atoms,radius,escape,tc-law,speed,trap";
const SETUP =
  `?atoms=30&radius=10&seed=7&speed=2&tc-law=cup&escape=knife&trap=300` +
  `&lock=${LOCKS}&hide=help,table,autopilot&theme=projector&sound=off&lang=de`;

/** What makes a setup: the game's config, the trap, the theme, locks, hidden buttons. */
const setupOf = (page) =>
  page.evaluate(async () => {
    const e = window.evapcool;
    const s = await e.state();
    const app = e.app;
    return {
      config: app.game.config,
      speed: s.speed,
      trap: s.trapHeight,
      theme: s.theme,
      soundOn: s.soundOn,
      locale: s.locale,
      lock: [...app.teaching.setup.locked].sort(),
      hide: [...app.teaching.setup.hidden].sort(),
      atomsX: Array.from(app.game.sim.trapped().x.slice(0, 30)),
    };
  });

/** The centre of a drawn panel target (its action) in CSS px. */
const targetAt = (page, action) =>
  page.evaluate((action) => {
    const app = window.evapcool.app;
    const t = app.targets.find((x) => x.action === action);
    const z = app.overlayZoom();
    const l = app.layout;
    const x = z.x + (t.rect.x + t.rect.w / 2 - z.cx) * z.k;
    const y = z.y + (t.rect.y + t.rect.h / 2 - z.cy) * z.k;
    return [l.offsetX + x * l.scale, l.offsetY + y * l.scale];
  }, action);

test("every new option applies; every lock holds against keys, taps and drags", async () => {
  const { page, log } = await openPage(browser, { ...VIEW, query: SETUP });
  const s = await state(page);
  assert.deepEqual(s.notices, []);
  const setup = await setupOf(page);
  assert.equal(setup.config.nAtoms, 30);
  assert.equal(setup.config.radius, 10);
  assert.equal(setup.config.escape, "knife");
  assert.equal(setup.config.seed, 7);
  assert.equal(setup.speed, 2);
  assert.equal(setup.trap, 300, "trap: the start height");
  assert.equal(setup.theme, "projector");
  assert.equal(setup.soundOn, false);
  assert.equal(setup.locale, "de");
  assert.deepEqual(setup.lock, LOCKS.split(",").sort());
  // trap: keys, the slider's keys and a drag leave it; each try is said.
  await page.keyboard.press("ArrowDown");
  await page.focus(".slider");
  await page.keyboard.press("Home");
  const box = await page.locator(".slider").boundingBox();
  await page.mouse.move(box.x + 10, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + 20, box.y + box.height / 2);
  await page.mouse.up();
  let now = await state(page);
  assert.equal(now.trapHeight, 300);
  assert.ok(
    now.notices.some((n) => n.includes("gesperrt")),
    now.notices.join("|"),
  );
  // speed: + and - do nothing.
  await page.keyboard.press("+");
  await page.keyboard.press("-");
  assert.equal((await state(page)).speed, 2);
  // atoms, radius, tc-law, escape: their rows on the settings screen do not move.
  await page.keyboard.press("o");
  for (let row = 0; row < 4; row++) {
    await page.keyboard.press("ArrowRight");
    await page.keyboard.press("ArrowLeft");
    await page.keyboard.press("ArrowDown");
  }
  const rows = await page.evaluate(() => window.evapcool.app.options.rows());
  assert.ok(
    rows.slice(0, 4).every(([, v]) => v.includes("gesperrt")),
    JSON.stringify(rows),
  );
  await page.keyboard.press("Enter");
  assert.equal((await setupOf(page)).config.nAtoms, 30);
  // hide: the buttons are gone, and so are their keys.
  for (const name of ["help", "table", "autopilot"])
    assert.equal(await page.locator(`[data-control="${name}"]`).isHidden(), true, name);
  await page.keyboard.press("h");
  await page.keyboard.press("t");
  await page.keyboard.press("a");
  now = await state(page);
  assert.equal(now.overlay, null);
  assert.equal(now.autopilot, false);
  // A restart keeps the setup (start height included).
  await page.keyboard.press("r");
  assert.equal((await state(page)).trapHeight, 300);
  assert.deepEqual(log.errors, []);
  await page.close();
});

test("the link written from the screen opens the same setup; the control copies it", async () => {
  const { page, log } = await openPage(browser, { ...VIEW, query: SETUP });
  const before = await setupOf(page);
  const link = await page.evaluate(() => window.evapcool.link());
  assert.match(link, /^file:.*evapcool\.html\?/);
  assert.match(link, /lock=atoms,radius,escape,tc-law,speed,trap/);
  // The settings screen's control: a notice that it was copied (or the link to copy by hand).
  await page.keyboard.press("o");
  // The settings screen's targets exist once it has been drawn (the next frame).
  await page.waitForFunction(() =>
    window.evapcool.app.targets.some((x) => x.action === "copylink"),
  );
  const [x, y] = await targetAt(page, "copylink");
  await page.mouse.click(x, y);
  // The clipboard answers asynchronously: the notice comes when it has.
  let notices = [];
  for (let look = 0; look < 100 && notices.length === 0; look++) {
    notices = (await state(page)).notices;
    if (notices.length === 0) await page.waitForTimeout(50);
  }
  assert.ok(
    notices.some((n) => n.startsWith("Link kopiert") || n.includes(link)),
    notices.join("|"),
  );
  const again = await browser.context.newPage();
  await again.setViewportSize(VIEW.viewport);
  await again.goto(link);
  await again.waitForFunction(() => window.evapcool !== undefined);
  assert.deepEqual(await setupOf(again), before);
  assert.deepEqual((await state(again)).notices, []);
  assert.deepEqual(log.errors, []);
  await again.close();
  await page.close();
});

test("bad new options: one notice each, naming the option; the rest still applies", async () => {
  const query = "?trap=5&lock=atoms,wings&hide=nothing&theme=pink&seed=3";
  const { page } = await openPage(browser, { ...VIEW, query });
  const notices = (await state(page)).notices;
  assert.equal(notices.length, 4, notices.join("\n"));
  for (const name of ["trap", "lock", "hide", "theme"])
    assert.equal(notices.filter((n) => n.startsWith(`Address: ${name} must be`)).length, 1, name);
  assert.ok(notices[0].includes('(got "5")'));
  const s = await setupOf(page);
  assert.equal(s.config.seed, 3);
  assert.equal(s.trap, 400);
  assert.deepEqual(s.lock, []);
  await page.close();
});

test("Save this run (key W): the download is evapcool lab's CSV, read back", async () => {
  const { page, log } = await openPage(browser, { ...VIEW, query: "?seed=5&atoms=40&trap=200" });
  await page.evaluate(() => window.evapcool.runFrames(95));
  const download = page.waitForEvent("download");
  await page.keyboard.press("w");
  const file = await (await download).path();
  const text = readFileSync(file, "utf8");
  const lines = text.trimEnd().split("\n");
  assert.equal(lines[0], "# evapcool lab results");
  const header = lines.find((l) => !l.startsWith("#"));
  assert.equal(
    header,
    "frame,n_trapped,temperature,critical_temperature,trap_height,total_energy," +
      "pair_collisions,wall_collisions,escaped,evaporated,evaporated_energy,excess_energy," +
      "spilled,spilled_energy,phase_space_density,won",
  );
  const meta = Object.fromEntries(
    lines
      .filter((l) => l.startsWith("# ") && l.includes(": "))
      .map((l) => [l.slice(2, l.indexOf(": ")), JSON.parse(l.slice(l.indexOf(": ") + 2))]),
  );
  assert.equal(meta.parameters.seed, 5);
  assert.equal(meta.parameters.n_atoms, 40);
  assert.match(meta.replay_code, /\S{20,}/);
  const cols = header.split(",");
  const rows = lines.slice(lines.indexOf(header) + 1).map((l) => l.split(","));
  const col = (name) => rows.map((r) => Number(r[cols.indexOf(name)]));
  assert.ok(rows.length >= 4, `${rows.length} rows for 95 frames, one a second`);
  // One row a second: the first drawn frame of each (the worker's newest frame at most a
  // frame or two into it).
  col("frame")
    .slice(0, 4)
    .forEach((f, k) => assert.ok(f >= 30 * k && f <= 30 * k + 2, `row ${k} at frame ${f}`));
  col("n_trapped").forEach((n, k) => assert.equal(n + col("escaped")[k], 40));
  assert.ok(col("trap_height").every((h) => h === 200));
  const s = await state(page);
  assert.ok(s.notices.some((n) => n.startsWith("This run saved as a CSV file")));
  // The lab's own reader takes it, where the Python project is installed.
  const python = pythonWithEvapcool(); // none: this test fails, saying so (python.mjs)
  {
    const path = join(tmpdir(), `evapcool-run-${process.pid}.csv`);
    writeFileSync(path, text);
    const out = execFileSync(python, [
      "-c",
      "import sys; from evapcool.lab.io import read_result; m, c, e = read_result(sys.argv[1]);" +
        " print(len(c['frame']), int(c['n_trapped'][0]), m['parameters']['seed'])",
      path,
    ]).toString();
    assert.equal(out.trim(), `${rows.length} ${col("n_trapped")[0]} 5`);
  }
  assert.deepEqual(log.errors, []);
  await page.close();
});
