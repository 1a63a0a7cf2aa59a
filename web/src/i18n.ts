/**
 * Message catalogs of the page (issue 23): the same JSON files as the desktop
 * (src/evapcool/locales/), the same ICU MessageFormat subset as evapcool.i18n, with plural
 * categories and number formats from Intl so both editions print the same words.
 * Python's twin: `src/evapcool/i18n.py` (docs/twins.md).
 */
import { catalogs } from "virtual:evapcool-catalogs";

/** One catalog file: who wrote it, its direction, and the messages by stable dotted id. */
export interface CatalogFile {
  meta: { tag: string; name: string; direction: string; author: string; reviewed: boolean };
  messages: Record<string, string>;
}

export const FALLBACK = "en";
export const PSEUDO = "en-XA";
export const STORAGE_KEY = "evapcool.lang";

/** English first; a browser without DecompressionStream has only the line that says the
 * page cannot start there (scripts/catalogs-plugin.mjs). */
const SHIPPED: CatalogFile[] = catalogs;
const en: CatalogFile = SHIPPED[0];
export const CATALOGS: Record<string, CatalogFile> = Object.fromEntries(
  SHIPPED.map((c) => [c.meta.tag, c]),
);

/** Keys asked for but missing in the chosen catalog, per locale (read by the tests). */
export const missingKeys = new Map<string, Set<string>>();

export type Args = Record<string, string | number>;
type Node = string | { hash: true } | Argument;
interface Argument {
  name: string;
  kind: "text" | "number" | "plural" | "select";
  options: Record<string, Node[]>;
}

function syntaxError(key: string, problem: string, position: number): RangeError {
  return new RangeError(`message '${key}': ${problem} at position ${position}`);
}

function parseNodes(text: string, start: number, key: string, inPlural: boolean): [Node[], number] {
  const nodes: Node[] = [];
  let buf = "";
  let pos = start;
  while (pos < text.length) {
    const ch = text[pos];
    if (ch === "'" && pos + 1 < text.length && "{}#'".includes(text[pos + 1])) {
      if (text[pos + 1] === "'") {
        buf += "'";
        pos += 2;
        continue;
      }
      let end = text.indexOf("'", pos + 1);
      if (end < 0) end = text.length;
      buf += text.slice(pos + 1, end);
      pos = end + 1;
      continue;
    }
    if (ch === "}") break;
    if (ch === "#" && inPlural) {
      nodes.push(buf, { hash: true });
      buf = "";
      pos += 1;
      continue;
    }
    if (ch !== "{") {
      buf += ch;
      pos += 1;
      continue;
    }
    nodes.push(buf);
    buf = "";
    const [node, next] = parseArgument(text, pos + 1, key, inPlural);
    nodes.push(node);
    pos = next;
  }
  nodes.push(buf);
  return [nodes.filter((n) => n !== ""), pos];
}

function parseArgument(
  text: string,
  pos: number,
  key: string,
  inPlural: boolean,
): [Argument, number] {
  const close = text.indexOf("}", pos);
  const comma = text.indexOf(",", pos);
  if (close < 0) throw syntaxError(key, "unclosed {", pos);
  if (comma < 0 || comma > close) {
    return [{ name: text.slice(pos, close).trim(), kind: "text", options: {} }, close + 1];
  }
  const name = text.slice(pos, comma).trim();
  const comma2 = text.indexOf(",", comma + 1);
  if (comma2 < 0 || comma2 > close) {
    const kind = text.slice(comma + 1, close).trim();
    if (kind !== "number") throw syntaxError(key, kind, comma + 1);
    return [{ name, kind: "number", options: {} }, close + 1];
  }
  const kind = text.slice(comma + 1, comma2).trim();
  if (kind !== "plural" && kind !== "select") throw syntaxError(key, kind, comma + 1);
  const options: Record<string, Node[]> = {};
  let at = comma2 + 1;
  for (;;) {
    while (at < text.length && /\s/.test(text[at])) at += 1;
    if (at >= text.length) throw syntaxError(key, "unclosed", at);
    if (text[at] === "}") return [{ name, kind, options }, at + 1];
    const brace = text.indexOf("{", at);
    const [body, end] = parseNodes(text, brace + 1, key, kind === "plural" || inPlural);
    options[text.slice(at, brace).trim()] = body;
    at = end + 1;
  }
}

/** The node list of one message; a RangeError names the key and the position. */
export function parseMessage(text: string, key = "?"): Node[] {
  const [nodes, pos] = parseNodes(text, 0, key, false);
  if (pos !== text.length) throw syntaxError(key, "stray }", pos);
  return nodes;
}

