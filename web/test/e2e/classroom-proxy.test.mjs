// A department's class server behind the class guide's Caddy, in real Chromium over HTTPS
// and HTTP/2: `evapcool class --department --public-url https://class.example.edu:PORT` on
// 127.0.0.1, Debian's Caddy in front of it with the guide's site block (docs/class.md; only
// the ports put in, the certificate from Caddy's own local authority), and the browser told
// that class.example.edu is 127.0.0.1. The lecturer's page opens a challenge, the projector
// shows the public address, a phone joins by code at the root, plays and is verified, and
// its name reaches the projector's stream through the proxy. No page may log an error or a
// blocked (mixed) resource.
import assert from "node:assert/strict";
import { spawn, spawnSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { after, before, test } from "node:test";
import { chromium } from "playwright-core";
import { CHROMIUM } from "./browser.mjs";
import {
  freePort,
  departmentClass,
  play,
  startClassServer,
  stopClassServer,
  watchErrors,
} from "./class-server.mjs";
import { optional, pythonWithEvapcool } from "./python.mjs";

const PYTHON = pythonWithEvapcool(); // none: this file fails, saying so (python.mjs)
const GUIDE = resolve(import.meta.dirname, "../../../docs/class.md");
const HOST = "class.example.edu";
const HAVE_CADDY = !spawnSync("caddy", ["version"]).error;
// Caddy is optional (the README says so): without it this file skips, and test-all says so.
const SKIP = !HAVE_CADDY && optional("Caddy is not installed (Debian: apt-get install caddy)");
const SEED = 77;

let server;
let caddy;
let folder;
let browser;
let publicUrl;

/** The guide's Caddyfile site block, on `port`, in front of the server at `upstream`. */
function siteBlock(port, upstream) {
  const text = readFileSync(GUIDE, "utf8");
  const from = text.indexOf("```text\n", text.indexOf("Caddy (`/etc/caddy/Caddyfile`)")) + 8;
  const block = text.slice(from, text.indexOf("```", from));
  const put = (s, a, b) => {
    assert.ok(s.includes(a), `the guide's Caddyfile no longer has ${a}`);
    return s.replace(a, b);
  };
  return put(
    put(block, `${HOST} {`, `${HOST}:${port} {`),
    "127.0.0.1:8765 127.0.0.1:8766",
    upstream,
  );
}

before(async () => {
  if (SKIP) return;
  const port = await freePort();
  publicUrl = `https://${HOST}:${port}`;
  server = await startClassServer(PYTHON, {
    prefix: "evapcool-proxied-",
    args: ["--department", "--public-url", publicUrl],
    token: /admin\?token=(\S+)/,
    readyPath: "/",
    tries: 150,
  });
  folder = mkdtempSync(join(tmpdir(), "evapcool-caddy-"));
  const options = [
    "{",
    "  admin off",
    "  default_bind 127.0.0.1",
    "  local_certs",
    "  skip_install_trust",
    `  http_port ${await freePort()}`,
    `  storage file_system ${folder}/data`,
    "  grace_period 2s",
    "}",
  ].join("\n");
  const conf = join(folder, "Caddyfile");
  writeFileSync(conf, `${options}\n${siteBlock(port, server.base.replace("http://", ""))}`);
  caddy = spawn("caddy", ["run", "--config", conf, "--adapter", "caddyfile"], {
    env: { ...process.env, HOME: folder, XDG_DATA_HOME: join(folder, "data") },
    stdio: "ignore",
  });
  browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: [
      "--no-sandbox",
      "--disable-gpu",
      "--disable-quic", // HTTP/2 over TCP, not Caddy's HTTP/3 offer
      `--host-resolver-rules=MAP ${HOST} 127.0.0.1`,
    ],
  });
});

after(async () => {
  await browser?.close();
  caddy?.kill("SIGKILL");
  await stopClassServer(server);
  if (folder) rmSync(folder, { recursive: true, force: true });
});

test("a department behind Caddy: HTTPS, HTTP/2, the public address", { skip: SKIP }, async () => {
  // Caddy's local authority is not the browser's: the certificate is Caddy's own business
  // here (tests/classroom/test_proxies.py checks it against that authority).
  const context = await browser.newContext({ ignoreHTTPSErrors: true });
  const errors = [];
  const watch = watchErrors(errors);
  const { lecturerToken, room, base } = await departmentClass(server);
  assert.equal(room.join, `${publicUrl}${base}/`);

  const lecturer = watch(await context.newPage());
  for (let k = 0; k < 100; k++) {
    // Caddy starts beside the server: wait until it serves
    try {
      const answer = await lecturer.goto(`${publicUrl}${base}/lecturer?token=${lecturerToken}`);
      if (answer.ok()) break;
    } catch {
      /* not listening yet */
    }
    await new Promise((r) => setTimeout(r, 200));
  }
  assert.equal(
    await lecturer.evaluate(() => performance.getEntriesByType("navigation")[0].nextHopProtocol),
    "h2",
  );
  const link = await lecturer.getAttribute("#projector", "href");
  await lecturer.fill("#seed", String(SEED));
  await lecturer.getByRole("button", { name: "Open", exact: true }).click();
  await lecturer.waitForFunction(() =>
    document.getElementById("current").textContent.includes("Open"),
  );
  const projector = watch(await context.newPage());
  await projector.setViewportSize({ width: 1920, height: 1080 });
  await projector.goto(`${publicUrl}${link}`);
  await projector.waitForFunction(() => /^Open/.test(document.getElementById("state").textContent));
  // The short public address (no scheme) and the class's join code (issue 45).
  const short = publicUrl.replace(/^\w+:\/\//, "").replace(/\/$/, "");
  assert.ok((await projector.textContent("#join")).includes(short));
  assert.equal(await projector.textContent("#join-code"), base.slice("/c/".length));
  assert.equal(await projector.locator("#loopback").count(), 0, "no 'phones cannot reach' warning");

  const phoneContext = await browser.newContext({
    ignoreHTTPSErrors: true,
    viewport: { width: 390, height: 844 },
    isMobile: true,
    hasTouch: true,
  });
  const phone = watch(await phoneContext.newPage());
  await phone.goto(`${publicUrl}/`);
  await phone.fill("#code", room.code);
  await phone.tap("button");
  await phone.waitForURL(`${publicUrl}${base}/`);
  await phone.waitForFunction(() => window.evapcool !== undefined);
  await phone.waitForSelector("#join input");
  await phone.fill("#join input", "Zoë");
  await phone.tap("#join button");
  await phone.waitForFunction(() => window.evapcool.app.play.fixedSeed !== null);
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
  assert.deepEqual(errors, []);
  await phoneContext.close();
  await context.close();
});
