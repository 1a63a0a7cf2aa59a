// The students of issue 45 in real Chromium, phones of 390 x 844 in English, German and
// Arabic, on a real `evapcool class --department`: each phone opens the server's root (the
// German and Arabic ones with ?lang=), types the class's join code, and lands in the class
// page in its language (lang kept through the redirect); joins with a name; plays a game
// lost for good (the trap dropped to the floor: the challenge counts lost games, so it is
// sent) and a won one. With the names hidden by the lecturer each phone finds its place by
// its entry: its bar says the place the server gives it. One student of two classes is
// herself in both (a token per class). Every button a student taps is at least 44 x 44 CSS
// px; the debrief's close button keeps clear of its title (Arabic too).
// EVAPCOOL_SHOTS=DIR saves the phones' screenshots there.
import assert from "node:assert/strict";
import { existsSync, mkdirSync } from "node:fs";
import { join, resolve } from "node:path";
import { after, before, test } from "node:test";
import {
  departmentClass,
  play,
  postJson,
  closeServerAndBrowser,
  startServerAndBrowser,
  watchErrors,
} from "./class-server.mjs";
import { pythonWithEvapcool } from "./python.mjs";

const PYTHON = pythonWithEvapcool(); // none: this file fails, saying so (python.mjs)
const SHOTS = process.env.EVAPCOOL_SHOTS;
const SEED = 77;
/** The smallest target a finger hits reliably (WCAG 2.5.5), CSS px. */
const TARGET = 44;

let server;
let browser;

before(async () => {
  ({ server, browser } = await startServerAndBrowser(PYTHON, "evapcool-students-", {
    department: true,
  }));
  if (SHOTS) mkdirSync(SHOTS, { recursive: true });
});

after(() => closeServerAndBrowser({ server, browser }));

async function shot(page, name) {
  if (SHOTS) await page.screenshot({ path: join(SHOTS, name) });
}

/** Width and height of every visible element matching `selector`, CSS px. */
const sizes = (page, selector) =>
  page.$$eval(selector, (els) =>
    els
      .filter((e) => e.getClientRects().length > 0)
      .map((e) => {
        const r = e.getBoundingClientRect();
        return { text: e.textContent.trim(), w: r.width, h: r.height };
      }),
  );

function assertTargets(found, where) {
  assert.ok(found.length > 0, `no button on ${where}`);
  for (const b of found)
    assert.ok(b.w >= TARGET && b.h >= TARGET, `${where}: "${b.text}" is ${b.w} x ${b.h}`);
}

/** A phone in its own browser context (its own localStorage). */
async function newPhone(watch) {
  const context = await browser.newContext({
    viewport: { width: 390, height: 844 },
    deviceScaleFactor: 2,
    isMobile: true,
    hasTouch: true,
  });
  return watch(await context.newPage());
}

/** The phone types the join code on the server's root (?lang= as given) and its name. */
async function joinByCode(page, code, lang, name) {
  const query = lang === "en" ? "" : `?lang=${lang}`;
  await page.goto(`${server.base}/${query}`);
  assert.equal(await page.getAttribute("html", "lang"), lang);
  assertTargets(await sizes(page, "button"), `the join page (${lang})`);
  assertTargets(await sizes(page, "input#code"), `the join page's box (${lang})`);
  await shot(page, `students-join-${lang}.png`);
  await page.fill("#code", code.toLowerCase().replace(/(...)/, "$1 "));
  await page.tap("button");
  await page.waitForURL(`${server.base}/c/${code}/${query}`);
  await page.waitForFunction(() => window.evapcool !== undefined);
  await page.waitForSelector("#join input");
  const state = await page.evaluate(() => window.evapcool.stateNow());
  assert.equal(state.locale, lang, "the class page speaks the join page's language");
  assertTargets(await sizes(page, "#join button"), `the name box (${lang})`);
  await page.fill("#join input", name);
  await page.tap("#join button");
  await page.waitForFunction(() => document.getElementById("join") === null);
  await page.waitForFunction(() => window.evapcool.app.play.fixedSeed !== null);
}

/** The student's token as the page saved it for this class. */
const savedToken = (page, api) =>
  page.evaluate(
    (key) => JSON.parse(localStorage.getItem(key)).token,
    `evapcool.class.player:${api}`,
  );

/** Drop the trap to the floor (the slider's Home key) and play: lost for good. */
async function loseGame(page) {
  await page.keyboard.press("r");
  await page.focus(".hit.slider");
  await page.keyboard.press("Home");
  let s = await page.evaluate(() => window.evapcool.state());
  for (let k = 0; k < 60 && s.nTrapped > 1 && !s.won; k++) {
    await page.evaluate(() => window.evapcool.runFrames(25));
    s = await page.evaluate(() => window.evapcool.state());
  }
  assert.equal(s.won, false);
  return s;
}

/** Wait until the class bar says `pattern` (its text in the failure if it never does). */
async function barSays(page, pattern) {
  try {
    await page.waitForFunction(
      (source) => new RegExp(source).test(document.getElementById("classbar").textContent),
      pattern.source,
      { timeout: 60_000 },
    );
  } catch (err) {
    const said = await page.textContent("#classbar");
    const state = await page.evaluate(() => window.evapcool.stateNow());
    await shot(page, "students-failed.png");
    throw new Error(`the bar never said ${pattern}: "${said}" (${JSON.stringify(state)})`, {
      cause: err,
    });
  }
}

const me = async (api, token) =>
  (
    await fetch(`${server.base}${api}/me`, { headers: { authorization: `Bearer ${token}` } })
  ).json();

