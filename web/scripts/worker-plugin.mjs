/**
 * The page's workers packed (issue 37: the verify panel's worker kept the page under its
 * 300 KB): `import code from "./NAME.worker?packed"` is the worker bundled on its own
 * (minified, one script), packed as text (scripts/packing.mjs), about a third of its
 * JavaScript; the page unpacks it once (src/app/main.ts, with `virtual:evapcool-unpack`) and
 * starts each worker from it.
 * Plain JavaScript like the other plugins; types in worker-plugin.d.mts.
 */
import { build } from "vite";
import { pack, unpackModule } from "./packing.mjs";

const SUFFIX = "?packed";

/** The Vite plugin; `plugins` are the worker's own build's (e.g. the core handed by the page). */
export function packedWorkers({ plugins = () => [] } = {}) {
  let root = process.cwd();
  return {
    name: "evapcool-packed-worker",
    enforce: "pre",
    configResolved(config) {
      root = config.root;
    },
    async resolveId(id, importer) {
      if (!id.endsWith(SUFFIX)) return unpackModule.resolveId(id);
      const entry = await this.resolve(id.slice(0, -SUFFIX.length), importer);
      return entry ? `\0${entry.id}${SUFFIX}` : null;
    },
    async load(id) {
      if (!id.startsWith("\0") || !id.endsWith(SUFFIX)) return unpackModule.load(id);
      const entry = id.slice(1, -SUFFIX.length);
      this.addWatchFile(entry);
      const result = await build({
        configFile: false,
        logLevel: "error",
        root,
        plugins: plugins(),
        build: {
          write: false,
          target: "es2022",
          minify: true,
          rollupOptions: { input: entry, output: { format: "iife" } },
        },
      });
      const out = Array.isArray(result) ? result[0] : result;
      const code = out.output[0].code;
      return `export default ${JSON.stringify(pack(Buffer.from(code)))};`;
    },
  };
}
