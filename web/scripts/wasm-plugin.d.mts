import type { Plugin } from "vite";

/** web/wasm/ seen from web/ (the Vite root): the core's C sources. */
export const WASM_FOLDER: string;
/** clang's flags for the core. */
export const CLANG_FLAGS: string[];
/** The core's bytes, freshly compiled from the C sources in folder `dir`. */
export function compileCore(dir: string): Uint8Array;
/** The Vite plugin: `virtual:evapcool-wasm` is the compiled core as base64 text. */
export function wasmCore(options?: { fromPage?: boolean }): Plugin;
