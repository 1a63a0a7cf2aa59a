// The lecturer's and administrator's console in real Chromium (issue 45): a real
// `evapcool class --department` on 127.0.0.1. The administrator opens their link (the
// token leaves the address), makes two lecturers on the page and copies a link; each
// lecturer opens theirs and makes a class (a reload makes no second); lecturer B is refused
// on A's class as a page; a stale link after a relink gets a page saying what to do (in
// the reader's language); lecturer A's class page names the class and its join code,
// opens a round, and a new round asks before it closes the open one. Screenshots of the
// administrator's and the lecturer's page at 1280 x 800 go to EVAPCOOL_SHOTS (or a
// temporary folder) to be looked at.
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { existsSync, mkdtempSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { after, before, test } from "node:test";
import { closeServerAndBrowser, startServerAndBrowser, watchErrors } from "./class-server.mjs";
import { pythonWithEvapcool } from "./python.mjs";

const PYTHON = pythonWithEvapcool(); // none: this file fails, saying so (python.mjs)
const SHOTS = process.env.EVAPCOOL_SHOTS ?? mkdtempSync(join(tmpdir(), "evapcool-console-"));
const LAPTOP = { width: 1280, height: 800 };
const ROOT = resolve(import.meta.dirname, "../../..");

let server;
let browser;

before(async () => {
  ({ server, browser } = await startServerAndBrowser(PYTHON, "evapcool-console-", {
    department: true,
  }));
});

after(() => closeServerAndBrowser({ server, browser }));

/** Students join a class by its API and send ramp games of `seed` (tests/classhelp.py). */
async function sendGames(base, seed, names) {
  const out = execFileSync(
    PYTHON,
    [join(ROOT, "tests/classhelp.py"), "ramps", String(names.length), String(seed)],
    { env: { ...process.env }, maxBuffer: 16 << 20 },
  );
  const games = JSON.parse(String(out));
  const json = { "content-type": "application/json" };
  const board = await (await fetch(`${server.base}${base}/api/leaderboard`)).json();
  for (const [k, g] of games.entries()) {
    const joined = await fetch(`${server.base}${base}/api/join`, {
      method: "POST",
      headers: json,
      body: JSON.stringify({ name: names[k] }),
    });
    assert.equal(joined.status, 200, await joined.clone().text());
    const { token } = await joined.json();
    const sent = await fetch(`${server.base}${base}/api/submit`, {
      method: "POST",
      headers: { ...json, authorization: `Bearer ${token}` },
      body: JSON.stringify({ challenge: board.challenge, code: g.code }),
    });
    assert.equal(sent.status, 200, await sent.clone().text());
  }
}

/** A person's own browser (cookies of their own), its pages watched for script errors. */
async function person(errors, options = {}) {
  const context = await browser.newContext({ viewport: LAPTOP, ...options });
  return errors ? watchErrors(errors)(await context.newPage()) : context.newPage();
}

/** The new link the administrator's page shows once (its box's text). */
async function shownLink(page) {
  return page.locator(".link-box input.link").inputValue();
}

/** A lecturer opens their link and makes a class on their list; its join code. */
async function makeClass(page, link, name) {
  await page.goto(link);
  assert.equal(new URL(page.url()).search, "", "the token left the address");
  await page.fill("#name", name);
  await page.getByRole("button", { name: "Create" }).click();
  await page.waitForSelector(`.class-card:has-text("${name}")`);
  return page.locator(`.class-card:has-text("${name}")`).getAttribute("data-code");
}

test("the administrator, two lecturers, a class each, refusals as pages", async () => {
  const errors = [];
  const admin = await person(errors, { permissions: ["clipboard-read", "clipboard-write"] });
  await admin.goto(`${server.base}/admin?token=${server.token}`);
  assert.equal(admin.url(), `${server.base}/admin`, "no token in the address after use");
  for (const name of ["Ada", "Bo"]) {
    await admin.fill("#lname", name);
    await admin.getByRole("button", { name: "Create" }).first().click();
    await admin.waitForSelector(".link-box");
  }
  const linkB = await shownLink(admin);
  assert.match(linkB, /\/lecturer\?token=[\w-]+$/);
  // The copy button puts the very link on the clipboard and says so.
  await admin.getByRole("button", { name: "Copy" }).click();
  assert.equal(await admin.evaluate(() => navigator.clipboard.readText()), linkB);
  await admin.getByRole("button", { name: "Copied" }).waitFor();
  assert.ok((await admin.locator(".link-box svg").count()) === 1, "the link's QR code");
  // A reload posts nothing again and shows the link no more.
  await admin.reload();
  assert.equal(await admin.locator(".link-box").count(), 0);
  assert.equal(await admin.locator("#lecturer-table tbody tr").count(), 2);
  const heads = await admin.locator("#lecturer-table th").allTextContents();
  assert.ok(heads.length === 5 && heads.every((h) => h.trim() !== ""), heads.join("|"));
  // Ada's link, made anew (Relink, confirmed): the first one she had will be stale.
  admin.once("dialog", (d) => void d.accept());
  const adaRow = admin.locator("#lecturer-table tbody tr", { hasText: "1" }).first();
  await adaRow.getByRole("button", { name: "Relink" }).click();
  await admin.waitForSelector(".link-box");
  const linkA = await shownLink(admin);

  const ada = await person(errors);
  const codeA = await makeClass(ada, linkA, "Optics");
  await ada.reload(); // a reload of the list after "Create" makes no second class
  assert.equal(await ada.locator(".class-card").count(), 1);
  const bo = await person(errors);
  const codeB = await makeClass(bo, linkB, "Waves");
  assert.notEqual(codeA, codeB);

  // Bo on Ada's class: a page in his language saying what to do; JSON for the API.
  const refusals = [];
  const boRefused = await bo.goto(`${server.base}/c/${codeA}/lecturer`);
  assert.equal(boRefused.status(), 403);
  assert.equal(await bo.textContent("h1"), "This page cannot be opened");
  assert.match(await bo.textContent("#todo"), /administrator/);
  const api = await bo.evaluate(async (url) => {
    const r = await fetch(url);
    return { status: r.status, type: r.headers.get("content-type"), body: await r.json() };
  }, `${server.base}/c/${codeA}/api/entries`);
  assert.equal(api.status, 403);
  assert.match(api.type, /application\/json/);
  assert.equal(api.body.error.field, "token");

  // Ada's first link, now stale, in a German browser: a German page saying what to do.
  const stale = await person(refusals, { locale: "de-DE" });
  const old = linkB.replace(/token=.*/, "token=stale-link-0000");
  const staleAnswer = await stale.goto(old);
  assert.equal(staleAnswer.status(), 403);
  assert.equal(await stale.textContent("h1"), "Diese Seite lässt sich nicht öffnen");
  assert.match(await stale.textContent("#todo"), /Link/);
  await stale.screenshot({ path: join(SHOTS, "console-refused-de.png") });

  // Ada's class page: its name and join code at the top.
  await ada.getByRole("link", { name: "Lecturer's page" }).click();
  await ada.waitForURL(`${server.base}/c/${codeA}/lecturer`);
  assert.equal(await ada.textContent("#class-name"), "Optics");
  assert.equal(await ada.textContent("#join-code"), codeA);
  assert.match(await ada.title(), /^Optics/);
  await ada.fill("#seed", "77");
  await ada.fill("#minutes", "20");
  await ada.getByRole("button", { name: "Open", exact: true }).click();
  await ada.waitForFunction(() => /Open$/.test(document.getElementById("current").textContent));
  // The state once, on the round's line; the large line below only counts down.
  assert.match(await ada.textContent("#countdown"), /^closes in (19:5\d|20:00)$/);
  const first = await ada.textContent("#current");
  // A new round while one is open: asked first; Escape (the keyboard) keeps the open one.
  await ada.getByRole("button", { name: "Open", exact: true }).focus();
  await ada.keyboard.press("Enter");
  await ada.waitForSelector("dialog#confirm[open]");
  assert.match(await ada.textContent("dialog#confirm"), /closes it now/);
  await ada.keyboard.press("Escape");
  await ada.waitForSelector("dialog#confirm", { state: "hidden" });
  assert.equal(await ada.textContent("#current"), first, "nothing opened");
  await ada.getByRole("button", { name: "Open", exact: true }).click();
  await ada.getByRole("button", { name: "Close it and open the new round" }).click();
  await ada.waitForFunction((was) => document.getElementById("current").textContent !== was, first);
  // The round it closed is in the page's past rounds: when it ended, its links.
  await ada.locator("#rounds-box:not([hidden]) #rounds tr").first().waitFor();
  const past = await ada.$$eval("#rounds tr", (rows) =>
    rows.map((tr) => ({
      round: tr.dataset.round,
      when: tr.querySelector("time")?.textContent ?? "",
      links: [...tr.querySelectorAll("a")].map((a) => [a.textContent, a.getAttribute("href")]),
    })),
  );
  assert.equal(past.length, 1, JSON.stringify(past));
  assert.doesNotMatch(past[0].when, /^$|^\d{4}-/, "a time for the reader");
  const [onProjector, csv, json] = past[0].links;
  assert.equal(onProjector[0], "Open on the projector");
  assert.match(
    onProjector[1],
    new RegExp(`/c/${codeA}/projector\\?key=.+&round=${past[0].round}$`),
  );
  assert.deepEqual(
    [csv, json].map(([text, href]) => [text, href]),
    [
      ["CSV", `/c/${codeA}/api/export.csv?challenge=${past[0].round}`],
      ["JSON", `/c/${codeA}/api/export.json?challenge=${past[0].round}`],
    ],
  );
  const exported = await ada.evaluate((href) => fetch(href).then((r) => r.status), json[1]);
  assert.equal(exported, 200);
  // Two students' games: one row each, ranked, with their games counted.
  await sendGames(`/c/${codeA}`, 77, ["Mia", "Finn"]);
  await ada.waitForFunction(
    () => document.querySelectorAll("#entries tbody tr[data-entry]").length === 2,
  );
  const columns = await ada.locator("#entries th").allTextContents();
  assert.ok(columns.includes("Games"), columns.join("|"));
  const firstRow = ada.locator("#entries tbody tr").first();
  const before = await firstRow.locator("td").nth(1).textContent();
  // Rename in place (Enter saves), then hide and undo, by keyboard and pointer.
  await firstRow.getByRole("button", { name: "Rename" }).click();
  // The box comes with the table's next drawing, focused: type only then.
  await ada.locator("form.rename input").waitFor();
  await ada.waitForFunction(() => document.activeElement?.matches("form.rename input"));
  await ada.keyboard.press("Control+a");
  await ada.keyboard.type("Mia K.");
  await ada.keyboard.press("Enter");
  await ada.waitForFunction(() =>
    document.getElementById("entries").textContent.includes("Mia K."),
  );
  assert.notEqual(before, "Mia K.");
  const renamed = ada.locator("#entries tbody tr", { hasText: "Mia K." });
  await renamed.getByRole("button", { name: "Hide student" }).click();
  await ada.locator("#entries tbody tr.hidden", { hasText: "Mia K." }).waitFor();
  await renamed.getByRole("button", { name: "Show again" }).click();
  await ada.locator("#entries tbody tr.hidden").waitFor({ state: "detached" });
  await ada.evaluate(() => window.scrollTo(0, 0));
  await ada.screenshot({ path: join(SHOTS, "console-lecturer.png") });
  await ada.screenshot({ path: join(SHOTS, "console-lecturer-full.png"), fullPage: true });
  await ada.emulateMedia({ media: "print" });
  await ada.screenshot({ path: join(SHOTS, "console-lecturer-print.png"), fullPage: true });
  await ada.emulateMedia({ media: "screen" });
  // The reload keeps the page (the cookie), never re-posts: still the second round.
  const second = await ada.textContent("#current");
  await ada.reload();
  await ada.waitForFunction(() => document.getElementById("current").textContent !== "");
  assert.equal(await ada.textContent("#current"), second);

  await admin.goto(`${server.base}/admin`);
  await admin.screenshot({ path: join(SHOTS, "console-admin.png"), fullPage: true });
  console.log(`screenshots in ${SHOTS}`);
  // Only Bo's two refusals (the page and the API call) are logged as failed loads.
  const refused = errors.filter((e) => /status of 403/.test(e));
  assert.equal(refused.length, 2, errors.join("\n"));
  assert.deepEqual(
    errors.filter((e) => !/status of 403/.test(e)),
    [],
  );
});
