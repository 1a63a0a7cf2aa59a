/** The WebAssembly core's bytes (scripts/wasm-plugin.mjs builds them; empty if not here). */
declare module "virtual:evapcool-wasm" {
  const bytes: Uint8Array<ArrayBuffer>;
  export default bytes;
}
