// The physics worker, end to end in headless Chromium (issue 24): the golden traces through
// the engine the page plays with inside the worker, the same game with and without it, the
// page's own loop where Workers are missing or fail, keys answered within two frames while
// 10 000 atoms run, and the slow-motion line when the device is throttled.
// Frames are counted, never timed.
import assert from "node:assert/strict";
import { existsSync, readdirSync, readFileSync } from "node:fs";
import { join, resolve } from "node:path";
import { after, before, describe, test } from "node:test";
import { launch, openPage, PAGE } from "./browser.mjs";

const GOLDEN = resolve(import.meta.dirname, "../golden");
const NO_WORKER = () => {
  delete window.Worker;
};
const BROKEN_WORKER = () => {
  // A worker that reports an error and never answers (a blocked or broken blob worker).
  window.Worker = class extends EventTarget {
    postMessage() {}
    terminate() {}
    set onerror(f) {
      setTimeout(() => f({ message: "broken on purpose" }), 0);
    }
  };
};

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

const state = (page) => page.evaluate(() => window.evapcool.state());

/** Wait n display frames of the page (counted, not timed). */
const frames = (page, n) =>
  page.evaluate(
    (n) =>
      new Promise((ok) => {
        const next = (k) => (k === 0 ? ok() : requestAnimationFrame(() => next(k - 1)));
        next(n);
      }),
    n,
  );

