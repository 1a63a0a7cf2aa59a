import type { Plugin } from "vite";

/** web/wasm/, the core's C sources. */
export const WASM_SOURCES: string;
/** clang's flags for the core. */
export const CLANG_FLAGS: string[];
/** The core's bytes, freshly compiled from web/wasm/. */
export function compileCore(): Uint8Array;
/** The Vite plugin: `virtual:evapcool-wasm` is the compiled core as base64 text. */
export function wasmCore(): Plugin;