/** The argument names a message uses. */
export function placeholders(nodes: Node[]): Set<string> {
  const names = new Set<string>();
  for (const node of nodes) {
    if (typeof node === "string" || "hash" in node) continue;
    names.add(node.name);
    for (const body of Object.values(node.options))
      for (const n of placeholders(body)) names.add(n);
  }
  return names;
}

/** For each plural argument, the category keywords it offers (`=N` excluded). */
export function pluralSelectors(nodes: Node[]): Set<string>[] {
  const found: Set<string>[] = [];
  for (const node of nodes) {
    if (typeof node === "string" || "hash" in node) continue;
    if (node.kind === "plural") {
      found.push(new Set(Object.keys(node.options).filter((k) => !k.startsWith("="))));
    }
    for (const body of Object.values(node.options)) found.push(...pluralSelectors(body));
  }
  return found;
}

const SCRIPT_REGION: Record<string, string> = { hans: "cn", hant: "tw" };

/** The first wanted tag's best shipped catalog: exact, script->region, language only. */
export function bestMatch(wanted: readonly string[], available: readonly string[]): string | null {
  const shipped = new Map(available.map((t) => [t.toLowerCase(), t]));
  for (const tag of wanted) {
    const parts = tag.replace(/_/g, "-").split(".")[0].split("-").filter(Boolean);
    if (parts.length === 0) continue;
    const lower = parts.map((p) => p.toLowerCase());
    const lang = lower[0];
    const regionPart = lower.slice(1).find((p) => p.length === 2 || p.length === 4);
    const region = regionPart === undefined ? undefined : (SCRIPT_REGION[regionPart] ?? regionPart);
    if (region !== undefined && region.length === 2 && shipped.has(`${lang}-${region}`)) {
      return shipped.get(`${lang}-${region}`)!;
    }
    if (shipped.has(lang)) return shipped.get(lang)!;
    const sameLanguage = [...shipped.keys()].filter((t) => t.split("-")[0] === lang).sort();
    if (sameLanguage.length > 0) return shipped.get(sameLanguage[0])!;
  }
  return null;
}

/** The shipped tags plus the pseudo-locale. */
export function availableLocales(): string[] {
  return [...Object.keys(CATALOGS).sort(), PSEUDO];
}

/** Browser languages, then `?lang=`, then the saved menu choice: the later beats the earlier. */
export function chooseLocale(
  languages: readonly string[],
  search: string,
  saved: string | null,
): string {
  const available = availableLocales();
  // An option given twice is refused, as the address's notice says (params.ts): not the first.
  const given = new URLSearchParams(search).getAll("lang");
  const fromQuery = given.length === 1 ? given[0] : null;
  for (const source of [saved ? [saved] : [], fromQuery ? [fromQuery] : [], languages]) {
    const match = bestMatch(source, available);
    if (match) return match;
  }
  return FALLBACK;
}

const PSEUDO_FROM = "aceinosuyACEINOSUY";
const PSEUDO_TO = "àçéîñöšüýÀÇÉÎÑÖŠÜÝ";

function pseudoNodes(nodes: Node[]): string {
  return nodes
    .map((node) => {
      if (typeof node === "string") {
        return [...node].map((c) => PSEUDO_TO[PSEUDO_FROM.indexOf(c)] ?? c).join("");
      }
      if ("hash" in node) return "#";
      if (node.kind === "text") return `{${node.name}}`;
      if (node.kind === "number") return `{${node.name}, number}`;
      const body = Object.entries(node.options)
        .map(([k, v]) => `${k} {${pseudoNodes(v)}}`)
        .join(" ");
      return `{${node.name}, ${node.kind}, ${body}}`;
    })
    .join("");
}

/** Accented, bracketed and 40 % longer; placeholders untouched (same as evapcool.i18n). */
export function pseudoMessage(text: string): string {
  const padding = "~".repeat(Math.max(1, pyRound(text.length * 0.4) - 2));
  return `[${pseudoNodes(parseMessage(text))} ${padding}]`;
}

/** Python's round(): halves to even, so both editions pad alike. */
function pyRound(x: number): number {
  const r = Math.round(x);
  return Math.abs(x % 1) === 0.5 && r % 2 !== 0 ? r - 1 : r;
}

function catalogFor(tag: string): CatalogFile {
  if (tag !== PSEUDO) return CATALOGS[tag];
  const messages = Object.fromEntries(
    Object.entries(en.messages).map(([k, v]) => [k, pseudoMessage(v)]),
  );
  return {
    meta: { ...en.meta, tag: PSEUDO, name: "English (pseudo)", author: "generated" },
    messages,
  };
}

