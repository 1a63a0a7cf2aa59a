// Every message of every locale (and the pseudo-locale, 40 % longer) measured with canvas
// measureText in real headless Chromium, in the page's own font stack and sizes, against
// the box the view draws it in (logical px: every layout scales them alike, so the phone in
// portrait holds exactly these boxes). Wrapped messages: each unbreakable piece must fit.
import { resolve } from "node:path";
import { pathToFileURL } from "node:url";
import { chromium } from "playwright-core";
import { afterAll, beforeAll, describe, expect, it } from "vitest";
import { CATALOGS, PSEUDO, createTranslator, languageNames, useLocale } from "../src/i18n";
import { DEFAULTS, describe as settingRows } from "../src/game/settings";
import { PLAY_RECT, SCENE_W } from "../src/view/geometry";
import { breakUnits, fontFor } from "../src/view/text";
import { keysInSource, NOT_ON_THE_PAGE } from "../scripts/catalogs-plugin.mjs";

const PAGE = pathToFileURL(resolve(import.meta.dirname, "../../src/evapcool/web/evapcool.html"));
/** The messages the page shows (the build bundles these; the desktop's are measured by
 * tests/test_i18n_fits.py in its own boxes). */
const NAMED = keysInSource(resolve(import.meta.dirname, "../src"));
const PAGE_KEYS = Object.keys(CATALOGS.en.messages).filter(
  (k) => NAMED.has(k) && !NOT_ON_THE_PAGE.some((p) => k.startsWith(p)),
);
const PLAY_W = PLAY_RECT.w;
/** overlay()'s panel. */
const PANEL_W = PLAY_W - 24;
const ARGS: Record<string, string | number> = {};
for (const [key, text] of Object.entries(CATALOGS.en.messages))
  for (const m of text.matchAll(/\{(\w+)/g)) ARGS[m[1]] = key.includes("address") ? "abc" : 12345;
Object.assign(ARGS, { name: "Anonymous", code: "EC1.eNqrVkrL...", edition: "desktop" });
Object.assign(ARGS, { problem: "disk full", reason: "lose.stuck", mode: "autopilot" });

/** Drawn in one line: [size, box width] (scene.ts, overlays.ts, widgets.ts). Titles that
 * shrink are measured at their smallest size. */
const BOXES: Record<string, [number, number]> = {
  "app.title": [16, SCENE_W - 380],
  "status.speed": [12, 170],
  "controls.trap_height": [24, PLAY_W / 2],
  "win.score_big": [40, PLAY_W - 20],
  "win.condensed": [16, PLAY_W - 20],
  "lose.too_few": [26, PLAY_W - 20],
  "start.press_space": [16, PLAY_W - 20],
  "start.tap_play": [16, PLAY_W - 20],
  "win.top10": [26, PLAY_W - 80],
  "win.store_or_skip": [22, PLAY_W - 180],
  "win.name_full": [22, 160],
  "scores.title": [18, PANEL_W - 20],
  "settings.title": [18, PANEL_W - 20],
  "verify.title": [18, PANEL_W - 20],
  "page.copy_code": [24, PLAY_W - 40],
  "chart.energies": [12, PLAY_W / 2],
  "chart.path": [12, PLAY_W / 2],
};
/** Rows of text buttons (24 px, 28 px padding, 16 px gaps) within their panel's width. */
const BUTTON_ROWS: Array<[string[], number]> = [
  [["button.close", "scores.clear", "button.verify_codes"], PANEL_W],
  [["scores.clear_yes", "button.no"], PANEL_W],
  [["button.next_player", "button.close"], PANEL_W],
  [["button.save", "button.cancel"], PANEL_W],
  [["button.verify", "button.close"], PANEL_W],
  [["button.store", "button.skip"], PLAY_W - 60],
];
/** Said, not drawn: the live region, the status line, labels and the document's words
 * (the browser lays these out), the class form (HTML that wraps). */
const SPOKEN =
  /^(page\.(won_spoken|paused|playing|speed_spoken|energy_|path_|panel_shown|restarted|height_spoken|status|doc_title|about|canvas_|name_label|class_name_label|class_join|fatal)|control\.|verify\.(label|placeholder|summary)|hint\.touch\.clear_confirm_spoken|scores\.clear_confirm|autopilot\.label|notice\.mode)/;
/** Wrapped where drawn (notices, help rows, hints, the too-few lines, footers, verify lines):
 * [size, width] of each piece's line; everything else not listed above is a notice. */
function wrapBox(key: string): [number, number] {
  if (key.startsWith("lose.") || key.startsWith("hint.touch.try")) return [26, PLAY_W - 40];
  if (key.startsWith("help.") || key.startsWith("controls.")) return [16, PLAY_W / 2];
  if (key.startsWith("chart.")) return [15, PLAY_W / 2 - 40];
  if (key.startsWith("table.") || key.startsWith("verify.")) return [22, PANEL_W - 36];
  return [22, PLAY_W - 32];
}

let browser: Awaited<ReturnType<typeof chromium.launch>>;
let measure: (font: string, texts: string[]) => Promise<number[]>;

beforeAll(async () => {
  browser = await chromium.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    args: ["--no-sandbox", "--disable-gpu"],
  });
  const page = await browser.newPage();
  await page.goto(PAGE.href);
  await page.evaluate(() => document.fonts.ready);
  measure = (font, texts) =>
    page.evaluate(
      ([f, ts]) => {
        const ctx = document.createElement("canvas").getContext("2d")!;
        ctx.font = f;
        return ts.map((t) => ctx.measureText(t).width);
      },
      [font, texts] as const,
    );
}, 60_000);

