// The debrief after a class competition (issue 36) in real Chromium against a real
// `evapcool class`: 30 students' games with different ramps (one played on a phone, 29 sent
// as codes of ramp games: tests/classhelp.py ramps), the challenge closed. The phone's page
// shows its own path over the class's cloud and its place, and the path the server keeps
// for its game equals the one its own page drew, point for point. The projector (1920 x
// 1080) shows 30 curves, the best on top; the archetypes point at the right entries and
// picking one highlights it and plays its replay; two games side by side stay in step to
// the last frame, both their replays (the game page in two frames) and their numbers;
// anonymous mode shows no name anywhere, in the page nor in the JSON it
// receives. EVAPCOOL_SHOTS=DIR saves the projector's debrief there.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdirSync, readdirSync } from "node:fs";
import { join, resolve } from "node:path";
import { after, before, test } from "node:test";
import { closeServerAndBrowser, startServerAndBrowser } from "./class-server.mjs";
import { pythonWithEvapcool } from "./python.mjs";

const PYTHON = pythonWithEvapcool(); // none: this file fails, saying so (python.mjs)
const ROOT = resolve(import.meta.dirname, "../../..");
const SEED = 77;
const STUDENTS = 30;
const SHOTS = process.env.EVAPCOOL_SHOTS;
/** Every language the catalogs speak. */
const LOCALES = readdirSync(join(ROOT, "src/evapcool/locales"))
  .map((f) => f.replace(/\.json$/, ""))
  .sort();

let server;
let browser;

before(async () => {
  // `evapcool class` on a fresh data file (class-server.mjs)
  ({ server, browser } = await startServerAndBrowser(PYTHON, "evapcool-debrief-", { tries: 300 }));
});

after(() => closeServerAndBrowser({ server, browser }));

const lecturer = () => ({
  authorization: `Bearer ${server.token}`,
  "content-type": "application/json",
});

async function api(path, { body, headers = {} } = {}) {
  const init =
    body === undefined ? { headers } : { method: "POST", headers, body: JSON.stringify(body) };
  const res = await fetch(server.base + path, init).catch((err) => {
    throw new Error(`${path}: ${err.cause ?? err}; the server said: ${server.output()}`);
  });
  const text = await res.text();
  assert.ok(res.ok, `${path}: ${res.status} ${text}`);
  return JSON.parse(text);
}

/** Records every server message a page receives (JSON answers and the stream's events). */
function recordReceived(page) {
  page.received = [];
  page.on("response", async (r) => {
    if (!r.url().includes("/api/") || r.url().includes("/api/stream")) return;
    try {
      page.received.push(await r.text());
    } catch {
      /* a redirect or an aborted request: no body */
    }
  });
  return page.addInitScript(() => {
    const Original = window.EventSource;
    window.__events = [];
    window.EventSource = class extends Original {
      constructor(...args) {
        super(...args);
        this.addEventListener("message", (e) => window.__events.push(e.data));
      }
    };
  });
}

/** A phone (touch, 390 x 844) on the students' link, joined as `name`. */
async function phone(name) {
  const context = await browser.newContext({
    viewport: { width: 390, height: 844 },
    deviceScaleFactor: 2,
    isMobile: true,
    hasTouch: true,
  });
  const page = await context.newPage();
  page.errors = [];
  page.on("pageerror", (e) => page.errors.push(e.message));
  await recordReceived(page);
  await page.goto(`${server.base}/`);
  await page.waitForSelector("#join input");
  await page.fill("#join input", name);
  await page.tap("#join button");
  await page.waitForFunction(() => document.getElementById("join") === null);
  await page.waitForFunction(() => window.evapcool.app.play.fixedSeed !== null);
  return page;
}

/** The physics time of the live path chart's last point. */
const lastDrawn = (page) => page.evaluate(() => window.evapcool.app.charts.path.time.at(-1) ?? -1);

/** Pause, then `n` single frames (S), each drawn before the next: whole frames in the
 * page's live path chart; then play on. */
async function stepFrames(page, n) {
  await page.keyboard.press("Space");
  for (let i = 0; i < n; i++) {
    const before = await lastDrawn(page);
    await page.keyboard.press("s");
    await page.waitForFunction(
      (b) => (window.evapcool.app.charts.path.time.at(-1) ?? -1) > b,
      before,
    );
  }
  await page.keyboard.press("Space");
}

