// The two themes measured in screenshot pixels (issue 48): every text and line at 7:1 or
// more against its background (WCAG's contrast of relative luminances), the atoms told apart
// from the wall (3:1) and from each other (each sphere's rim darker than its face).
import assert from "node:assert/strict";
import { existsSync, mkdirSync } from "node:fs";
import { after, before, test } from "node:test";
import { launch, openPage, PAGE } from "./browser.mjs";
import { decodePng, pixel } from "./png.mjs";

let browser;
before(async () => {
  assert.ok(existsSync(PAGE), `${PAGE} is missing: run npm run build first`);
  browser = await launch();
});
after(async () => browser?.close());

const lin = (c) => {
  const v = c / 255;
  return v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4;
};
const luminance = ([r, g, b]) => 0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b);
const contrast = (a, b) => {
  const [x, y] = [luminance(a), luminance(b)].sort((p, q) => q - p);
  return (x + 0.05) / (y + 0.05);
};

/** A region's background (its most frequent colour) and its ink (the pixel farthest from
 * it in contrast), and their contrast. */
function inkOn(img, [x0, y0, w, h]) {
  const counts = new Map();
  const px = [];
  for (let y = Math.round(y0); y < y0 + h; y++)
    for (let x = Math.round(x0); x < x0 + w; x++) {
      const p = pixel(img, x, y).slice(0, 3);
      px.push(p);
      const k = p.join(",");
      counts.set(k, (counts.get(k) ?? 0) + 1);
    }
  const bg = [...counts]
    .sort((a, b) => b[1] - a[1])[0][0]
    .split(",")
    .map(Number);
  let ink = bg;
  for (const p of px) if (contrast(p, bg) > contrast(ink, bg)) ink = p;
  return { bg, ink, ratio: contrast(ink, bg) };
}

/** Logical rect -> CSS px rect on the screenshot. */
const onScreen = (l, [x, y, w, h]) => [
  l.offsetX + x * l.scale,
  l.offsetY + y * l.scale,
  w * l.scale,
  h * l.scale,
];

async function shoot(theme, keys = []) {
  const { page, log } = await openPage(browser, {
    viewport: { width: 1000, height: 720 },
    query: `?theme=${theme}&seed=4`,
  });
  for (const k of keys) await page.keyboard.press(k);
  // Two display frames, still paused: the start hint shows.
  await page.evaluate(
    () => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))),
  );
  const buf = await page.screenshot();
  if (process.env.EVAPCOOL_SHOTS) {
    mkdirSync(process.env.EVAPCOOL_SHOTS, { recursive: true });
    await page.screenshot({
      path: `${process.env.EVAPCOOL_SHOTS}/theme-${theme}${keys.length ? "-settings" : ""}.png`,
    });
  }
  const info = await page.evaluate(() => {
    const app = window.evapcool.app;
    const l = app.layout;
    const sim = app.game.sim;
    const a = sim.trapped();
    return {
      layout: {
        offsetX: l.offsetX,
        offsetY: l.offsetY,
        scale: l.scale,
        slider: l.slider,
        knob: l.knobRadius,
      },
      geo: window.evapcool.geometry,
      atoms: Array.from({ length: a.count }, (_, i) => [a.x[i], a.y[i], a.radius[i]]),
      origin: [sim.room ? 0 : 0],
      targets: app.targets.map((t) => t.rect),
    };
  });
  assert.deepEqual(log.errors, []);
  await page.close();
  return { img: decodePng(buf), ...info };
}

for (const theme of ["dark", "projector"]) {
  test(`${theme}: words and lines at 7:1, atoms apart from the wall and each other`, async () => {
    const { img, layout: l, geo } = await shoot(theme);
    const P = geo.PLAY_RECT;
    const regions = {
      title: [200, 4, 240, geo.BORDER_TOP - 8],
      "speed line": [6, 8, 150, geo.BORDER_TOP - 16],
      "thermometer's T": [geo.THERMO_X - 14, 0, 28, geo.BORDER_TOP + 6],
      "slider label": [l.slider.x, l.slider.y + l.slider.h + l.knob + 2, l.slider.w, 30],
      "slider track": [l.slider.x + 4, l.slider.y - 6, 40, l.slider.h + 12],
      "start hint": [P.x + 60, P.y + 24, P.w - 120, 32],
      "cup wall": [P.x + 2, P.y + 100, 60, 40],
    };
    const low = [];
    for (const [name, r] of Object.entries(regions)) {
      const m = inkOn(img, onScreen(l, r));
      if (m.ratio < 7) low.push(`${name}: ${m.ratio.toFixed(2)} (${m.ink} on ${m.bg})`);
    }
    assert.deepEqual(low, [], `${theme}: below 7:1`);
    // Atoms: face against the black wall at 3:1 or more; the rim darker than the face
    // at 2.5:1 (two touching atoms show a dark seam).
    const faces = [];
    const rims = [];
    for (let y = Math.round(l.offsetY + P.y * l.scale); y < l.offsetY + (P.y + P.h) * l.scale; y++)
      for (
        let x = Math.round(l.offsetX + P.x * l.scale);
        x < l.offsetX + (P.x + P.w) * l.scale;
        x++
      ) {
        const p = pixel(img, x, y);
        if (p[2] > p[0] + 90) (luminance(p) > 0.1 ? faces : rims).push(p);
      }
    assert.ok(faces.length > 1000, `${faces.length} atom pixels`);
    const lum = faces.map(luminance).sort((a, b) => a - b);
    const median = lum[lum.length >> 1];
    assert.ok(
      (median + 0.05) / 0.05 >= 3,
      `atoms on the wall: ${((median + 0.05) / 0.05).toFixed(2)}`,
    );
    const darkest = Math.min(...[...faces, ...rims].map(luminance));
    assert.ok((median + 0.05) / (darkest + 0.05) >= 2.5, `rim against face ${median} / ${darkest}`);
  });

  test(`${theme}: the settings screen's words at 7:1`, async () => {
    const { img, layout: l, targets } = await shoot(theme, ["o"]);
    const low = [];
    // Each row (its label and value, both its arrows) and every button.
    for (const r of targets) {
      const m = inkOn(img, onScreen(l, [r.x, r.y, r.w, r.h]));
      if (m.ratio < 7) low.push(`${JSON.stringify(r)}: ${m.ratio.toFixed(2)}`);
    }
    assert.deepEqual(low, []);
  });
}
