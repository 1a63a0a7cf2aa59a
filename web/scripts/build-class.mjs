/**
 * `npm run build`'s second part: the class server's pages (src/classroom/*), each entry's
 * script (one IIFE, minified) and stylesheet written to src/evapcool/web/class/ in the
 * Python package, which inlines them with their CSP hashes. CI checks they equal a fresh build.
 */
import { mkdirSync, renameSync, writeFileSync } from "node:fs";
import { resolve } from "node:path";
import { build } from "vite";

const WEB = resolve(import.meta.dirname, "..");
/** Where the Python package keeps them (package data, see pyproject.toml). */
export const CLASS_DIR = resolve(WEB, "../src/evapcool/web/class");
/** The pages' entries: src/classroom/NAME.ts, each importing its NAME.css. */
export const ENTRIES = ["projector", "lecturer", "console"];

/** The built script and stylesheet of one entry. */
async function bundle(name) {
  const out = await build({
    configFile: false,
    root: WEB,
    logLevel: "warn",
    build: {
      write: false,
      target: "es2022",
      minify: true,
      cssMinify: true,
      reportCompressedSize: false,
      lib: { entry: resolve(WEB, `src/classroom/${name}.ts`), formats: ["iife"], name },
    },
  });
  const files = (Array.isArray(out) ? out : [out]).flatMap((o) => o.output);
  const script = files.find((f) => f.type === "chunk" && f.isEntry);
  const styles = files.filter((f) => f.type === "asset" && f.fileName.endsWith(".css"));
  if (!script || styles.length !== 1 || files.length !== 2) {
    throw new Error(`${name}: expected one script and one stylesheet, got ${files.length} files`);
  }
  return { js: script.code.trim(), css: String(styles[0].source).trim() };
}

/** Write a file whole or not at all (a reader never sees half of it). */
function writeAtomic(path, text) {
  const part = `${path}.part`;
  writeFileSync(part, text);
  renameSync(part, path);
}

mkdirSync(CLASS_DIR, { recursive: true });
for (const name of ENTRIES) {
  const { js, css } = await bundle(name);
  // Inlined in <script> and <style>: a closing tag inside would end the element early.
  if (/<\/script/i.test(js) || /<\/style/i.test(css)) {
    throw new Error(`${name}: the built code holds a closing tag`);
  }
  writeAtomic(resolve(CLASS_DIR, `${name}.js`), `${js}\n`);
  writeAtomic(resolve(CLASS_DIR, `${name}.css`), `${css}\n`);
}
