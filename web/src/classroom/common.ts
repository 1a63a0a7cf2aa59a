/**
 * What every class page shares: the words the server put in the page (from the message
 * catalog), the server's JSON, and its event stream. Names reach the page only as data:
 * callers put them in with textContent.
 */

/** The page's words: its key -> the catalog's text in the page's language. */
export type Words = Readonly<Record<string, string>>;

/** The element with this id; a page without it is a server bug, said once. */
export function byId<T extends HTMLElement = HTMLElement>(id: string): T {
  const found = document.getElementById(id);
  if (found === null) throw new Error(`the page has no #${id}`);
  return found as T;
}

/** The words the server gave the page (the JSON in <script id="words">). */
export function pageWords(): Words {
  return JSON.parse(byId("words").textContent ?? "{}") as Words;
}

/** A catalog text with its {placeholders} filled (an unknown one stays as written). */
export function fill(text: string, args: Readonly<Record<string, unknown>>): string {
  return text.replace(/\{(\w+)\}/g, (whole, key: string) =>
    key in args ? String(args[key]) : whole,
  );
}

/** A parameter of the page's own address, or null. */
export function queryParam(name: string): string | null {
  return new URLSearchParams(location.search).get(name);
}

/** The server's answer: whether it took the request, and its JSON. */
export interface Answer<T> {
  ok: boolean;
  body: T;
}

/** GET a JSON document from this server. */
export async function getJson<T>(path: string, headers: HeadersInit = {}): Promise<Answer<T>> {
  const r = await fetch(path, { headers });
  return { ok: r.ok, body: r.ok ? ((await r.json()) as T) : (undefined as T) };
}

/** POST a JSON body to this server and read its JSON answer. */
export async function postJson<T>(
  path: string,
  body: unknown,
  headers: HeadersInit = {},
): Promise<Answer<T>> {
  const r = await fetch(path, { method: "POST", headers, body: JSON.stringify(body) });
  return { ok: r.ok, body: (await r.json()) as T };
}

/** The server's refusal document ({"error": {"field", "message"}}, see docs/class.md). */
export interface Refusal {
  error: { field: string; message: string };
}

/** A refusal as one line: the field it names, then the server's (translated) words. */
export function refusalText(doc: Refusal): string {
  return doc.error.field + ": " + doc.error.message;
}

/** Follow the server's event stream (path with its query), each message's JSON to `take`. */
export function listen(path: string, take: (doc: unknown) => void): EventSource {
  const source = new EventSource(path);
  source.onmessage = (e: MessageEvent<string>) => take(JSON.parse(e.data));
  return source;
}
