// The console at a phone's size and right to left (issue 45), in real Chromium against a
// real `evapcool class --department`: the administrator's page, the lecturer's list of
// classes (each past round's time in the reader's language and time zone, its links to the
// projector and its exports), the class's lecturer page, the projector (live, and a past
// round reopened: its board, paged, and its podium) and the join page, each at 390 x 844 in
// English and Arabic: no sideways scrolling, every button at least 44 x 44 CSS px, nothing
// cut or off the screen, dir="rtl" in Arabic. EVAPCOOL_SHOTS=DIR saves the screenshots.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdirSync } from "node:fs";
import { join, resolve } from "node:path";
import { after, before, test } from "node:test";
import {
  departmentClass,
  postJson,
  closeServerAndBrowser,
  startServerAndBrowser,
  watchErrors,
} from "./class-server.mjs";
import { pythonWithEvapcool } from "./python.mjs";

const PYTHON = pythonWithEvapcool(); // none: this file fails, saying so (python.mjs)
const ROOT = resolve(import.meta.dirname, "../../..");
const SEED = 77;
const PHONE = { width: 390, height: 844 };
const SHOTS = process.env.EVAPCOOL_SHOTS;
/** The names of the first round's students (Arabic ones too: the board's text runs both ways). */
const NAMES = [
  "Mia",
  "Finn",
  "ليلى",
  "Priya",
  "Elif",
  "عمر",
  "Konstantinos",
  "Sofía",
  "Kenji",
  "Ana",
];
/** Weekday, day, month and minute, as times.ts writes them. */
const SHORT = {
  weekday: "short",
  day: "numeric",
  month: "short",
  hour: "2-digit",
  minute: "2-digit",
};

let server;
let browser;
/** The department's class with a past round (closed) and an open one. */
let world;

before(async () => {
  ({ server, browser } = await startServerAndBrowser(PYTHON, "evapcool-console-phone-", {
    department: true,
  }));
  world = await twoRounds();
});

after(() => closeServerAndBrowser({ server, browser }));

async function shot(page, name) {
  if (!SHOTS) return;
  mkdirSync(SHOTS, { recursive: true });
  await page.screenshot({ path: join(SHOTS, name), fullPage: true });
}

/** Ada's class Optics: round one (a time window, ten students' games) closed, round two
 * open with three games. */
async function twoRounds() {
  const { lecturerToken, room, base } = await departmentClass(server);
  const lecturer = (path, body) => postJson(server, base + path, lecturerToken, body);
  const settings = { n_atoms: 49, radius: 12, escape: "rim", seed: SEED };
  const first = await lecturer("/api/challenge", { ...settings, minutes: 30 });
  const games = JSON.parse(
    execFileSync(
      PYTHON,
      [join(ROOT, "tests/classhelp.py"), "ramps", String(NAMES.length + 3), "77"],
      {
        maxBuffer: 64 << 20,
      },
    ),
  );
  const tokens = [];
  for (const [k, g] of games.slice(0, NAMES.length).entries()) {
    const joined = await fetch(`${server.base}${base}/api/join`, {
      method: "POST",
      headers: { "content-type": "application/json" },
      body: JSON.stringify({ name: NAMES[k] }),
    }).then((r) => r.json());
    tokens.push(joined.token);
    await postJson(server, `${base}/api/submit`, joined.token, {
      challenge: first.id,
      code: g.code,
    });
  }
  await lecturer("/api/challenge/close", {});
  const board = await (await fetch(`${server.base}${base}/api/leaderboard`)).json();
  // Round two, open: three of them have played it (the lecturer's table has rows).
  const second = await lecturer("/api/challenge", settings);
  for (const k of [0, 1, 2])
    await postJson(server, `${base}/api/submit`, tokens[k], {
      challenge: second.id,
      code: games[NAMES.length + k].code, // a game of its own: a copy is refused
    });
  const page = await (
    await fetch(`${server.base}${base}/lecturer`, {
      headers: { authorization: `Bearer ${lecturerToken}` },
    })
  ).text();
  const projector = /href="([^"]*\/projector\?key=[0-9a-f]+)"/.exec(page)[1];
  return { lecturerToken, room, base, first, second, board, projector };
}

