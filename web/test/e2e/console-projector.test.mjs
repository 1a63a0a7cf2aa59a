// The projector and the rounds (issue 45) in real Chromium against a real `evapcool class
// --department`: a lecturer's class, two phones (390 x 844) join by its code and play, 24
// more students send ramp games; the projector (1280 x 720, 1920 x 1080, 3840 x 2160) shows
// the join code in its largest type beside the QR code, how many played, every entry a
// page at a time; on the close a podium (names, then ranks in anonymous mode) over the
// debrief; a picked replay presented without buttons, hints or its code; the pair's line
// naming the pair; every word >= 24 px at 1080p (in proportion at 720p and 4K), no heading
// cut. A new round keeps the last: the history reopens it on the projector; its CSV and
// JSON exports read back; printed light, one chart a page; the light theme >= 7:1 by
// pixels. EVAPCOOL_SHOTS=DIR saves the screenshots there.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
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
import { decodePng, pixel } from "./png.mjs";

const PYTHON = pythonWithEvapcool(); // none: this file fails, saying so (python.mjs)
const ROOT = resolve(import.meta.dirname, "../../..");
const SEED = 77;
const MORE = 24;
const SHOTS = process.env.EVAPCOOL_SHOTS;
const SIZES = [
  [1280, 720],
  [1920, 1080],
  [3840, 2160],
];

let server;
let browser;

before(async () => {
  ({ server, browser } = await startServerAndBrowser(PYTHON, "evapcool-projector-", {
    department: true,
  }));
});

after(() => closeServerAndBrowser({ server, browser }));

async function shot(page, name) {
  if (!SHOTS) return;
  mkdirSync(SHOTS, { recursive: true });
  await page.screenshot({ path: join(SHOTS, name) });
}

/** A phone joining the class by its code at the server's root, as `name`. */
async function phone(watch, room, base, name) {
  const context = await browser.newContext({
    viewport: { width: 390, height: 844 },
    isMobile: true,
    hasTouch: true,
  });
  const page = watch(await context.newPage());
  await page.goto(`${server.base}/`);
  await page.fill("#code", room.code);
  await page.tap("button");
  await page.waitForURL(`${server.base}${base}/`);
  await page.waitForSelector("#join input");
  await page.fill("#join input", name);
  await page.tap("#join button");
  await page.waitForFunction(() => window.evapcool?.app?.play?.fixedSeed !== null);
  return page;
}

/** Every visible word's computed size (elements with their own text), and the canvases'
 * smallest drawn words, against 24 px at 1080 lines in proportion. */
function textSizes(page) {
  return page.evaluate(() => {
    const least = (24 * window.innerHeight) / 1080;
    const small = [];
    for (const el of document.body.querySelectorAll("*")) {
      const own = [...el.childNodes].some((n) => n.nodeType === 3 && n.textContent.trim());
      if (!own || el.closest("script, style, svg") || !el.getClientRects().length) continue;
      const size = parseFloat(getComputedStyle(el).fontSize);
      if (size < least - 0.01) small.push(`${el.id || el.tagName}: ${size} px`);
    }
    for (const c of document.querySelectorAll("canvas")) {
      if (!c.getClientRects().length || !c.dataset.minText) continue;
      const size = Number(c.dataset.minText);
      if (size < least - 0.01) small.push(`${c.id} (canvas): ${size} px`);
    }
    return { least, small };
  });
}

/** Headings and lines that would be cut (wider or taller than their box, or ellipsised). */
function cutHeadings(page) {
  return page.evaluate(() =>
    [...document.querySelectorAll("h1, h2, #state, #debrief-pick, #replay-head, #podium .who")]
      .filter((el) => el.getClientRects().length && el.textContent.trim())
      .filter(
        (el) =>
          el.scrollWidth > el.clientWidth + 1 || getComputedStyle(el).textOverflow === "ellipsis",
      )
      .map((el) => el.id || el.className),
  );
}

/** A projector page at a size; its errors collected. */
async function projectorAt(watch, link, [width, height]) {
  const page = watch(await browser.newPage({ viewport: { width, height } }));
  await page.goto(`${server.base}${link}`);
  await page.waitForFunction(() => document.getElementById("state").textContent !== "");
  return page;
}

/** The game buttons of the framed pages (`selector`) that show inside their stage, and
 * the notices they draw (a presented replay shows none of either). */