/** What every layer that shows words holds: `t(key, args)` and the locale's facts. */
export interface Translator {
  locale: string;
  direction: "ltr" | "rtl";
  t(key: string, args?: Args): string;
  formatNumber(value: number): string;
}

/** A translator for `locale` (best match); RangeError names the allowed tags. */
export function createTranslator(locale: string): Translator {
  const tag = bestMatch([locale], availableLocales());
  if (tag === null) {
    throw new RangeError(
      `locale must be one of ${availableLocales().join(", ")} (got '${locale}')`,
    );
  }
  const catalog = catalogFor(tag);
  const intlTag = tag === PSEUDO ? FALLBACK : tag;
  const tools = (lang: string) => ({
    plural: new Intl.PluralRules(lang),
    number: new Intl.NumberFormat(lang, { maximumFractionDigits: 3 }),
  });
  const own = tools(intlTag);
  const english = tools(FALLBACK);
  // Messages are drawn every frame: each is parsed once per translator.
  const parsed = new Map<string, Node[]>();
  const nodesOf = (key: string, text: string): Node[] => {
    let nodes = parsed.get(text);
    if (nodes === undefined) parsed.set(text, (nodes = parseMessage(text, key)));
    return nodes;
  };
  return {
    locale: tag,
    direction: catalog.meta.direction === "rtl" ? "rtl" : "ltr",
    t(key, args = {}) {
      let text = catalog.messages[key];
      let use = own;
      if (text === undefined) {
        if (!missingKeys.has(tag)) missingKeys.set(tag, new Set());
        missingKeys.get(tag)!.add(key);
        text = en.messages[key] ?? key;
        use = english;
      }
      return render(nodesOf(key, text), args, use, 0);
    },
    formatNumber: (value) => own.number.format(value),
  };
}

interface Tools {
  plural: Intl.PluralRules;
  number: Intl.NumberFormat;
}

function render(nodes: Node[], args: Args, tools: Tools, count: number): string {
  let out = "";
  for (const node of nodes) {
    if (typeof node === "string") out += node;
    else if ("hash" in node) out += tools.number.format(count);
    else {
      const value = args[node.name];
      if (node.kind === "text") out += String(value);
      else if (node.kind === "number") out += tools.number.format(Number(value));
      else if (node.kind === "select") {
        out += render(node.options[String(value)] ?? node.options.other, args, tools, count);
      } else {
        const n = Number(value);
        const body =
          node.options[`=${n}`] ?? node.options[tools.plural.select(n)] ?? node.options.other;
        out += render(body, args, tools, n);
      }
    }
  }
  return out;
}

let current: Translator | null = null;
const listeners: Array<(t: Translator) => void> = [];

/** The page's language from now on (best match of `locale`); listeners redo their words. */
export function useLocale(locale: string): Translator {
  current = createTranslator(locale);
  for (const listener of listeners) listener(current);
  return current;
}

/** The language in use (English until `useLocale`). */
export function activeTranslator(): Translator {
  return current ?? useLocale(FALLBACK);
}

/** Called after each change of language (aria labels, the document's lang and dir). */
export function onLocaleChange(listener: (t: Translator) => void): void {
  listeners.push(listener);
}

/** The active language's message `key` with `args` (English, reported, when it lacks one). */
export function t(key: string, args?: Args): string {
  return activeTranslator().t(key, args);
}

/** A number as the active language writes it (decimal comma, grouping). */
export function formatNumber(value: number): string {
  return activeTranslator().formatNumber(value);
}

/** The name of each shipped language in itself, by tag (the settings' language menu). */
export function languageNames(): Array<{ tag: string; name: string }> {
  return Object.values(CATALOGS)
    .map((c) => ({ tag: c.meta.tag, name: c.meta.name }))
    .sort((a, b) => a.tag.localeCompare(b.tag));
}

/** The active language's decimal mark ("." or "," or "٫"). */
export function decimalMark(): string {
  return formatNumber(0.5).replace(/[^.,٫]/g, "") || ".";
}

const fixedFormats = new Map<string, Intl.NumberFormat>();

/** `value` with exactly `digits` decimals as the active language writes it (0,60 in German). */
export function formatFixed(value: number, digits: number): string {
  const tag = activeTranslator().locale;
  const key = `${tag}|${digits}`;
  let format = fixedFormats.get(key);
  if (format === undefined) {
    const options = { minimumFractionDigits: digits, maximumFractionDigits: digits };
    format = new Intl.NumberFormat(tag === PSEUDO ? FALLBACK : tag, options);
    fixedFormats.set(key, format);
  }
  return format.format(value);
}

/** The active language's writing direction (the canvas's ctx.direction). */
export function textDirection(): "ltr" | "rtl" {
  return activeTranslator().direction;
}