/** A phone's browser in `lang` (its Accept-Language too), in Tokyo's time zone. */
async function phone(lang, errors) {
  const context = await browser.newContext({
    viewport: PHONE,
    isMobile: true,
    hasTouch: true,
    locale: lang === "ar" ? "ar" : "en-GB",
    timezoneId: "Asia/Tokyo",
  });
  return { context, page: watchErrors(errors)(await context.newPage()) };
}

/**
 * What is wrong with the page as a phone shows it: sideways scrolling, buttons under 44 x 44
 * CSS px, text cut by its box or an ellipsis, elements off the screen's sides, the wrong
 * direction.
 */
function problems(page, direction) {
  return page.evaluate((dir) => {
    const out = [];
    const name = (el) =>
      el.id
        ? `#${el.id}`
        : `${el.tagName.toLowerCase()}.${el.className}:"${el.textContent.trim().slice(0, 24)}"`;
    const width = document.documentElement.clientWidth;
    if (document.documentElement.scrollWidth > width + 1)
      out.push(`scrolls sideways: ${document.documentElement.scrollWidth} > ${width}`);
    if (document.documentElement.dir !== dir) out.push(`dir=${document.documentElement.dir}`);
    const shown = (el) => el.checkVisibility({ visibilityProperty: true, opacityProperty: true });
    // A checkbox is tapped through its label too: its target is the two together.
    const target = (el) => {
      const rects = [el, ...(el.labels ?? [])].map((x) => x.getBoundingClientRect());
      const [l, t] = [Math.min(...rects.map((r) => r.left)), Math.min(...rects.map((r) => r.top))];
      const [r, b] = [
        Math.max(...rects.map((x) => x.right)),
        Math.max(...rects.map((x) => x.bottom)),
      ];
      return el.type === "checkbox" ? { width: r - l, height: b - t } : rects[0];
    };
    const taps = "button, a.button, #crumbs a, select, input:not([type=hidden])";
    for (const el of document.querySelectorAll(taps)) {
      if (!shown(el)) continue;
      const r = target(el);
      if (r.width < 44 - 0.01 || r.height < 44 - 0.01)
        out.push(`small: ${name(el)} ${r.width.toFixed(1)} x ${r.height.toFixed(1)}`);
    }
    // Inside a box that scrolls sideways on purpose (a wide table) it can be reached.
    const inScroller = (el) => {
      for (let a = el.parentElement; a && a !== document.body; a = a.parentElement) {
        const o = getComputedStyle(a).overflowX;
        if ((o === "auto" || o === "scroll") && a.getBoundingClientRect().right <= width + 1)
          return true;
      }
      return false;
    };
    for (const el of document.body.querySelectorAll("*")) {
      if (!shown(el) || el.closest("svg, script, style, iframe")) continue;
      const r = el.getBoundingClientRect();
      if (r.width <= 1 || r.height <= 1) continue; // visually hidden, for screen readers
      if ((r.right > width + 1 || r.left < -1) && !inScroller(el))
        out.push(`off the screen: ${name(el)} ${r.left.toFixed(0)}..${r.right.toFixed(0)}`);
      const own = [...el.childNodes].some((n) => n.nodeType === 3 && n.textContent.trim());
      if (!own) continue;
      const style = getComputedStyle(el);
      const clips = style.overflowX !== "visible" || style.textOverflow === "ellipsis";
      if (clips && el.scrollWidth > el.clientWidth + 1)
        out.push(`cut: ${name(el)} ${el.scrollWidth} > ${el.clientWidth}`);
    }
    // Headings and buttons not covered by something else (the topmost at their middle).
    for (const el of document.querySelectorAll("h1, h2, button, a.button")) {
      if (!shown(el)) continue;
      el.scrollIntoView({ block: "center", inline: "center" });
      const r = el.getBoundingClientRect();
      const top = document.elementFromPoint(r.left + r.width / 2, r.top + r.height / 2);
      if (top && !el.contains(top) && !top.contains(el))
        out.push(`covered: ${name(el)} by ${name(top)}`);
    }
    window.scrollTo(0, 0);
    return [...new Set(out)];
  }, direction);
}

