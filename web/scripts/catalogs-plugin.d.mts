import type { Plugin } from "vite";

/** The catalogs' folder seen from web/ (the Vite root). */
export const LOCALES_FOLDER: string;
/** Key prefixes the page never shows. */
export const NOT_ON_THE_PAGE: string[];
/** The message keys the page's code names. */
export function keysInSource(srcDir: string): Set<string>;
/** Every catalog in `dir`, English first, each with the keys in `keep` (or all the page's). */
export function pageCatalogs(
  dir: string,
  keep?: Set<string> | null,
): Array<{
  meta: { tag: string; name: string; direction: string; author: string; reviewed: boolean };
  messages: Record<string, string>;
}>;
/** The Vite plugin: `virtual:evapcool-catalogs`. */
export function catalogs(options?: { allKeys?: boolean }): Plugin;
