/**
 * The WebAssembly engine core's build (issues 24, 32): compiles the one physics core, core/*.c
 * at the top of the repository (the Python package builds the same files natively,
 * setup.py), with Debian's clang and lld for wasm32 and serves the module packed as text
 * (scripts/packing.mjs) to `import "virtual:evapcool-wasm"` (src/physics/wasm.ts), so the page
 * stays one file. Used by vite.config.ts,
 * vitest.config.ts and the scripts' own builds (plain JavaScript: scripts/run.mjs loads it
 * in Node 20; types in wasm-plugin.d.mts).
 */
import { spawnSync } from "node:child_process";
import { mkdtempSync, readdirSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { pack, UNPACK, unpackModule } from "./packing.mjs";

const VIRTUAL = "virtual:evapcool-wasm";
const RESOLVED = "\0evapcool-wasm";
/** The core's C sources, core/ at the top of the repository, seen from web/ (the Vite root). */
export const CORE_FOLDER = "../core";

/**
 * IEEE arithmetic as written: no contraction into fused multiply-adds, no fast-math; link-time
 * optimisation so the kernels inline across the room files; no libc (-nostdlib). The linker
 * leaves out the function names and the target features (--strip-all): the page calls the
 * core by its exports only.
 */
export const CLANG_FLAGS = [
  "--target=wasm32",
  "-nostdlib",
  "-std=c11",
  "-O3",
  "-flto",
  "-ffp-contract=off",
  "-fno-fast-math",
  "-mbulk-memory", // struct copies as memory.copy: no libc memcpy to link
  // The pair scan's two lanes (core/tables.h), float-to-int without range-check branches,
  // sign extension: all three in every browser that has DecompressionStream (Chrome 103,
  // Firefox 113, Safari 16.4), which the page needs anyway.
  "-msimd128",
  "-mnontrapping-fptoint",
  "-msign-ext",
  "-Wall",
  "-Wextra",
  "-Werror",
  "-Wl,--no-entry",
  "-Wl,--lto-O3",
  "-Wl,--strip-all",
];

/** The compiler: `clang`, or another name (e.g. clang-14) from EVAPCOOL_CLANG. */
const CLANG = process.env.EVAPCOOL_CLANG || "clang";

const NO_CLANG = `evapcool: building the WebAssembly core needs ${CLANG} and lld (Debian: apt-get install clang lld)`;

/** An unsigned LEB128 number at bytes[at]: [value, the place after it]. */
function leb128(bytes, at) {
  let value = 0;
  for (let shift = 0; ; shift += 7) {
    const b = bytes[at++];
    value += (b & 0x7f) * 2 ** shift;
    if (b < 0x80) return [value, at];
  }
}

/**
 * The module without its "producers" section, which names the compiler's build ("Debian
 * clang version ..."): the page's bytes then depend on the compiler's code, not its vendor.
 */
function withoutProducers(bytes) {
  const kept = [bytes.subarray(0, 8)]; // magic and version
  for (let at = 8; at < bytes.length;) {
    const start = at;
    const [size, body] = leb128(bytes, at + 1);
    at = body + size;
    if (bytes[start] === 0) {
      const [length, name] = leb128(bytes, body);
      if (Buffer.from(bytes.subarray(name, name + length)).toString() === "producers") continue;
    }
    kept.push(bytes.subarray(start, at));
  }
  return new Uint8Array(Buffer.concat(kept));
}

/** The core's bytes, freshly compiled from the C sources in folder `dir`. */
export function compileCore(dir) {
  const sources = readdirSync(dir)
    .filter((f) => f.endsWith(".c"))
    .sort()
    .map((f) => join(dir, f));
  const tmp = mkdtempSync(join(tmpdir(), "evapcool-wasm-"));
  try {
    const out = join(tmp, "core.wasm");
    const run = spawnSync(CLANG, [...CLANG_FLAGS, "-o", out, ...sources], { encoding: "utf8" });
    if (run.error || /wasm-ld.*(not found|doesn't exist|No such file)/.test(run.stderr)) {
      console.error(NO_CLANG); // one clear line, not a stack trace
      process.exit(1);
    }
    if (run.status !== 0)
      throw new Error(`evapcool: the WebAssembly core did not compile:\n${run.stderr}`);
    return withoutProducers(new Uint8Array(readFileSync(out)));
  } finally {
    rmSync(tmp, { recursive: true, force: true });
  }
}

/**
 * The Vite plugin: `virtual:evapcool-wasm` is the compiled core's bytes (packed in the page,
 * unpacked at import), or none with `fromPage` (the physics worker's bundle: the page hands
 * it the core's bytes). A browser without DecompressionStream gets no bytes, and the page says
 * it cannot start (src/app/main.ts).
 */
export function wasmCore({ fromPage = false } = {}) {
  let dir = "";
  let bytes = 0;
  let packedLength = 0;
  return {
    name: "evapcool-wasm-core",
    configResolved(config) {
      dir = resolve(config.root, CORE_FOLDER);
    },
    buildStart() {
      if (spawnSync(CLANG, ["--version"]).error) {
        console.error(NO_CLANG); // one clear line, not a stack trace
        process.exit(1);
      }
    },
    resolveId: (id) => (id === VIRTUAL ? RESOLVED : unpackModule.resolveId(id)),
    load(id) {
      if (id !== RESOLVED) return unpackModule.load(id);
      if (fromPage) return `export default new Uint8Array(0);`;
      for (const f of readdirSync(dir)) this.addWatchFile(join(dir, f));
      const core = compileCore(dir);
      bytes = core.length;
      const packed = pack(core);
      packedLength = packed.length;
      return [
        `import { unpack } from "${UNPACK}";`,
        `let core;`,
        `try { core = await unpack(${JSON.stringify(packed)}); } catch { core = new Uint8Array(0); }`,
        `export default core;`,
      ].join("\n");
    },
    generateBundle() {
      if (bytes > 0)
        console.log(
          `evapcool: the WebAssembly core inlined: ${bytes} bytes, packed to ${packedLength} (deflate, base 85)`,
        );
    },
  };
}