async function framedControls(page, selector) {
  await page.waitForFunction(
    (sel) => {
      const frames = [...document.querySelectorAll(sel)];
      return frames.length && frames.every((f) => f.dataset.presented === "1");
    },
    selector,
    { timeout: 30_000 },
  );
  return page.evaluate((sel) => {
    const out = { buttons: [], notices: [] };
    for (const frame of document.querySelectorAll(sel)) {
      const stage = frame.parentElement.getBoundingClientRect();
      const app = frame.contentWindow.evapcool.app;
      const l = app.layout;
      const style = getComputedStyle(frame);
      const m = new DOMMatrix(style.transform);
      // The part of the page left visible: its clip (inset, in its own px), then the stage.
      const [top, right, bottom, left] = (style.clipPath.match(/[\d.]+px/g) ?? []).map(parseFloat);
      const clip = [
        left ?? 0,
        top ?? 0,
        frame.clientWidth - (right ?? 0),
        frame.clientHeight - (bottom ?? 0),
      ];
      const inStage = (r) => {
        const a = Math.max(l.offsetX + r.x * l.scale, clip[0]);
        const b = Math.max(l.offsetY + r.y * l.scale, clip[1]);
        const c = Math.min(l.offsetX + (r.x + r.w) * l.scale, clip[2]);
        const d = Math.min(l.offsetY + (r.y + r.h) * l.scale, clip[3]);
        if (c - a < 1 || d - b < 1) return false; // clipped away
        const [x0, y0, x1, y1] = [m.a * a + m.e, m.d * b + m.f, m.a * c + m.e, m.d * d + m.f];
        return x1 > 1 && y1 > 1 && x0 < stage.width - 1 && y0 < stage.height - 1;
      };
      for (const [n, r] of Object.entries(l.buttons)) if (inStage(r)) out.buttons.push(n);
      out.notices.push(...app.notices.visible);
      // "Press Space to start", drawn before the replay's first frame, is a key's hint too.
      if (app.win.startHint) out.notices.push("start hint");
    }
    return out;
  }, selector);
}

/** Ids of the elements reaching past the screen's edge. */
function outside(page, ids) {
  return page.evaluate(
    (list) =>
      list.filter((id) => {
        const el = document.getElementById(id);
        if (!el || !el.getClientRects().length) return false;
        const r = el.getBoundingClientRect();
        return r.bottom > window.innerHeight + 1 || r.right > window.innerWidth + 1;
      }),
    ids,
  );
}

/** WCAG contrast of two sRGB colours. */
function contrast(a, b) {
  const lum = ([r, g, bb]) => {
    const f = (c) => ((c /= 255) <= 0.03928 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);
    return 0.2126 * f(r) + 0.7152 * f(g) + 0.0722 * f(bb);
  };
  const [x, y] = [lum(a), lum(b)].sort((p, q) => q - p);
  return (x + 0.05) / (y + 0.05);
}

