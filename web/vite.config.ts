/**
 * `npm run build` writes dist/evapcool.html: one self-contained page (script, styles and
 * font inline; no other file, no network request), the same bytes from the same sources.
 */
import { copyFileSync } from "node:fs";
import { resolve } from "node:path";
import { defineConfig, type Plugin } from "vite";
import { wasmCore } from "./scripts/wasm-plugin.mjs";
import { catalogs } from "./scripts/catalogs-plugin.mjs";
import { packedWorkers } from "./scripts/worker-plugin.mjs";

/** The copy shipped in the Python package (`evapcool web`); CI checks it equals a fresh build. */
const PACKAGE_COPY = resolve(import.meta.dirname, "../src/evapcool/web/evapcool.html");

/** Inline the built script and stylesheet into the HTML and drop the separate files. */
function singleFile(): Plugin {
  return {
    name: "evapcool-single-file",
    enforce: "post",
    generateBundle(_options, bundle) {
      const html = Object.values(bundle).find((f) => f.fileName.endsWith(".html"));
      if (!html || html.type !== "asset") throw new Error("no HTML page in the bundle");
      let page = String(html.source);
      for (const [name, file] of Object.entries(bundle)) {
        if (file === html) continue;
        if (file.type === "chunk" && file.isEntry) {
          const tag = new RegExp(`<script[^>]*src="[^"]*${escape(file.fileName)}"[^>]*></script>`);
          // A "</script" inside the code would end the element early.
          const code = file.code.replace(/<\/(script)/gi, "<\\/$1");
          page = replaceOnce(page, tag, `<script type="module">${code}</script>`);
        } else if (file.type === "asset" && file.fileName.endsWith(".css")) {
          const tag = new RegExp(`<link[^>]*href="[^"]*${escape(file.fileName)}"[^>]*>`);
          page = replaceOnce(page, tag, `<style>${String(file.source)}</style>`);
        } else {
          throw new Error(`${file.fileName} would be a second file; inline it`);
        }
        delete bundle[name];
      }
      html.source = page;
    },
  };
}

function escape(s: string): string {
  return s.replace(/[.*+?^${}()|[\]\\]/g, "\\$&");
}

function replaceOnce(text: string, pattern: RegExp, value: string): string {
  if (!pattern.test(text)) throw new Error(`not found in the page: ${pattern}`);
  return text.replace(pattern, () => value);
}

export default defineConfig({
  base: "./",
  build: {
    outDir: "dist",
    emptyOutDir: true,
    target: "es2022",
    assetsInlineLimit: 1_000_000,
    cssCodeSplit: false,
    modulePreload: false,
    reportCompressedSize: false,
    rollupOptions: {
      input: "index.html",
    },
  },
  plugins: [
    // The physics worker's own bundle (src/app/main.ts imports it packed) gets the core from
    // the page in its start message: the page holds one copy.
    packedWorkers({ plugins: () => [wasmCore({ fromPage: true })] }),
    wasmCore(),
    catalogs(),
    singleFile(),
    {
      name: "evapcool-page-name",
      enforce: "post",
      generateBundle(_o, bundle) {
        const html = bundle["index.html"];
        if (html) {
          html.fileName = "evapcool.html";
        }
      },
      writeBundle(options) {
        copyFileSync(resolve(options.dir ?? "dist", "evapcool.html"), PACKAGE_COPY);
      },
    },
  ],
});