/** Play one game with a ramp down to `floor`, one frame drawn at a time (a stretch frame
 * by frame); its state. */
async function play(page, floor) {
  await page.keyboard.press("r");
  let s = await page.evaluate(() => window.evapcool.state());
  for (let k = 0; k < 300 && s.wonAt === null; k++) {
    if (k === 8) await stepFrames(page, 30);
    if (s.trapHeight > floor) await page.keyboard.press("ArrowDown");
    await page.evaluate(() => window.evapcool.runFrames(25));
    s = await page.evaluate(() => window.evapcool.state());
  }
  return s;
}

const roundT = (t) => Number(t.toExponential(4));

test(
  "the class's debrief: the student's own path, the projector's curves, archetypes, a pair, anonymity",
  { timeout: 600_000 },
  async () => {
    await api("/api/challenge", {
      body: { n_atoms: 49, radius: 12, escape: "rim", seed: SEED, lost: true, max_frames: 6000 },
      headers: lecturer(),
    });
    // One student plays on a phone; the page sends the won game's code itself.
    const ada = await phone("Ada Phone");
    const played = await play(ada, 90);
    assert.notEqual(played.wonAt, null, "the phone's ramp wins");
    await ada.waitForFunction(
      () => /verified/i.test(document.getElementById("classbar").textContent),
      null,
      { timeout: 60_000 },
    );
    // 29 more, as codes of ramp games (two of them never win: the challenge takes lost games).
    const games = JSON.parse(
      execFileSync(
        PYTHON,
        [join(ROOT, "tests/classhelp.py"), "ramps", String(STUDENTS - 1), String(SEED)],
        {
          env: { ...process.env },
          maxBuffer: 64 << 20,
        },
      ),
    );
    const names = ["Ada Phone"];
    for (const [k, g] of games.entries()) {
      const name = `Learner-${k + 1}`;
      names.push(name);
      const { token } = await api("/api/join", {
        body: { name },
        headers: { "content-type": "application/json" },
      });
      const got = await api("/api/submit", {
        body: { challenge: (await api("/api/leaderboard")).challenge, code: g.code },
        headers: { authorization: `Bearer ${token}`, "content-type": "application/json" },
      });
      assert.equal(got.score, g.score);
    }
    // While open: the lecturer's early look on their own page; the projector shows none.
    const early = await browser.newContext({ viewport: { width: 1280, height: 900 } });
    const lecturerPage = await early.newPage();
    await lecturerPage.goto(`${server.base}/lecturer?token=${server.token}`);
    await lecturerPage.click("#debrief-show");
    await lecturerPage.waitForFunction(
      () => document.getElementById("debrief-paths")?.dataset.curves,
    );
    const earlyCurves = await curvesOf(lecturerPage);
    assert.equal(earlyCurves.length, STUDENTS);
    assert.match(await lecturerPage.textContent("#debrief-early"), /Only you see this/);
    const openProjector = await browser.newPage({ viewport: { width: 1920, height: 1080 } });
    await openProjector.goto(`${server.base}/projector?key=${await projectorKey()}`);
    await openProjector.waitForFunction(() => document.querySelectorAll("#board tr").length > 1);
    assert.equal(await openProjector.isVisible("#debrief"), false, "no debrief while open");
    await openProjector.close();
    await early.close();
    await api("/api/challenge/close", { body: {}, headers: lecturer() });

    // The phone: its own path over the class's cloud, and its place.
    await ada.waitForSelector("#class-debrief canvas#debrief-paths", { timeout: 10_000 });
    const doc = await api("/api/debrief");
    assert.equal(doc.games.length, STUDENTS);
    const mine = doc.games.find((g) => g.name === "Ada Phone");
    await ada
      .waitForFunction(() => document.getElementById("debrief-paths").dataset.curves, null, {
        timeout: 10_000,
      })
      .catch(() => assert.fail(`no curves drawn: ${ada.errors.join("; ")}`));
    const seen = await ada.evaluate(() => ({
      you: document.getElementById("debrief-you").textContent,
      curves: document.getElementById("debrief-paths").dataset.curves.split(",").map(Number),
    }));
    assert.match(seen.you, new RegExp(`place ${mine.rank} of ${STUDENTS}`));
    assert.equal(seen.curves.length, STUDENTS);
    assert.equal(seen.curves.at(-1), mine.entry, "the student's own path is drawn over the cloud");
    // The server's path of the phone's game is the one the phone's page drew, point for point:
    // the debrief's (the page replays its own game) and the live chart's at whole frames.
    const own = await ada.evaluate(() => window.evapcool.app.classMode.ownPath);
    assert.ok(mine.path.k.length > 100, "a few hundred points");
    assert.deepEqual(own, mine.path);
    const other = doc.games.find((g) => g.entry !== mine.entry).entry;
    await api("/api/debrief", { body: { pair: [mine.entry, other] }, headers: lecturer() });
    const full = (await api("/api/debrief/pair")).games[0].path;
    assert.deepEqual(full.k, [...Array(mine.path.frames + 1).keys()]);
    const live = await ada.evaluate(() => {
      const p = window.evapcool.app.charts.path;
      return { n: p.n, t: p.t, time: p.time };
    });
    let whole = 0;
    for (const [i, k] of live.time.entries()) {
      if (!Number.isInteger(k)) continue;
      whole += 1;
      assert.equal(live.n[i], full.n[k], `N at frame ${k}`);
      assert.equal(roundT(live.t[i]), full.t[k], `T at frame ${k}`);
    }
    assert.ok(whole >= 30, `the live chart drew ${whole} whole frames`);
    assert.deepEqual(ada.errors, []);
    await shot(ada, "class-debrief-phone.png");
    await checkProjector(doc, names, games, ada);
  },
);