afterAll(async () => {
  await browser?.close();
});

/** Keys whose drawn text is wider than its box, with the widths. */
async function overflows(tag: string): Promise<string[]> {
  const t = createTranslator(tag);
  // The pseudo-locale's padding stands for more words: it may break every 8 characters.
  const text = (key: string) =>
    t
      .t(key, { ...ARGS, reason: key.startsWith("hint") ? t.t("lose.stuck") : ARGS.reason })
      .replace(/~{8}/g, "~~~~~~~~ ");
  const out: string[] = [];
  const check = async (what: string, size: number, width: number, texts: string[]) => {
    const drawn = Math.max(...(await measure(fontFor(size), texts)));
    if (drawn > width) out.push(`${what} ${Math.round(drawn)} > ${Math.round(width)}`);
  };
  const inRows = new Set(BUTTON_ROWS.flatMap(([keys]) => keys));
  for (const key of PAGE_KEYS) {
    if (SPOKEN.test(key) || inRows.has(key)) continue;
    if (key in BOXES) await check(key, ...BOXES[key], [text(key)]);
    else {
      const [size, width] = wrapBox(key);
      await check(
        key,
        size,
        width,
        breakUnits(text(key)).map((u) => u.piece),
      );
    }
  }
  for (const [keys, width] of BUTTON_ROWS) {
    const widths = await measure(fontFor(24), keys.map(text));
    const total = widths.reduce((a, w) => a + w + 28, 0) + 16 * (keys.length - 1);
    if (total > width) out.push(`${keys.join("+")} ${Math.round(total)} > ${width}`);
  }
  // The settings rows: the label, then "< value >" at the right (overlays.drawSettings).
  useLocale(tag);
  try {
    for (const language of ["auto", ...languageNames().map((l) => l.tag)]) {
      const name = languageNames().find((l) => l.tag === language)?.name;
      const rows = [
        ...settingRows({ ...DEFAULTS, nAtoms: 10000, radius: 2.5, escape: "knife" }),
        [t.t("settings.language"), name ?? t.t("settings.language_browser")],
      ];
      for (const [label, value] of rows) {
        // The label shrinks to 12 at least beside the value (24).
        const [lw] = await measure(fontFor(12), [label]);
        const [vw] = await measure(fontFor(24), [value]);
        if (34 + lw + vw + 62 > PANEL_W) out.push(`settings row ${label} | ${value}`);
      }
    }
  } finally {
    useLocale("en");
  }
  return [...new Set(out)];
}

describe("fits in Chromium", () => {
  it("detects an overflow", async () => {
    const [w] = await measure(fontFor(22), ["W".repeat(80)]);
    expect(w).toBeGreaterThan(PLAY_W);
  });

  // Every page message of a locale measured: seconds on a shared, busy machine.
  it.each([...Object.keys(CATALOGS), PSEUDO])(
    "%s fits its boxes",
    async (tag) => {
      expect(await overflows(tag)).toEqual([]);
    },
    30_000,
  );
});
