// Replay codes across the two editions (issue 22), in real Chromium: a game won in the page
// gives a code the desktop's `evapcool verify` accepts; a code the desktop's engine made is
// verified in the page's verify panel (a forged one refused with its reason); ?replay=CODE
// plays a recording back to its claimed score.
import assert from "node:assert/strict";
import { execFileSync, spawnSync } from "node:child_process";
import { existsSync } from "node:fs";
import { after, before, describe, test } from "node:test";
import { launch, openPage, PAGE, rampToWin, verifyButtonAt } from "./browser.mjs";
import { pythonWithEvapcool } from "./python.mjs";

const PYTHON = pythonWithEvapcool(); // none: this file fails, saying so (python.mjs)

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

const state = (page) => page.evaluate(() => window.evapcool.state());

/** Win with a scripted ramp (the page's keys): 5 px lower every 25 frames down to 100. */
async function winGame(page) {
  const s = await rampToWin(page);
  assert.equal(s.won, true, "the ramp wins");
  return s;
}

/** A code made by the desktop's engine: the demo autopilot's game of this seed (and forged). */
function desktopCodes(seed) {
  const script = [
    "import dataclasses, json",
    "from evapcool.game.replay import Settings, encode, record_autopilot",
    `rec = record_autopilot("demo", Settings(), ${seed}, budget=2400)`,
    "forged = dataclasses.replace(rec, score=rec.score + 3)",
    "print(json.dumps({'code': encode(rec), 'forged': encode(forged), 'score': rec.score,",
    "  'frames': rec.frames, 'won': rec.won}))",
  ].join("\n");
  return JSON.parse(execFileSync(PYTHON, ["-c", script], { encoding: "utf-8" }));
}

describe("replay codes between the editions", () => {
  test("a game won in the page: C copies its code; the desktop verifies it", async () => {
    const { page, log } = await openPage(browser, { query: "?seed=21" });
    await page.evaluate(() => localStorage.clear());
    const s = await winGame(page);
    if (s.nameBox) await page.keyboard.press("Escape"); // skip the name: the code is shown
    await page.waitForFunction(() => window.evapcool.app.replays.current !== null);
    await page.evaluate(() => window.evapcool.runFrames(2));
    const targets = await page.evaluate(() => window.evapcool.app.targets.map((t) => t.action));
    assert.ok(targets.includes("copycode"), `win screen buttons: ${targets}`);
    await page.keyboard.press("c");
    await page.waitForFunction(
      () => window.evapcool.stateNow().notices.some((n) => /Replay code copied|by hand/.test(n)),
      null,
      { timeout: 10_000 },
    );
    const notices = (await state(page)).notices.join(" | ");
    assert.match(notices, /Replay code copied|Copy this replay code by hand/);
    const code = await page.evaluate(() => window.evapcool.app.replays.current);
    const out = spawnSync(PYTHON, ["-m", "evapcool", "verify", code], { encoding: "utf-8" });
    assert.equal(out.status, 0, out.stdout + out.stderr);
    assert.match(out.stdout, new RegExp(`1\\.\\s+${s.score} atoms`));
    assert.deepEqual(log.errors, []);
    await page.close();
  });

  test("the verify panel ranks desktop codes and refuses a forged one with its reason", async () => {
    const a = desktopCodes(3);
    const b = desktopCodes(8);
    assert.ok(a.won && b.won, "the demo won both");
    const { page, log } = await openPage(browser, { query: "?seed=1" });
    await page.keyboard.press("v");
    assert.equal((await state(page)).overlay, "verify");
    await page.waitForSelector("#codes:not([hidden])");
    await page.fill("#codes", [a.code, b.forged, "EC1.broken.00000000", b.code].join("\n"));
    // The panel's Verify button, as drawn (a mouse click on it).
    const at = await verifyButtonAt(page);
    await page.mouse.click(at[0], at[1]);
    await page.waitForFunction(
      () => !window.evapcool.app.verifier.busy && window.evapcool.app.verifier.results.length === 4,
      null,
      { timeout: 60_000 },
    );
    const lines = await page.evaluate(() => window.evapcool.app.verifier.lines());
    const [best, second] = [a, b].sort((x, y) => y.score - x.score || x.frames - y.frames);
    const en = (n) => n.toLocaleString("en"); // the panel writes numbers as English does
    assert.match(
      lines[0],
      new RegExp(`^1\\.\\s+${en(best.score)} atoms\\s+${en(best.frames)} frames\\s+desktop`),
    );
    assert.match(lines[1], new RegExp(`^2\\.\\s+${en(second.score)} atoms`));
    assert.ok(lines.some((l) => l.includes("rejected (does not replay to the claimed score)")));
    assert.ok(lines.some((l) => l.includes("rejected (damaged)")));
    assert.deepEqual(log.errors, []);
    await page.close();
  });

  test("?replay=CODE plays the recording back to its claimed score", async () => {
    const a = desktopCodes(5);
    const { page, log } = await openPage(browser, {
      query: `?replay=${encodeURIComponent(a.code)}`,
    });
    let s = await state(page);
    assert.ok(
      s.notices.some((n) => n.startsWith("Watching a replay")),
      s.notices.join("|"),
    );
    for (let k = 0; k < 200 && s.wonAt === null; k++) {
      await page.evaluate(() => window.evapcool.runFrames(30));
      s = await state(page);
    }
    assert.equal(s.won, true);
    assert.equal(s.score, a.score);
    assert.equal(s.nameBox, false, "a replay's win is not a player's");
    assert.deepEqual(log.errors, []);
    await page.close();
  });
});