test(
  "the projector and the rounds: join code, paged board, podium, debrief, history, exports, print",
  { timeout: 900_000 },
  async () => {
    const errors = [];
    const watch = watchErrors(errors);
    const { lecturerToken, room, base } = await departmentClass(server);
    const lecturer = (path, body) => postJson(server, base + path, lecturerToken, body);
    const api = async (path, headers = {}) => {
      const r = await fetch(server.base + base + path, { headers });
      assert.equal(r.status, 200, `${path}: ${await r.clone().text()}`);
      return r;
    };
    const first = await lecturer("/api/challenge", {
      n_atoms: 49,
      radius: 12,
      escape: "rim",
      seed: SEED,
      lost: true,
      max_frames: 6000,
    });
    const page = await (
      await fetch(`${server.base}${base}/lecturer`, {
        headers: { authorization: `Bearer ${lecturerToken}` },
      })
    ).text();
    const link = /href="([^"]*\/projector\?key=[0-9a-f]+)"/.exec(page)[1];
    const key = /key=([0-9a-f]+)/.exec(link)[1];

    // The projector while the round is open: the join code in its largest type.
    const live = await projectorAt(watch, link, [1920, 1080]);
    await shot(live, "console-projector-join-1080.png");
    assert.equal(await live.textContent("#join-code"), room.code);
    const joinBox = await live.evaluate(() => {
      const sizes = [...document.querySelectorAll("body *")]
        .filter((el) => el.id !== "join-code" && el.checkVisibility({ visibilityProperty: true }))
        .map((el) => parseFloat(getComputedStyle(el).fontSize));
      const code = document.getElementById("join-code");
      const qr = document.querySelector("#qr svg").getBoundingClientRect();
      const box = code.getBoundingClientRect();
      return {
        code: parseFloat(getComputedStyle(code).fontSize),
        largestElse: Math.max(...sizes),
        beside: box.left >= qr.right && box.top < qr.bottom,
        address: document.getElementById("join").textContent,
      };
    });
    assert.ok(
      joinBox.code > joinBox.largestElse,
      `code ${joinBox.code} px vs ${joinBox.largestElse} px`,
    );
    assert.ok(joinBox.beside, "the code beside the QR code");
    assert.ok(joinBox.address.includes("127.0.0.1:") && !joinBox.address.includes("http"));

    // Two phones join by the code and play; 24 more students send ramp games.
    const names = [];
    for (const [name, floor] of [
      ["Mia Phone", 90],
      ["Finn Phone", 110],
    ]) {
      const p = await phone(watch, room, base, name);
      const s = await play(p, floor);
      assert.notEqual(s.wonAt, null, `${name} wins`);
      await p.waitForFunction(
        () => /verified/i.test(document.getElementById("classbar").textContent),
        null,
        { timeout: 60_000 },
      );
      names.push(name);
      await p.context().close();
    }
    const games = JSON.parse(
      execFileSync(PYTHON, [join(ROOT, "tests/classhelp.py"), "ramps", String(MORE), "77"], {
        maxBuffer: 64 << 20,
      }),
    );
    for (const [k, g] of games.entries()) {
      const name = `Learner-${String(k + 1).padStart(2, "0")}`;
      names.push(name);
      const joined = await fetch(`${server.base}${base}/api/join`, {
        method: "POST",
        headers: { "content-type": "application/json" },
        body: JSON.stringify({ name }),
      }).then((r) => r.json());
      await postJson(server, `${base}/api/submit`, joined.token, {
        challenge: first.id,
        code: g.code,
      });
    }
    const board = await (await api("/api/leaderboard")).json();
    assert.equal(board.players, names.length);
    await live.waitForFunction(
      (n) => document.getElementById("players").textContent.includes(String(n)),
      names.length,
    );
    assert.equal(await live.textContent("#players"), `Students who played: ${names.length}`);

    // At 720p the board does not fit: its pages show every entry in turn.
    const small = await projectorAt(watch, link, SIZES[0]);
    await small.waitForFunction(
      () => Number(document.getElementById("board-page").dataset.pages) > 1,
    );
    const seen = new Set();
    const pagesN = Number(await small.getAttribute("#board-page", "data-pages"));
    for (let p = 0; p < pagesN; p++) {
      await small.waitForFunction(
        (want) => document.getElementById("board-page").dataset.page === String(want),
        p,
        { timeout: 30_000 },
      );
      const rows = await small.evaluate(() =>
        [...document.querySelectorAll("#board tr:not([hidden]) td:nth-child(2)")]
          .filter((td) => {
            const box = document.getElementById("board-box").getBoundingClientRect();
            return td.getBoundingClientRect().bottom <= box.bottom + 0.5;
          })
          .map((td) => td.textContent),
      );
      for (const r of rows) seen.add(r);
    }
    assert.deepEqual([...seen].sort(), [...names].sort(), "every entry on some page");
    assert.match(await small.textContent("#board-page"), new RegExp(`of ${names.length}$`));
    for (const size of SIZES) {
      const p =
        size[0] === 1280 ? small : size[0] === 1920 ? live : await projectorAt(watch, link, size);
      await p.waitForFunction(() => document.querySelectorAll("#board tr").length > 1);
      const sizes = await textSizes(p);
      assert.deepEqual(sizes.small, [], `open, ${size.join("x")}: >= ${sizes.least} px`);
      assert.deepEqual(await cutHeadings(p), [], `open, ${size.join("x")}: nothing cut`);
      await shot(p, `console-projector-open-${size[1]}.png`);
      if (p !== small && p !== live) await p.close();
    }
    await small.close();

    // The close: "Closed: final results" with the podium over the debrief, at three sizes.
    await lecturer("/api/challenge/close", {});
    const top = board.entries.slice(0, 3).map((e) => e.name);
    const closedPages = [];
    for (const size of SIZES) {
      const p = size[0] === 1920 ? live : await projectorAt(watch, link, size);
      await p.waitForFunction(() => document.getElementById("debrief-paths")?.dataset.curves);
      assert.equal(await p.textContent("#state"), "Closed: final results");
      const podium = await p.$$eval("#podium li .who", (els) => els.map((e) => e.textContent));
      assert.deepEqual(podium, top);
      const atoms = await p.$$eval("#podium li .atoms", (els) => els.map((e) => e.textContent));
      assert.deepEqual(
        atoms,
        board.entries.slice(0, 3).map((e) => `Atoms: ${e.score}`),
      );
      assert.ok(await p.isVisible("#podium"));
      const sizes = await textSizes(p);
      assert.deepEqual(sizes.small, [], `closed, ${size.join("x")}: >= ${sizes.least} px`);
      assert.deepEqual(await cutHeadings(p), [], `closed, ${size.join("x")}: nothing cut`);
      // The podium, the charts and the state all inside the screen.
      const out = await outside(p, ["podium", "debrief-paths", "debrief-heights", "state"]);
      assert.deepEqual(out, [], `closed, ${size.join("x")}: inside the screen`);
      await shot(p, `console-projector-podium-${size[1]}.png`);
      closedPages.push(p);
    }

    // A picked game: presented (the play area only, no hint), never its code.
    const doc = await (await api("/api/debrief")).json();
    const best = doc.archetypes.best;
    await lecturer("/api/debrief", { pick: best });
    for (const [i, p] of closedPages.entries()) {
      await p.waitForFunction(() => !document.getElementById("replay").hidden);
      const framed = await framedControls(p, "#replay-frame");
      assert.deepEqual(framed.buttons, [], `no game button shows (${SIZES[i].join("x")})`);
      assert.deepEqual(framed.notices, [], "no key's hint");
      const seenOf = await p.evaluate(() => ({
        text: document.body.innerText,
        codes: [...document.querySelectorAll("code, #replay-code")].length,
      }));
      assert.equal(seenOf.codes, 0, "no replay code element");
      assert.ok(!/[A-Za-z0-9_.-]{80,}/.test(seenOf.text), "no replay code on the projector");
      assert.deepEqual(await cutHeadings(p), [], "the replay's heading whole");
      const sizes = await textSizes(p);
      assert.deepEqual(sizes.small, [], `picked, ${SIZES[i].join("x")}: >= ${sizes.least} px`);
      await shot(p, `console-projector-replay-${SIZES[i][1]}.png`);
    }

    // A pair: the line over it names the two games played, not the one picked before.
    const [a, b] = [doc.games[3], doc.games[5]];
    await lecturer("/api/debrief", { pair: [a.entry, b.entry] });
    await live.waitForFunction(() => !document.getElementById("debrief-pair").hidden);
    await live.waitForFunction(
      (want) => document.getElementById("debrief-pick").textContent === want,
      `Side by side: ${a.name} · ${b.name}`,
    );
    await live.waitForFunction(() => document.getElementById("debrief-pair").dataset.minText);
    const pairFramed = await framedControls(live, "#debrief-replays iframe");
    assert.deepEqual(pairFramed.buttons, [], "no game button in the pair's frames");
    assert.deepEqual(pairFramed.notices, [], "no key's hint in the pair's frames");
    assert.deepEqual(await outside(live, ["debrief-pair", "debrief-replays"]), []);
    const pairSizes = await textSizes(live);
    assert.deepEqual(pairSizes.small, [], "the pair's numbers >= 24 px at 1080p");
    await shot(live, "console-projector-pair-1080.png");

    // Anonymous mode: ranks on the podium, no name anywhere.
    await lecturer("/api/debrief", { anonymous: true, pair: null, pick: null });
    await live.waitForFunction(
      () => document.querySelector("#podium li .who")?.textContent === "Student 1",
    );
    // Once the debrief's document is read again (without names), no name anywhere.
    await live
      .waitForFunction((list) => !list.some((n) => document.body.innerText.includes(n)), names, {
        timeout: 30_000,
      })
      .catch(async () => {
        const text = await live.evaluate(() => document.body.innerText);
        assert.fail(`a name still shows: ${names.filter((n) => text.includes(n))}`);
      });
    assert.deepEqual(await live.$$eval("#podium li .who", (els) => els.map((e) => e.textContent)), [
      "Student 1",
      "Student 2",
      "Student 3",
    ]);
    await shot(live, "console-projector-anonymous-1080.png");
    await lecturer("/api/debrief", { anonymous: false });
    for (const p of closedPages) if (p !== live) await p.close();

    // A new round: the last one stays in the history, reopened on the projector.
    const second = await lecturer("/api/challenge", { n_atoms: 49, radius: 12, seed: 5 });
    await live.waitForFunction(() => /^Open/.test(document.getElementById("state").textContent));
    const r409 = await fetch(`${server.base}${base}/api/debrief`);
    assert.equal(r409.status, 409, "the new round's debrief waits for its close");
    await live.click("#history");
    await live.waitForSelector(`#rounds-list a[data-round="${first.id}"]`);
    assert.equal(await live.$$eval("#rounds-list a[data-round]", (a) => a.length), 1);
    // When the round ended, in the room's words (closed by hand: the time it closed).
    const ended = await live.$eval(`#rounds-list a[data-round="${first.id}"] time`, (t) => [
      t.dateTime,
      t.textContent,
    ]);
    assert.ok(Math.abs(Date.parse(ended[0]) - Date.now()) < 3_600_000, ended.join(" | "));
    assert.doesNotMatch(ended[1], /^\d{4}-/, "a time for the reader, not ISO");
    await live.click(`#rounds-list a[data-round="${first.id}"]`);
    await live.waitForURL(/round=\d+/);
    await live.waitForFunction(() => document.getElementById("debrief-paths")?.dataset.curves);
    assert.equal(await live.textContent("#round-head"), `Round ${first.id}`);
    assert.deepEqual(
      await live.$$eval("#podium li .who", (els) => els.map((e) => e.textContent)),
      top,
    );
    assert.equal(
      (await live.getAttribute("#debrief-paths", "data-curves")).split(",").length,
      names.length,
    );
    assert.ok(second.id !== first.id);
    assert.deepEqual(await outside(live, ["podium", "debrief-paths", "debrief-heights"]), []);
    await shot(live, "console-projector-history-1080.png");

    // Exports of the first round, read back.
    const auth = { authorization: `Bearer ${lecturerToken}` };
    const csv = await (await api(`/api/export.csv?challenge=${first.id}`, auth)).text();
    const lines = csv.trim().split(/\r?\n/);
    const header = lines[0].split(",");
    assert.ok(["archetype", "won", "path_points", "end_atoms"].every((c) => header.includes(c)));
    assert.equal(lines.length - 1, names.length, "every game sent");
    const col = (c) => header.indexOf(c);
    const bestRow = lines.slice(1).find((l) => l.split(",")[col("entry")] === String(best));
    assert.match(bestRow.split(",")[col("archetype")], /\bbest\b/);
    const json = await (await api(`/api/export.json?challenge=${first.id}`, auth)).json();
    assert.equal(json.entries.length, names.length);
    for (const e of json.entries) {
      assert.ok(e.path && e.path.n.length > 1, `entry ${e.entry}'s path`);
      assert.equal(e.path.score, e.score);
    }

    // Printed: light, the first page the podium and board, then one chart a page.
    await live.emulateMedia({ media: "print" });
    const printed = await live.evaluate(() => ({
      bg: getComputedStyle(document.body).backgroundColor,
      side: getComputedStyle(document.getElementById("side")).display,
      breaks: [...document.querySelectorAll("#debrief-charts canvas")].map(
        (c) => getComputedStyle(c).breakBefore,
      ),
    }));
    assert.equal(printed.bg, "rgb(255, 255, 255)");
    assert.equal(printed.side, "none");
    assert.deepEqual(printed.breaks, ["page", "page"]);
    const pdf = await live.pdf({ format: "A4", landscape: true });
    const pdfPages = (pdf.toString("latin1").match(/\/Type\s*\/Page[^s]/g) ?? []).length;
    assert.ok(pdfPages >= 3, `${pdfPages} pages printed`);
    if (SHOTS) {
      const { writeFileSync } = await import("node:fs");
      writeFileSync(join(SHOTS, "console-projector-print.pdf"), pdf);
    }
    await live.emulateMedia({ media: "screen" });

    // The light theme: the state and the players' line >= 7:1 against the page, by pixels.
    await live.click("#theme");
    assert.equal(await live.getAttribute("#theme", "aria-pressed"), "true");
    for (const id of ["state", "settings", "round-head", "players"]) {
      const box = await live.locator(`#${id}`).boundingBox();
      const img = decodePng(await live.screenshot({ clip: box }));
      const bg = pixel(img, 1, 1);
      let worst = Infinity;
      // The text's own colour: the pixel farthest from the background.
      let ink = bg;
      let far = -1;
      for (let y = 0; y < img.height; y++)
        for (let x = 0; x < img.width; x++) {
          const c = pixel(img, x, y);
          const d = Math.abs(c[0] - bg[0]) + Math.abs(c[1] - bg[1]) + Math.abs(c[2] - bg[2]);
          if (d > far) [far, ink] = [d, c];
        }
      worst = Math.min(worst, contrast(bg, ink));
      assert.ok(worst >= 7, `#${id}: contrast ${worst.toFixed(2)}:1`);
    }
    await shot(live, "console-projector-light-1080.png");
    await live.click("#theme");
    assert.deepEqual(errors, []);
  },
);