/** The projector's key, from the link on the lecturer's page. */
async function projectorKey() {
  const headers = { authorization: `Bearer ${server.token}` }; // a link's ?token= redirects
  const page = await (await fetch(`${server.base}/lecturer`, { headers })).text();
  return /href="\/projector\?key=([0-9a-f]+)"/.exec(page)[1];
}

async function projectorPage(key, locale = "en") {
  const context = await browser.newContext({
    viewport: { width: 1920, height: 1080 },
    extraHTTPHeaders: { "accept-language": locale },
  });
  const page = await context.newPage();
  page.errors = [];
  page.on("pageerror", (e) => page.errors.push(e.message));
  await recordReceived(page);
  await page.goto(`${server.base}/projector?key=${key}`);
  await page.waitForFunction(() => document.getElementById("debrief-paths")?.dataset.curves);
  return page;
}

const curvesOf = (page) =>
  page.evaluate(() =>
    document.getElementById("debrief-paths").dataset.curves.split(",").map(Number),
  );

async function shot(page, name) {
  if (!SHOTS) return;
  mkdirSync(SHOTS, { recursive: true });
  await page.screenshot({ path: join(SHOTS, name) });
}

/** The projector's part: curves, sizes, archetypes picked, a pair in step, anonymity. */
async function checkProjector(doc, names, games, ada) {
  // No pair yet (the phone's part set one): two replays in step take the charts' place.
  await api("/api/debrief", { body: { pair: null }, headers: lecturer() });
  const key = await projectorKey();
  const projector = await projectorPage(key);
  const curves = await curvesOf(projector);
  assert.equal(curves.length, STUDENTS, "one curve a student");
  assert.equal(curves.at(-1), doc.archetypes.best, "the best game on top");
  assert.equal(doc.games[0].entry, doc.archetypes.best);
  // The archetypes, from the games' own results.
  const won = doc.games.filter((g) => g.won);
  const by = (key) => (a, b) => key(a) - key(b) || a.entry - b.entry;
  assert.equal(doc.archetypes.fastest, [...won].sort(by((g) => g.frames))[0].entry);
  const mostLost = [...won].sort((a, b) => a.score - b.score || b.frames - a.frames)[0];
  assert.equal(doc.archetypes.most_lost, mostLost.entry);
  const lostNames = games.map((g, k) => [g, names[k + 1]]).filter(([g]) => !g.won);
  assert.equal(lostNames.length, 1, "the last ramp never wins");
  const neverWon = doc.games.find((g) => g.entry === doc.archetypes.never_won);
  assert.equal(neverWon.name, lostNames[0][1], "the game that never won");
  // Readable at the back of the hall in every language: no word under 24 px, none cut off.
  for (const locale of LOCALES) {
    const page = locale === "en" ? projector : await projectorPage(key, locale);
    assert.equal(await page.getAttribute("html", "lang"), locale);
    for (const id of ["debrief-paths", "debrief-heights"]) {
      const d = await page.evaluate((i) => ({ ...document.getElementById(i).dataset }), id);
      assert.ok(Number(d.minText) >= 24, `${locale} ${id}: smallest word ${d.minText} px`);
      assert.equal(d.outside, "", `${locale} ${id}: words outside the chart`);
    }
    if (locale !== "en") {
      if (locale === "ja" || locale === "ar") await shot(page, `class-debrief-${locale}.png`);
      await page.context().close();
    }
  }
  const described = await projector.textContent("#debrief-describe");
  assert.ok(described.includes(doc.games[0].name), described);
  await shot(projector, "class-debrief-projector.png");

  // The lecturer picks each archetype: highlighted on top, named, its replay playing.
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const lecturerPage = await context.newPage();
  await lecturerPage.goto(`${server.base}/lecturer?token=${server.token}`);
  await lecturerPage.waitForSelector("#debrief-picks button");
  const kinds = await lecturerPage.$$eval("#debrief-picks button", (bs) =>
    bs.map((b) => [b.dataset.kind, Number(b.dataset.entry)]),
  );
  assert.deepEqual(
    kinds.map(([k]) => k),
    ["best", "fastest", "most_lost", "never_won"],
  );
  for (const [kind, entry] of kinds) {
    assert.equal(entry, doc.archetypes[kind], kind);
    await lecturerPage.click(`#debrief-picks button[data-kind="${kind}"]`);
    await projector.waitForFunction(
      (e) =>
        document.getElementById("debrief-paths").dataset.curves.split(",").at(-1) === String(e),
      entry,
    );
    const game = doc.games.find((g) => g.entry === entry);
    await projector.waitForFunction(
      (n) => document.getElementById("debrief-pick").textContent.startsWith(n + ":"),
      game.name,
    );
    await projector.waitForFunction(() =>
      document.getElementById("replay-frame").src.includes("replay="),
    );
    // The replay beside the paths: both in view, the paths' words still large.
    const box = await projector.evaluate(() => {
      const r = document.getElementById("replay-frame").getBoundingClientRect();
      return {
        w: r.width,
        h: r.height,
        min: document.getElementById("debrief-paths").dataset.minText,
      };
    });
    assert.ok(box.h >= 400 && box.w >= 600, `the replay's frame ${box.w} x ${box.h}`);
    assert.ok(Number(box.min) >= 24, `the paths' smallest word beside a replay: ${box.min} px`);
  }
  await shot(projector, "class-debrief-picked.png");
  await shot(lecturerPage, "class-debrief-lecturer.png");

  // Two games side by side: their replays (the game page in two frames) and their
  // numbers, the same frame in both at every moment, to the last of the longer game.
  // The fastest win and the best (or, were they as long, the slowest win): two lengths.
  const framesOf = (e) => doc.games.find((g) => g.entry === e).frames;
  const a = doc.archetypes.fastest;
  const slowest = [...won].sort(by((g) => -g.frames))[0].entry;
  const b = framesOf(doc.archetypes.best) !== framesOf(a) ? doc.archetypes.best : slowest;
  await lecturerPage.selectOption("#debrief-pair-a", String(a));
  await lecturerPage.selectOption("#debrief-pair-b", String(b));
  await lecturerPage.click("#debrief-pair-go");
  await projector.waitForFunction(() => !document.getElementById("debrief-pair").hidden);
  await projector.waitForFunction(() => !document.getElementById("debrief-replays").hidden);
  const frames = [a, b].map(framesOf);
  const last = Math.max(...frames);
  assert.notEqual(frames[0], frames[1], "two games of different lengths");
  // One look at everything in one task: what each replay's page shows, and the numbers.
  const look = () =>
    projector.evaluate(() => {
      const views = [...document.querySelectorAll("#debrief-replays iframe")].map((f) => {
        const r = f.getBoundingClientRect();
        const api = f.contentWindow.evapcool;
        const g = api?.app.game;
        const state = api?.stateNow();
        return {
          src: f.src,
          box: [r.left, r.top, r.width, r.height],
          frame: g ? Math.round(g.sim.time) : null,
          paused: g?.paused,
          won: state?.won,
          trapped: state?.nTrapped,
        };
      });
      const d = document.getElementById("debrief-pair").dataset;
      return { views, numbers: d.frames ?? "", frame: Number(d.frame) };
    });
  let seen = 0;
  let shotTaken = false;
  let now = await look();
  assert.equal(now.views.length, 2, "two replays");
  const [left, right] = now.views.map((v) => v.box);
  assert.ok(left[0] + left[2] <= right[0] && left[2] >= 300 && left[3] >= 300, `${left} ${right}`);
  assert.ok(Math.abs(left[1] - right[1]) < 1, "side by side");
  assert.ok(now.views.every((v) => v.src.includes("replay=")));
  for (let k = 0; k < 20000; k++) {
    now = await look();
    const shown = now.views.map((v) => v.frame);
    if (shown.every((f) => f !== null)) {
      // The shared frame: the longer game's; the shorter holds its last frame.
      const at = Math.max(...shown);
      assert.deepEqual(
        shown,
        frames.map((f) => Math.min(at, f)),
        `in step at frame ${at}`,
      );
      assert.equal(now.numbers, shown.join(","), `the numbers at frame ${at}`);
      assert.ok(
        now.views.every((v) => v.paused),
        "the projector's clock, not the page's",
      );
      seen += 1;
      if (at > 60 && !shotTaken) {
        shotTaken = true;
        await shot(projector, "class-debrief-pair.png");
      }
      if (at >= last) break;
    }
    await new Promise((r) => setTimeout(r, 40));
  }
  assert.deepEqual(
    now.views.map((v) => v.frame),
    frames,
    "each game at its own last frame",
  );
  const pairWon = [a, b].map((e) => doc.games.find((g) => g.entry === e).won);
  assert.deepEqual(
    now.views.map((v) => v.won),
    pairWon,
    "each replay's own end",
  );
  assert.equal(now.numbers, frames.join(","), "the numbers at each game's last frame");
  assert.ok(seen > 10, `${seen} looks`);
  // The end holds: no replay starts again by itself (alone, one would after 6 s).
  await new Promise((r) => setTimeout(r, 7000));
  assert.deepEqual(
    (await look()).views.map((v) => v.frame),
    frames,
  );

  // Anonymous: no name in a projector's page nor in anything it receives.
  await lecturerPage.click("#debrief-anonymous");
  // The pair still shows: its line names its two games, by place (issue 45).
  const pairLine = () =>
    /^Side by side: Student \d+ · Student \d+$/.test(
      document.getElementById("debrief-pick").textContent,
    );
  await projector.waitForFunction(pairLine);
  const fresh = await projectorPage(key);
  await fresh.waitForFunction(pairLine);
  for (const page of [projector, fresh]) {
    const text = await page.evaluate(() => document.body.innerText);
    const events = await page.evaluate(() => window.__events);
    const after = page === fresh ? [...page.received, ...events] : [];
    for (const name of names) {
      assert.ok(!text.includes(name), `${name} on the anonymous projector`);
      for (const got of after) assert.ok(!got.includes(name), `${name} in ${got.slice(0, 80)}`);
    }
    assert.deepEqual(page.errors, []);
  }
  assert.ok(
    fresh.received.some((r) => r.includes('"games"')),
    "the debrief's JSON was seen",
  );
  await shot(fresh, "class-debrief-anonymous.png");
  // The phone fetches the debrief anew, without the others' names.
  await ada.waitForFunction(() => document.getElementById("class-debrief") !== null);
  const anonymousSent = () =>
    [...ada.received]
      .reverse()
      .find((r) => r.includes('"games"') && r.includes('"anonymous":true'));
  for (let k = 0; k < 100 && !anonymousSent(); k++) await new Promise((r) => setTimeout(r, 100));
  const phoneGot = anonymousSent();
  assert.ok(phoneGot, "the phone fetched the anonymous debrief");
  for (const name of names.slice(1)) assert.ok(!phoneGot.includes(name), `${name} sent to a phone`);
}
