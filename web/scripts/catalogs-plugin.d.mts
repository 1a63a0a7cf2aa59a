import type { Plugin } from "vite";

/** The catalogs' folder seen from web/ (the Vite root). */
export const LOCALES_FOLDER: string;
/** Key prefixes the page never shows. */
export const NOT_ON_THE_PAGE: string[];
/** Every catalog in `dir`, English first, each with the page's keys only. */
export function pageCatalogs(dir: string): Array<{
  meta: { tag: string; name: string; direction: string; author: string; reviewed: boolean };
  messages: Record<string, string>;
}>;
/** The Vite plugin: `virtual:evapcool-catalogs`. */
export function catalogs(): Plugin;
