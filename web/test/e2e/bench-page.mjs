// `npm run bench:page`: the browser edition's figures in headless Chromium (medians):
// time to the first frame of the file, frame work (physics + drawing) for 49 atoms,
// thousands of atoms, and the page's size; then (issue 24) 10 000 atoms of radius 1 played
// for BENCH_PLAY_SECONDS (20) with the physics in the worker and, interleaved, on the page,
// and (issue 47) 15 000 atoms, the most of radius 1 the cup holds, and 20 000 of radius 0.85,
// in the worker (BENCH_ATOMS=20000 plays only those):
// animation frames per second, the worst frame, key press to drawn effect in frames, the
// physics' pace against real time; 49 atoms' physics ms per frame in the worker.
// Build first (npm run build).
import { statSync } from "node:fs";
import { launch, openPage, PAGE } from "./browser.mjs";

const seconds = Number(process.env.BENCH_SECONDS ?? 10);
const playSeconds = Number(process.env.BENCH_PLAY_SECONDS ?? 20);
/** BENCH_ATOMS=20000 (a comma list): only these counts are played (all if unset). */
const only = process.env.BENCH_ATOMS?.split(",").map(Number);
const NO_WORKER = () => {
  delete window.Worker;
};
const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
};

const browser = await launch();
try {
  const first = [];
  for (let k = 0; k < 7; k++) {
    const { page } = await openPage(browser, { query: `?seed=${k}` });
    await page.waitForFunction(
      () => performance.getEntriesByName("evapcool-first-frame").length > 0,
    );
    first.push(
      await page.evaluate(() => performance.getEntriesByName("evapcool-first-frame")[0].startTime),
    );
    await page.close();
  }
  console.log(`page size: ${statSync(PAGE).size} bytes`);
  console.log(
    `time to first frame (file://, 7 loads): median ${median(first).toFixed(0)} ms (${first.map((t) => t.toFixed(0)).join(", ")})`,
  );
  for (let round = 0; round < 2; round++) {
    for (const [atoms, radius, where, initScript] of [
      [10000, 1, "worker", undefined],
      [10000, 1, "page", NO_WORKER],
      [15000, 1, "worker", undefined], // issue 47: 20 000 of radius 1 do not fit (15 085 do)
      [20000, 0.85, "worker", undefined], // issue 47's 20 000: no settings' radius (1-20) holds them
    ].filter(([atoms]) => !only || only.includes(atoms))) {
      const query = `?atoms=${atoms}&radius=${radius}&seed=1`;
      const r = await play(browser, query, initScript, playSeconds);
      console.log(
        `${atoms} atoms (radius ${radius}), physics on the ${r.engine} (asked: ${where}), 1280 x 720, ${playSeconds} s after Space: ` +
          `${r.fps.toFixed(1)} animation frames/s, worst frame ${r.worstMs.toFixed(1)} ms, ` +
          `frames over 50 ms: ${r.over50}, key to drawn effect: median ${r.keyMedian} frames, worst ${r.keyWorst} (${r.keys} keys), ` +
          `key to the physics' trap: median ${r.physicsKeyMedian} frames, worst ${r.physicsKeyWorst}, ` +
          `pace ${r.pace.toFixed(2)} of real time (${r.playS.toFixed(1)} s played; ${r.slowSeconds} of ${r.seconds} s below 0.95), ` +
          `slow-motion line on ${(100 * r.notedShare).toFixed(0)} % of frames, at the end: ${r.note ?? "none"}` +
          (r.engine === "worker"
            ? `, worker physics ${r.physicsPerFrame.toFixed(1)} ms per physics frame`
            : "") +
          (r.errors.length ? `, errors: ${r.errors.join("; ")}` : ""),
      );
    }
  }
  {
    // 49 atoms: 3000 physics frames at once in the worker, 7 times (its clock is coarse).
    const { page } = await openPage(browser, { query: "?seed=1" });
    await page.evaluate(() => window.evapcool.app.stop());
    const ms = [];
    for (let k = 0; k < 7; k++) {
      await page.evaluate(() => window.evapcool.physicsFrames(3000));
      ms.push((await page.evaluate(() => window.evapcool.stateNow().physicsMs)) / 3000);
    }
    const s = await page.evaluate(() => window.evapcool.stateNow());
    console.log(
      `49 atoms, physics in the ${s.engine}: median ${median(ms).toFixed(4)} ms per physics frame ` +
        `(7 runs of 3000 frames: ${ms.map((m) => m.toFixed(4)).join(", ")}; ${s.nTrapped} trapped at the end)`,
    );
    await page.close();
  }
  for (const [atoms, radius, scale] of [
    [49, 12, 1],
    [49, 12, 2],
    [5000, 1, 1],
    [10000, 1, 1],
  ]) {
    const { page, log } = await openPage(browser, {
      viewport: { width: 1280, height: 720 },
      scale,
      query: `?atoms=${atoms}&radius=${radius}&seed=1`,
    });
    await page.keyboard.press("Space");
    await page.waitForTimeout(500);
    await page.evaluate(() => window.evapcool.resetStats());
    await page.waitForTimeout(seconds * 1000);
    const st = await page.evaluate(() => window.evapcool.frameStats(100000));
    const s = await page.evaluate(() => window.evapcool.state());
    console.log(
      `${atoms} atoms (radius ${radius}), 1280 x 720 at ${scale}x, ${seconds} s: frame work median ${st.medianMs.toFixed(2)} ms, ` +
        `p95 ${st.p95Ms.toFixed(2)} ms, ${st.fps.toFixed(1)} frames/s shown, ` +
        `play ${(s.time / 30).toFixed(1)} s of ${seconds + 0.5} s, ${s.nTrapped} trapped` +
        (log.errors.length ? `, errors: ${log.errors.join("; ")}` : ""),
    );
    await page.close();
  }
} finally {
  await browser.close();
}

