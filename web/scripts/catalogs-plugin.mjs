/**
 * The message catalogs for the page (issue 23): `import "virtual:evapcool-catalogs"` gives
 * every locale, English first, each cut to the keys the page's code names (the desktop's and
 * the class server's own words stay out). They travel packed (scripts/packing.mjs) as one
 * table: the locales' headers, the keys once, then each locale's messages in the keys' order;
 * the module unpacks them at import. Used by vite.config.ts, vitest.config.ts and
 * scripts/run.mjs (plain JavaScript).
 */
import { readdirSync, readFileSync } from "node:fs";
import { join, resolve } from "node:path";
import { pack, UNPACK, unpackModule } from "./packing.mjs";

const VIRTUAL = "virtual:evapcool-catalogs";
const RESOLVED = "\0evapcool-catalogs";
/** The catalogs' folder seen from web/ (the Vite root): one JSON file per locale. */
export const LOCALES_FOLDER = "../src/evapcool/locales";
/**
 * English words the page shows where nothing unpacks (no DecompressionStream): it cannot
 * start there, and says so (src/app/main.ts).
 */
export const WITHOUT_UNPACKING = ["page.fatal"];
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
    resolveId: (id) => (id === VIRTUAL ? RESOLVED : unpackModule.resolveId(id)),
    load(id) {
      if (id !== RESOLVED) return unpackModule.load(id);
      for (const f of readdirSync(dir)) this.addWatchFile(join(dir, f));
      // The page's own keys only: the desktop's words stay out of its file.
      const all = pageCatalogs(dir, allKeys ? null : keysInSource(src));
      const keys = [...new Set(all.flatMap((c) => Object.keys(c.messages)))];
      // A key a locale lacks is null: the page then shows it in English (src/i18n.ts).
      const table = [
        all.map((c) => c.meta),
        keys,
        ...all.map((c) => keys.map((k) => c.messages[k] ?? null)),
      ];
      const raw = Buffer.from(JSON.stringify(table));
      const packed = pack(raw);
      const [english] = all;
      const fallback = {
        meta: english.meta,
        messages: Object.fromEntries(WITHOUT_UNPACKING.map((k) => [k, english.messages[k]])),
      };
      cost =
        `evapcool: the page's ${all.length} message catalogs inlined: ${keys.length} keys,` +
        ` ${raw.length} bytes packed to ${packed.length} (deflate, base 85)`;
      return `import { unpack } from "${UNPACK}";
async function read() {
  try {
    const [metas, keys, ...locales] = JSON.parse(new TextDecoder().decode(await unpack(${JSON.stringify(packed)})));
    return metas.map((meta, c) => ({
      meta,
      messages: Object.fromEntries(keys.map((k, i) => [k, locales[c][i]]).filter(([, m]) => m !== null)),
    }));
  } catch {
    return [${JSON.stringify(fallback)}];
  }
}
export const catalogs = await read();`;
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
