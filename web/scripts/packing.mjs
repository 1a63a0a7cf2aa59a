/**
 * Bytes packed into the page's script as text (the core, the catalogs, the physics worker):
 * deflate-raw, then base 85 (five characters for four bytes, where base64 spends 5.33), with
 * digits that need no escape in any JavaScript quote and cannot end a <script> element, nor
 * start an attribute (no quote, backslash, dollar, "<", ">" or "&"). The page reads them with
 * `unpack` from `import "virtual:evapcool-unpack"`, which each of the plugins serves (one
 * module in the bundle, whichever plugin answers first). Plain JavaScript like the plugins;
 * types in packing.d.mts.
 */
import { deflateRawSync } from "node:zlib";

export const UNPACK = "virtual:evapcool-unpack";
const RESOLVED = "\0evapcool-unpack";

/** Printable ASCII less the characters above, and "~" (85 left). */
export const DIGITS = Array.from({ length: 94 }, (_, k) => String.fromCharCode(33 + k))
  .filter((c) => !`"$&'<>\\\`~`.includes(c))
  .join("");
if (DIGITS.length !== 85) throw new Error(`evapcool: ${DIGITS.length} digits, not 85`);

/** Base 85 of `bytes`: a last group of k < 4 bytes is written as its first k + 1 digits. */
export function base85(bytes) {
  let text = "";
  for (let at = 0; at < bytes.length; at += 4) {
    const take = Math.min(4, bytes.length - at);
    let n = 0;
    for (let i = 0; i < 4; i++) n = n * 256 + (i < take ? bytes[at + i] : 0);
    let group = "";
    for (let i = 0; i < 5; i++, n = Math.floor(n / 85)) group = DIGITS[n % 85] + group;
    text += group.slice(0, take + 1);
  }
  return text;
}

/** `bytes` deflated and written in base 85: what `unpack` reads back. */
export function pack(bytes) {
  return base85(deflateRawSync(bytes, { level: 9 }));
}

/**
 * The page's side: a short last group is padded with the highest digit, which keeps its
 * leading bytes (85^m < 256^m for the m digits left out). Throws where the browser cannot
 * inflate (no DecompressionStream): each caller says what the page does then.
 */
const UNPACK_CODE = `const DIGITS = ${JSON.stringify(DIGITS)};
export async function unpack(text) {
  const value = new Uint8Array(128);
  for (let k = 0; k < 85; k++) value[DIGITS.charCodeAt(k)] = k;
  const groups = Math.ceil(text.length / 5);
  const bytes = new Uint8Array(groups * 4);
  const view = new DataView(bytes.buffer);
  for (let g = 0; g < groups; g++) {
    let n = 0;
    for (let i = 5 * g; i < 5 * g + 5; i++) n = n * 85 + (i < text.length ? value[text.charCodeAt(i)] : 84);
    view.setUint32(4 * g, n);
  }
  const packed = bytes.subarray(0, bytes.length - ((5 - (text.length % 5)) % 5));
  const stream = new Blob([packed]).stream().pipeThrough(new DecompressionStream("deflate-raw"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}`;

/** The hooks that serve `virtual:evapcool-unpack`, for a plugin to call from its own. */
export const unpackModule = {
  resolveId: (id) => (id === UNPACK ? RESOLVED : null),
  load: (id) => (id === RESOLVED ? UNPACK_CODE : null),
};
