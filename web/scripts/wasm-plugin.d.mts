import type { Plugin } from "vite";

/** The core's C sources, core/ at the top of the repository, seen from web/ (the Vite root). */
export const CORE_FOLDER: string;
/** clang's flags for the core. */
export const CLANG_FLAGS: string[];
/** The core's bytes, freshly compiled from the C sources in folder `dir`. */
export function compileCore(dir: string): Uint8Array;
/** The Vite plugin: `virtual:evapcool-wasm` is the compiled core's bytes (packed in the page). */
export function wasmCore(options?: { fromPage?: boolean }): Plugin;