/** The console's pages for a phone, each with how to open it and a name for its picture. */
function consolePages(lang) {
  const q = `lang=${lang}`;
  const { base, projector, first, lecturerToken } = world;
  return [
    ["admin", `/admin?token=${server.token}&${q}`, "#lecturer-table"],
    ["lecturer-list", `/lecturer?token=${lecturerToken}&${q}`, "time[title]"],
    ["lecturer-class", `${base}/lecturer?${q}`, "#entries tr[data-entry]"],
    ["projector", `${projector}&${q}`, "#players:not(:empty)"],
    ["projector-past", `${projector}&challenge=${first.id}&${q}`, "#board tr td"],
    ["join", `/?${q}`, "#code"],
  ];
}

/** A checkbox on the line of its label (its middle within the label's height), or why not. */
async function boxBesideLabel(page, id) {
  const [box, label] = await page.evaluate((id) => {
    const rect = (el) => {
      const r = el.getBoundingClientRect();
      return { top: r.top, bottom: r.bottom, middle: (r.top + r.bottom) / 2 };
    };
    return [rect(document.getElementById(id)), rect(document.querySelector(`label[for="${id}"]`))];
  }, id);
  const beside = box.middle > label.top && box.middle < label.bottom;
  return beside
    ? []
    : [`#${id} at ${box.top}-${box.bottom}, its label at ${label.top}-${label.bottom}`];
}

for (const lang of ["en", "ar"]) {
  test(
    `the console's pages at 390 x 844 in ${lang}: nothing scrolls sideways, is small or cut`,
    { timeout: 300_000 },
    async () => {
      const errors = [];
      const { context, page } = await phone(lang, errors);
      const found = {};
      for (const [name, path, ready] of consolePages(lang)) {
        await page.goto(server.base + path);
        await page.waitForSelector(ready, { state: "attached" });
        await page.evaluate(() => document.fonts.ready);
        await shot(page, `console-phone-${lang}-${name}.png`);
        const wrong = await problems(page, lang === "ar" ? "rtl" : "ltr");
        if (name === "lecturer-class") wrong.push(...(await boxBesideLabel(page, "lost")));
        if (wrong.length) found[name] = wrong;
      }
      await context.close();
      assert.deepEqual(found, {});
      assert.deepEqual(errors, []);
    },
  );
}