test("phones in three languages join by code, send a lost and a won game, find their place", async () => {
  const errors = [];
  const watch = watchErrors(errors);
  const { lecturerToken, room, base } = await departmentClass(server);
  const other = await postJson(server, "/api/classes", lecturerToken, { name: "Heat" });
  const api = `${base}/api`;
  const body = { n_atoms: 49, radius: 12, escape: "rim", seed: SEED, lost: true };
  await postJson(server, `${api}/challenge`, lecturerToken, body);
  await postJson(server, `/c/${other.code}/api/challenge`, lecturerToken, body);

  const phones = {};
  const names = { en: "Mia", de: "Jonas", ar: "ليلى" };
  for (const lang of ["en", "de", "ar"]) {
    phones[lang] = await newPhone(watch);
    await joinByCode(phones[lang], room.code, lang, names[lang]);
  }
  // Lost games count: each phone's lost game is sent, verified, and ranked with 0 atoms.
  const lostSaid = { en: /lost game counts too/, de: /verlorene Spiel zählt/, ar: /الخاسرة/ };
  for (const lang of ["en", "de", "ar"]) {
    await loseGame(phones[lang]);
    await barSays(phones[lang], lostSaid[lang]);
  }
  await shot(phones.de, "students-lost-de.png");
  const listed = await (
    await fetch(`${server.base}${api}/entries`, {
      headers: { authorization: `Bearer ${lecturerToken}` },
    })
  ).json();
  assert.deepEqual(
    listed.entries.map((e) => e.score),
    [0, 0, 0],
    "three lost games on the lecturer's list",
  );
  // Then a win each, on ramps to different floors: different places.
  const floors = { en: 100, de: 140, ar: 120 };
  const verified = { en: /Verified/, de: /Geprüft/, ar: /تم التحقق/ };
  for (const lang of ["en", "de", "ar"]) {
    const s = await play(phones[lang], floors[lang]);
    assert.equal(s.won, true, `${lang} won`);
    await phones[lang].waitForFunction(() => window.evapcool.app.classMode.used === 2, null, {
      timeout: 60_000,
    });
    await barSays(phones[lang], verified[lang]);
  }
  // Names hidden: the board has no names, and each phone's place is its entry's.
  await postJson(server, `${api}/debrief`, lecturerToken, { anonymous: true });
  const board = await (await fetch(`${server.base}${api}/leaderboard`)).json();
  assert.ok(board.entries.every((e) => e.name === null));
  const placeSaid = {
    en: (r) => new RegExp(`place ${r} of 3`),
    de: (r) => new RegExp(`Platz ${r} von 3`),
    ar: (r) => new RegExp(`المرتبة ${r} من 3`),
  };
  for (const lang of ["en", "de", "ar"]) {
    const mine = await me(api, await savedToken(phones[lang], api));
    const row = board.entries.find((e) => e.entry === mine.best_entry);
    assert.equal(row.rank, mine.rank, `${lang}: the board's row of its entry`);
    await barSays(phones[lang], placeSaid[lang](mine.rank));
    await shot(phones[lang], `students-place-${lang}.png`);
  }
  // A new win that moves one student up: the others' bars follow by entry, names hidden.
  const before = await me(api, await savedToken(phones.de, api));
  const s = await play(phones.de, 60);
  assert.equal(s.won, true);
  await phones.de.waitForFunction(() => window.evapcool.app.classMode.used === 3, null, {
    timeout: 60_000,
  });
  for (const lang of ["en", "de", "ar"]) {
    const mine = await me(api, await savedToken(phones[lang], api));
    await barSays(phones[lang], placeSaid[lang](mine.rank));
  }
  const after = await me(api, await savedToken(phones.de, api));
  assert.ok(after.best >= before.best);

  // One student of two classes: Mia joins Heat too, then goes back to Optics as herself.
  const mia = phones.en;
  await joinByCode(mia, other.code, "en", "Mia");
  const heatToken = await savedToken(mia, `/c/${other.code}/api`);
  const opticsToken = await savedToken(mia, api);
  assert.notEqual(heatToken, opticsToken);
  await mia.goto(`${server.base}${base}/`);
  await mia.waitForFunction(() => (window.evapcool?.app.classMode?.player ?? null) !== null);
  assert.equal(await mia.$("#join"), null, "no name asked again in her first class");
  assert.equal(await mia.evaluate(() => window.evapcool.app.classMode.player.name), "Mia");
  await barSays(mia, /place \d of 3/);

  // The close: each phone's debrief, its close button clear of its title and 44 px.
  await postJson(server, `${api}/challenge/close`, lecturerToken, {});
  for (const lang of ["en", "de", "ar"]) {
    const page = phones[lang];
    await page.waitForSelector("#class-debrief canvas", { timeout: 30_000 });
    assertTargets(await sizes(page, "#class-debrief button"), `the debrief (${lang})`);
    const [title, close] = await page.$$eval("#class-debrief header > *", (els) =>
      els.map((e) => {
        const r = e.getBoundingClientRect();
        return { left: r.left, right: r.right, top: r.top, bottom: r.bottom };
      }),
    );
    const apart = close.left >= title.right + 8 || close.right <= title.left - 8;
    assert.ok(
      apart,
      `${lang}: the close button touches the title ${JSON.stringify([title, close])}`,
    );
    if (lang === "ar") assert.ok(close.right <= title.left - 8, "Arabic: close on the left");
    await shot(page, `students-debrief-${lang}.png`);
  }
  assert.deepEqual(errors, []);
});
