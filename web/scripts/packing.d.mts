/** The module's name the page imports `unpack` from. */
export const UNPACK: string;
/** The 85 digits of the packed text. */
export const DIGITS: string;
/** Base 85 of `bytes` (a short last group as its first k + 1 digits). */
export function base85(bytes: Uint8Array): string;
/** `bytes` deflated and written in base 85. */
export function pack(bytes: Uint8Array): string;
/** The hooks that serve `virtual:evapcool-unpack`. */
export const unpackModule: {
  resolveId(id: string): string | null;
  load(id: string): string | null;
};