/**
 * Play `query` for `secs` after Space: every animation frame's interval, keys pressed (Down
 * and Up in turn, twice a second) and the frames until each is drawn and until the
 * physics has it, the worker's physics ms and the pace against real time.
 */
async function play(browser, query, initScript, secs) {
  const { page, log } = await openPage(browser, {
    viewport: { width: 1280, height: 720 },
    query,
    initScript,
  });
  await page.evaluate(() => window.evapcool.app.play.ready());
  await page.keyboard.press("Space");
  await page.waitForTimeout(500);
  await page.evaluate(() => {
    const api = window.evapcool;
    const rec = (window.__bench = {
      gaps: [],
      keys: [],
      physics: [],
      start: null,
      samples: [],
      noted: 0,
    });
    let last = null;
    let lastTime = api.stateNow().time;
    const frame = (now) => {
      if (last !== null) rec.gaps.push(now - last);
      last = now;
      const s = api.stateNow();
      if (s.time !== lastTime) rec.physics.push([s.physicsMs, s.time - lastTime]);
      rec.samples.push([now, s.time]);
      if (s.slowNote !== null) rec.noted++;
      lastTime = s.time;
      if (!rec.stopped) requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
    rec.start = { wall: performance.now(), time: lastTime };
    addEventListener(
      "keydown",
      (ev) => {
        const at = api.frames().frames;
        const want = api.app.game.trapHeight + (ev.key === "ArrowDown" ? -5 : 5);
        const entry = { drawn: null, physics: null };
        rec.keys.push(entry);
        const check = () => {
          const now = api.frames();
          if (entry.drawn === null && now.drawn.frame > at && now.drawn.trapHeight === want)
            entry.drawn = now.drawn.frame - at;
          if (entry.physics === null && api.app.game.sim.trapHeight === want)
            entry.physics = now.frames - at;
          if ((entry.drawn === null || entry.physics === null) && now.frames - at < 600)
            requestAnimationFrame(check);
        };
        requestAnimationFrame(check);
      },
      { capture: true },
    );
  });
  const keysAt = Date.now();
  for (let k = 0; Date.now() - keysAt < secs * 1000; k++) {
    await page.keyboard.press(k % 2 ? "ArrowUp" : "ArrowDown");
    await page.waitForTimeout(500);
  }
  const r = await page.evaluate(() => {
    const rec = window.__bench;
    rec.stopped = true;
    const s = window.evapcool.stateNow();
    const wall = (performance.now() - rec.start.wall) / 1000;
    return { rec, s, wall };
  });
  await page.close();
  const gaps = r.rec.gaps;
  const drawn = r.rec.keys.map((k) => k.drawn ?? Infinity);
  const phys = r.rec.keys.map((k) => k.physics ?? Infinity);
  const physMs = r.rec.physics.map(([ms]) => ms).filter((x) => Number.isFinite(x));
  const physFrames = r.rec.physics.reduce((a, [, d]) => a + d, 0);
  const playS = (r.s.time - r.rec.start.time) / 30;
  // Seconds of wall clock whose pace was below 0.95 (where the line should show).
  let slowSeconds = 0;
  let seconds = 0;
  const sm = r.rec.samples;
  for (let a = 0, b = 0; b < sm.length; b++) {
    if (sm[b][0] - sm[a][0] < 1000) continue;
    seconds++;
    if ((sm[b][1] - sm[a][1]) / 30 / ((sm[b][0] - sm[a][0]) / 1000) / r.s.speed < 0.95)
      slowSeconds++;
    a = b;
  }
  return {
    engine: r.s.engine,
    fps: gaps.length / (gaps.reduce((a, b) => a + b, 0) / 1000),
    worstMs: Math.max(...gaps),
    over50: gaps.filter((g) => g > 50).length,
    keys: drawn.length,
    keyMedian: median(drawn),
    keyWorst: Math.max(...drawn),
    physicsKeyMedian: median(phys),
    physicsKeyWorst: Math.max(...phys),
    playS,
    pace: playS / (r.wall * r.s.speed),
    note: r.s.slowNote,
    notedShare: r.rec.noted / Math.max(1, sm.length),
    slowSeconds,
    seconds,
    physicsPerFrame: physFrames > 0 ? physMs.reduce((a, b) => a + b, 0) / physFrames : NaN,
    errors: log.errors,
  };
}
