/** The WebAssembly core's bytes as base64 text (scripts/wasm-plugin.ts builds them). */
declare module "virtual:evapcool-wasm" {
  const base64: string;
  export default base64;
}
