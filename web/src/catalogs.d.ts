/** The page's message catalogs (scripts/catalogs-plugin.mjs builds them). */
declare module "virtual:evapcool-catalogs" {
  /** English, the page's keys only. */
  export const english: {
    meta: { tag: string; name: string; direction: string; author: string; reviewed: boolean };
    messages: Record<string, string>;
  };
  /** The other locales: a JSON array of catalogs, deflate-raw, base64. */
  export const packed: string;
}
