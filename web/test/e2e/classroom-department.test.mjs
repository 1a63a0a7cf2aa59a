// A department's class server in real Chromium (issue 35): a real `evapcool class
// --department` on 127.0.0.1; the administrator's call makes a lecturer and the lecturer
// a class; a phone types the join code at the server's root and lands in the class's game
// page, which talks to the class's API; the class's lecturer page opens a challenge and
// its projector (at the class's path) follows it; the phone's verified game reaches both;
// the lecturer page's link goes back to the lecturer's list of classes.
// No page may log a script error or a blocked resource.
import assert from "node:assert/strict";
import { after, before, test } from "node:test";
import {
  departmentClass,
  play,
  closeServerAndBrowser,
  startServerAndBrowser,
  watchErrors,
} from "./class-server.mjs";
import { pythonWithEvapcool } from "./python.mjs";

const PYTHON = pythonWithEvapcool(); // none: this file fails, saying so (python.mjs)
const SEED = 77;

let server;
let browser;

before(async () => {
  ({ server, browser } = await startServerAndBrowser(PYTHON, "evapcool-dept-", {
    department: true,
  }));
});

after(() => closeServerAndBrowser({ server, browser }));

test(
  "a class of a department: join by code, its lecturer's page and projector",
  { timeout: 600_000 },
  async () => {
    const errors = [];
    const watch = watchErrors(errors);
    const { lecturerToken, room, base } = await departmentClass(server);

    const lecturer = watch(await browser.newPage({ viewport: { width: 1280, height: 900 } }));
    await lecturer.goto(`${server.base}${base}/lecturer?token=${lecturerToken}`);
    const link = await lecturer.getAttribute("#projector", "href");
    assert.ok(link.startsWith(`${base}/projector?key=`), link);
    await lecturer.fill("#seed", String(SEED));
    await lecturer.getByRole("button", { name: "Open", exact: true }).click();
    await lecturer.waitForFunction(() =>
      document.getElementById("current").textContent.includes("Open"),
    );
    const projector = watch(await browser.newPage({ viewport: { width: 1920, height: 1080 } }));
    await projector.goto(`${server.base}${link}`);
    await projector.waitForFunction(() =>
      /^Open/.test(document.getElementById("state").textContent),
    );
    // The join code in large type (issue 45), the QR code holding the class's address.
    assert.equal(await projector.textContent("#join-code"), room.code);

    const context = await browser.newContext({
      viewport: { width: 390, height: 844 },
      isMobile: true,
      hasTouch: true,
    });
    const phone = watch(await context.newPage());
    await phone.goto(`${server.base}/`);
    await phone.fill("#code", room.code.toLowerCase().replace(/(...)/, "$1 "));
    await phone.tap("button");
    await phone.waitForURL(`${server.base}${base}/`);
    await phone.waitForFunction(() => window.evapcool !== undefined);
    await phone.waitForSelector("#join input");
    const joined = phone.waitForResponse((r) => r.url().endsWith(`${base}/api/join`));
    await phone.fill("#join input", "Zoë");
    await phone.tap("#join button");
    assert.equal((await joined).status(), 200);
    await phone.waitForFunction(() => window.evapcool.app.play.fixedSeed !== null);
    assert.equal(await phone.evaluate(() => window.evapcool.app.play.fixedSeed), SEED);
    const s = await play(phone, 100);
    assert.equal(s.won, true);
    await phone.waitForFunction(
      () => /Verified/.test(document.getElementById("classbar").textContent),
      null,
      { timeout: 30_000 },
    );
    await projector.waitForFunction(() =>
      document.getElementById("board").textContent.includes("Zoë"),
    );
    await lecturer.waitForFunction(() =>
      document.getElementById("entries").textContent.includes("Zoë"),
    );

    const admin = watch(await browser.newPage());
    await admin.goto(`${server.base}/admin?token=${server.token}`);
    assert.ok((await admin.textContent("body")).includes(room.code));
    // The class's page links back to its lecturer's list of classes (the cookie keeps the token).
    await lecturer.getByRole("link", { name: "Back to my classes" }).click();
    await lecturer.waitForURL(`${server.base}/lecturer`);
    assert.ok((await lecturer.textContent("h1")).includes("Ada"));
    assert.ok((await lecturer.textContent("body")).includes(room.code));
    assert.deepEqual(errors, []);
  },
);
