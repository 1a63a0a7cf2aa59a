/**
 * The message catalogs for the page (issue 23): `import "virtual:evapcool-catalogs"` gives
 * English as an object (the words the page can always show) and the other locales as one
 * deflate-raw stream in base64 (unpacked by src/i18n.ts with DecompressionStream), each cut to
 * the keys the page's code names: the desktop's and the class server's own words stay out.
 * Used by vite.config.ts, vitest.config.ts and scripts/run.mjs (plain JavaScript).
 */
import { readdirSync, readFileSync } from "node:fs";
import { join, resolve } from "node:path";
import { deflateRawSync } from "node:zlib";

const VIRTUAL = "virtual:evapcool-catalogs";
const RESOLVED = "\0evapcool-catalogs";
/** The catalogs' folder seen from web/ (the Vite root): one JSON file per locale. */
export const LOCALES_FOLDER = "../src/evapcool/locales";
/** Keys the page never shows: the desktop's own screens and the class server's pages. */
export const NOT_ON_THE_PAGE = ["class.", "desk.", "progress.", "debrief."];
// The class server's console (issue 45) gets its words from the server; a student's own
// lines (`console.student.`) are the page's.
NOT_ON_THE_PAGE.push(
  ...["admin.", "lecturer.", "projector.", "todo.", "error.", "refused", "home", "copy"].map(
    (k) => `console.${k}`,
  ),
  ...["console.copied", "console.sure", "console.rename"],
);

/** The message keys the page's code names (as quoted literals in src/**\/*.ts). */
export function keysInSource(srcDir) {
  const found = new Set();
  const walk = (d) => {
    for (const entry of readdirSync(d, { withFileTypes: true })) {
      const path = join(d, entry.name);
      if (entry.isDirectory()) walk(path);
      else if (entry.name.endsWith(".ts"))
        for (const m of readFileSync(path, "utf8").matchAll(
          /["'`]([a-z_]+(?:\.[a-z0-9_]+)+)["'`]/g,
        ))
          found.add(m[1]);
    }
  };
  walk(srcDir);
  return found;
}

/** Every catalog in `dir`, English first, each with the keys in `keep` (or all the page's). */
export function pageCatalogs(dir, keep = null) {
  const files = readdirSync(dir)
    .filter((f) => f.endsWith(".json"))
    .sort((a, b) => (a === "en.json" ? -1 : b === "en.json" ? 1 : a.localeCompare(b)));
  return files.map((f) => {
    const catalog = JSON.parse(readFileSync(join(dir, f), "utf8"));
    const messages = Object.fromEntries(
      Object.entries(catalog.messages).filter(
        ([key]) =>
          !NOT_ON_THE_PAGE.some((prefix) => key.startsWith(prefix)) &&
          (keep === null || keep.has(key)),
      ),
    );
    return { meta: catalog.meta, messages };
  });
}

function escapeHtml(text) {
  return text.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;");
}

/**
 * The Vite plugin; the build prints what the catalogs cost the page. `allKeys`: every
 * message (the unit tests check the formatting of the desktop's messages too).
 */
export function catalogs({ allKeys = false } = {}) {
  let dir = "";
  let src = "";
  let cost = "";
  return {
    name: "evapcool-catalogs",
    configResolved(config) {
      dir = resolve(config.root, LOCALES_FOLDER);
      src = resolve(config.root, "src");
    },
    resolveId: (id) => (id === VIRTUAL ? RESOLVED : null),
    load(id) {
      if (id !== RESOLVED) return null;
      for (const f of readdirSync(dir)) this.addWatchFile(join(dir, f));
      // The page's own keys only: the desktop's words stay out of its file.
      const [english, ...others] = pageCatalogs(dir, allKeys ? null : keysInSource(src));
      const plain = JSON.stringify(english);
      const raw = Buffer.from(JSON.stringify(others));
      const packed = deflateRawSync(raw, { level: 9 }).toString("base64");
      cost =
        `evapcool: the page's ${others.length + 1} message catalogs inlined: English ${Buffer.byteLength(plain)} bytes,` +
        ` the other ${others.length} ${raw.length} bytes packed to ${packed.length} (deflate, base64)`;
      return `export const english = ${plain};\nexport const packed = ${JSON.stringify(packed)};`;
    },
    // Without JavaScript nothing can choose a language: the page says so in every one.
    transformIndexHtml(html) {
      const say = pageCatalogs(dir)
        .map(({ meta, messages }, k) => {
          const id = k === 0 ? ' id="noscript"' : "";
          return `<p${id} lang="${meta.tag}" dir="${meta.direction}">${escapeHtml(messages["page.noscript"])}</p>`;
        })
        .join("");
      const pattern = /<p id="noscript">[^<]*<\/p>/;
      if (!pattern.test(html)) throw new Error('index.html lacks <p id="noscript">');
      return html.replace(pattern, () => say);
    },
    generateBundle() {
      if (cost) console.log(cost);
    },
  };
}