describe("the physics worker", () => {
  test("every golden trace replays bit for bit through the worker's engine", async () => {
    const { page, log } = await openPage(browser, { query: "?seed=1" });
    assert.equal((await state(page)).engine, "worker");
    const files = readdirSync(GOLDEN)
      .filter((f) => f.endsWith(".json"))
      .filter((f) =>
        readFileSync(join(GOLDEN, f), "utf8").slice(0, 200).includes('"evapcool-trace"'),
      );
    assert.ok(files.length >= 8);
    for (const file of files) {
      const text = readFileSync(join(GOLDEN, file), "utf8");
      const mine = await page.evaluate((t) => window.evapcool.replay(t), text);
      assert.ok(mine === text, `${file}: the worker's trace differs from the golden one`);
    }
    assert.deepEqual(log.errors, []);
    await page.close();
  });

  test("a scripted game gives the same events, bit for bit, with and without the worker", async () => {
    const play = async (initScript) => {
      const { page, log } = await openPage(browser, { query: "?seed=7", initScript });
      const out = await page.evaluate(async () => {
        const api = window.evapcool;
        api.app.stop(); // frames only from the script below
        const g = api.app.game;
        let wonAtStep = -1;
        for (let k = 0; k < 120 && wonAtStep < 0; k++) {
          if (g.trapHeight > 100) g.nudgeHeight(-5);
          await api.runFrames(25);
          if (g.won) wonAtStep = k;
        }
        const s = await api.state();
        const a = g.sim.trapped();
        const column = (c) => Array.from(c.subarray(0, a.count));
        return {
          engine: s.engine,
          wonAtStep,
          wonAt: g.wonAt,
          score: s.score,
          time: s.time,
          nTrapped: s.nTrapped,
          temperature: s.temperature,
          x: column(a.x),
          y: column(a.y),
          vx: column(a.vx),
          vy: column(a.vy),
          errors: s.errors,
        };
      });
      assert.deepEqual(log.errors, []);
      await page.close();
      return out;
    };
    const worker = await play(undefined);
    const page = await play(NO_WORKER);
    assert.equal(worker.engine, "worker");
    assert.equal(page.engine, "page");
    assert.ok(worker.wonAtStep >= 0, "the ramp condenses the gas");
    assert.deepEqual(worker.errors, []);
    for (const key of ["wonAtStep", "wonAt", "score", "time", "nTrapped", "temperature"])
      assert.ok(Object.is(worker[key], page[key]), `${key}: ${worker[key]} vs ${page[key]}`);
    for (const key of ["x", "y", "vx", "vy"])
      assert.ok(
        worker[key].every((v, i) => Object.is(v, page[key][i])),
        `atoms' ${key} differ`,
      );
  });

  test("the reach rule runs in the worker; the height asked for is clamped once, on the page", async () => {
    const play = async (initScript) => {
      const { page, log } = await openPage(browser, { query: "?seed=1&atoms=20", initScript });
      const out = await page.evaluate(async () => {
        const api = window.evapcool;
        api.app.stop(); // frames only from the script below
        const g = api.app.game;
        const changed = g.setTrapHeight(-1000);
        const asked = g.trapHeight; // answered at once
        const held = (await api.state()).trapHeight;
        const sim = g.sim.trapHeight; // the physics' own, as the worker (or page) applied it
        let reason = null;
        let k = 0;
        for (; k < 200 && reason === null; k++) {
          await api.runFrames(10);
          reason = g.tooFewAtoms();
        }
        const s = await api.state();
        return { engine: s.engine, changed, asked, held, sim, reason, k, nTrapped: s.nTrapped };
      });
      assert.deepEqual(log.errors, []);
      await page.close();
      return out;
    };
    const worker = await play(undefined);
    const page = await play(NO_WORKER);
    assert.equal(worker.engine, "worker");
    assert.equal(page.engine, "page");
    for (const run of [worker, page]) {
      assert.equal(run.changed, true);
      assert.equal(run.asked, 25);
      assert.equal(run.held, 25);
      assert.equal(run.sim, 25);
      assert.match(run.reason ?? "", /^lose\./, "too few atoms are left to condense");
    }
    for (const key of ["reason", "k", "nTrapped"])
      assert.ok(Object.is(worker[key], page[key]), `${key}: ${worker[key]} vs ${page[key]}`);
  });

  for (const [name, initScript] of [
    ["no Worker at all", NO_WORKER],
    ["a worker that fails", BROKEN_WORKER],
  ]) {
    test(`${name}: the page's own loop plays`, async () => {
      const { page, log } = await openPage(browser, { query: "?seed=2", initScript });
      await page.evaluate(() => window.evapcool.app.play.ready());
      assert.equal((await state(page)).engine, "page");
      await page.keyboard.press("Space");
      await frames(page, 30);
      await page.keyboard.press("ArrowDown");
      const s = await state(page);
      assert.equal(s.paused, false);
      assert.ok(s.time > 0, "the physics advanced");
      assert.equal(s.trapHeight, 395);
      assert.equal(s.nAtoms, 49);
      assert.deepEqual(s.errors, []);
      assert.deepEqual(
        log.errors.filter((e) => !e.includes("physics worker")),
        [],
      );
      await page.close();
    });
  }

  test("keys typed while 10 000 atoms run are drawn within two frames", async () => {
    const { page, log } = await openPage(browser, {
      viewport: { width: 1280, height: 720 },
      query: "?atoms=10000&radius=1&seed=1",
    });
    assert.equal((await state(page)).engine, "worker");
    await page.keyboard.press("Space");
    await frames(page, 10);
    // Each key's effect on what the next frames draw (the drawn controls), checked each frame.
    await page.evaluate(() => {
      const api = window.evapcool;
      window.__answers = [];
      window.addEventListener(
        "keydown",
        (ev) => {
          const before = { ...api.frames().drawn };
          const at = api.frames().frames;
          const answered = (d) =>
            ({
              ArrowDown: d.trapHeight === before.trapHeight - 5,
              ArrowUp: d.trapHeight === before.trapHeight + 5,
              " ": d.paused !== before.paused,
              "+": d.speed === before.speed * 2,
              "-": d.speed === before.speed / 2,
              e: d.energy !== before.energy,
            })[ev.key];
          const check = () => {
            const now = api.frames();
            if (now.drawn.frame > at && answered(now.drawn))
              window.__answers.push({ key: ev.key, frames: now.drawn.frame - at });
            else if (now.frames - at > 30) window.__answers.push({ key: ev.key, frames: Infinity });
            else requestAnimationFrame(check);
          };
          requestAnimationFrame(check);
        },
        { capture: true },
      );
    });
    const keys = ["ArrowDown", "ArrowUp", "+", "-", "e", "e", " ", " "];
    let sent = 0;
    for (let round = 0; round < 3; round++)
      for (const key of keys) {
        await page.keyboard.press(key);
        sent++;
        await frames(page, 3);
      }
    await page.waitForFunction((n) => window.__answers.length === n, sent, { polling: "raf" });
    const answers = await page.evaluate(() => window.__answers);
    const late = answers.filter((a) => !(a.frames <= 2));
    assert.deepEqual(late, [], `answered late: ${JSON.stringify(late)}`);
    const s = await state(page);
    assert.equal(s.paused, false, "still playing");
    assert.ok(s.time > 0);
    assert.deepEqual(s.errors, []);
    assert.deepEqual(log.errors, []);
    await page.close();
  });

  for (const [name, initScript] of [
    ["in the worker", undefined],
    ["on the page", NO_WORKER],
  ]) {
    test(`a throttled device shows the slow-motion line (${name})`, async () => {
      const { page, log, cdp } = await openPage(browser, { query: "?seed=3", initScript });
      await page.evaluate(() => window.evapcool.app.play.ready());
      await page.keyboard.press("Space");
      await frames(page, 20);
      assert.equal((await state(page)).slowNote, null, "real time before the throttle");
      await cdp.send("Emulation.setCPUThrottlingRate", { rate: 40 });
      await page.waitForFunction(() => window.evapcool.stateNow().slowNote !== null, null, {
        polling: "raf",
        timeout: 120_000,
      });
      // The note and what the live region said, at one moment: the pace is measured anew
      // each frame, so two reads apart may see two paces.
      const [s, live] = await page.evaluate(() => [
        window.evapcool.stateNow(),
        document.querySelector("#live").textContent,
      ]);
      await cdp.send("Emulation.setCPUThrottlingRate", { rate: 1 });
      assert.match(s.slowNote, /^slow motion 0\.\d\dx: this device$/);
      assert.ok(s.pace < 0.95, `pace ${s.pace}`);
      assert.equal(s.engine, name === "on the page" ? "page" : "worker");
      assert.equal(live, s.slowNote);
      assert.deepEqual(s.errors, []);
      assert.deepEqual(log.errors, []);
      await page.close();
    });
  }
});
