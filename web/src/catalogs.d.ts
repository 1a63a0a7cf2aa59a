/** The page's message catalogs (scripts/catalogs-plugin.mjs builds them). */
declare module "virtual:evapcool-catalogs" {
  /** Every locale, English first, the page's keys only (unpacked at import). */
  export const catalogs: Array<{
    meta: { tag: string; name: string; direction: string; author: string; reviewed: boolean };
    messages: Record<string, string>;
  }>;
}