test(
  "the lecturer's list: each past round's time for its reader, its projector and exports",
  { timeout: 300_000 },
  async () => {
    const errors = [];
    const { context, page } = await phone("en", errors);
    await page.goto(`${server.base}/lecturer?token=${world.lecturerToken}`);
    const rows = `#rounds-${world.room.code} tbody tr`;
    await page.waitForSelector(`${rows} time[title]`);
    const times = await page.$$eval(`${rows} time`, (ts) =>
      ts.map((t) => ({ iso: t.dateTime, text: t.textContent, title: t.title })),
    );
    assert.equal(times.length, 1, "the first round has the time it closed; the open one none");
    const { iso, text, title } = times[0];
    // Closed by the second round's opening, 30 minutes early: the time it closed.
    assert.ok(Date.parse(iso) < Date.parse(world.first.closes_at) - 25 * 60_000, iso);
    assert.ok(Math.abs(Date.now() - Date.parse(iso)) < 10 * 60_000, iso);
    assert.equal(title, iso);
    const tokyo = new Intl.DateTimeFormat("en-GB", { ...SHORT, timeZone: "Asia/Tokyo" });
    assert.equal(text, tokyo.format(new Date(iso)));
    assert.match(text, /^[A-Z][a-z]{2} \d{1,2} [A-Z][a-z]{2}, \d\d:\d\d$/);

    const links = await page.$$eval(`${rows}`, (trs) =>
      trs.map((tr) =>
        [...tr.querySelectorAll("a")].map((a) => [a.textContent, a.getAttribute("href")]),
      ),
    );
    const [openRow, pastRow] = links; // newest first
    const id = world.first.id;
    assert.deepEqual(
      pastRow.map(([t]) => t),
      ["Open on the projector", "CSV", "JSON"],
    );
    assert.match(
      pastRow[0][1],
      new RegExp(`/c/${world.room.code}/projector\\?key=[0-9a-f]+&round=${id}$`),
    );
    assert.doesNotMatch(openRow[0][1], /round=/, "the open round's link is the live board");
    await shot(page, "console-lecturer-list-390.png");
    await page.setViewportSize({ width: 1280, height: 800 });
    await shot(page, "console-lecturer-list-1280.png");
    // The exports with the browser's own cookie (the page's link, as a click fetches it).
    const csv = await context.request.get(server.base + pastRow[1][1]);
    assert.equal(csv.status(), 200);
    assert.match(csv.headers()["content-disposition"], /\.csv"/);
    assert.equal((await csv.text()).trim().split(/\r?\n/).length, NAMES.length + 1);
    const json = await (await context.request.get(server.base + pastRow[2][1])).json();
    assert.equal(json.challenge.id, id);
    assert.equal(json.entries.length, NAMES.length);

    // The projector's link opens the past round: its board and podium, not the open round's.
    const [shown] = await Promise.all([
      context.waitForEvent("page"),
      page.click(`${rows} a[data-round="${id}"]`),
    ]);
    watchErrors(errors)(shown);
    await shown.setViewportSize({ width: 1920, height: 1080 });
    await pastBoard(shown, id);
    await context.close();
    assert.deepEqual(errors, []);
  },
);

/** A past round on the projector: its heading, podium (top three) and board, every entry
 * on one of its pages, the podium's and board's names the round's. */
async function pastBoard(page, id) {
  await page.waitForFunction(() => document.getElementById("debrief-paths")?.dataset.curves);
  await page.waitForSelector("#board tr td");
  assert.equal(await page.textContent("#round-head"), `Round ${id}`);
  const top = world.board.entries.slice(0, 3).map((e) => e.name);
  assert.deepEqual(
    await page.$$eval("#podium li .who", (els) => els.map((e) => e.textContent)),
    top,
  );
  const seen = new Set();
  const cut = [];
  const pages = Number((await page.getAttribute("#board-page", "data-pages")) ?? 1);
  for (let p = 0; p < pages; p++) {
    await page.waitForFunction(
      (n) => document.getElementById("board-page").dataset.page === String(n),
      p,
      {
        timeout: 20_000,
      },
    );
    const rows = await page.$$eval("#board tr:not([hidden])", (trs) =>
      trs.filter((tr) => tr.checkVisibility()).map((tr) => [...tr.cells].map((c) => c.textContent)),
    );
    for (const cells of rows.slice(1)) seen.add(cells[1]);
    cut.push(
      ...(await page.$$eval("#board td, #board th, #podium .who", (els) =>
        els
          .filter((el) => el.checkVisibility() && el.scrollWidth > el.clientWidth + 1)
          .map((el) => el.textContent),
      )),
    );
  }
  assert.deepEqual([...seen].sort(), world.board.entries.map((e) => e.name).sort());
  assert.deepEqual(cut, [], "no name or number cut, on any page");
  const box = await page.evaluate(() => {
    const r = document.getElementById("board-box").getBoundingClientRect();
    const p = document.getElementById("debrief-paths").getBoundingClientRect();
    return {
      board: [r.left, r.right, r.bottom],
      paths: [p.left, p.right],
      h: innerHeight,
      w: innerWidth,
    };
  });
  assert.ok(
    box.board[2] <= box.h && box.board[1] <= box.w,
    `the board on the screen: ${JSON.stringify(box)}`,
  );
  assert.ok(
    box.board[1] <= box.paths[0] || box.paths[1] <= box.board[0],
    "the board beside the paths",
  );
  await shot(page, `console-projector-past-${page.viewportSize().width}.png`);
}

test(
  "a past round reopened with ?challenge= at 1280 x 720 and 3840 x 2160",
  { timeout: 300_000 },
  async () => {
    const errors = [];
    for (const [width, height] of [
      [1280, 720],
      [3840, 2160],
    ]) {
      const page = watchErrors(errors)(await browser.newPage({ viewport: { width, height } }));
      await page.goto(`${server.base}${world.projector}&challenge=${world.first.id}`);
      await pastBoard(page, world.first.id);
      await page.close();
    }
    assert.deepEqual(errors, []);
  },
);
