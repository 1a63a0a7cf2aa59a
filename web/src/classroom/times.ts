/**
 * Times on the console's pages in the reader's language and time zone: the server writes
 * each as <time datetime="ISO">ISO</time> (it knows neither), the page rewrites the text
 * ("Mon 7 Dec, 09:14" for a reader in en-GB) and keeps the ISO time in datetime=.
 */

/** Weekday, day, month and minute: a round of this term is told apart without the year. */
const SHORT: Intl.DateTimeFormatOptions = {
  weekday: "short",
  day: "numeric",
  month: "short",
  hour: "2-digit",
  minute: "2-digit",
};

/**
 * The locale to write times in: the reader's own variant of the page's language when the
 * browser names one (en-GB's day before month on an "en" page), else the page's language.
 */
export function readerLocale(pageLang: string, preferred: readonly string[]): string {
  const base = pageLang.toLowerCase().split("-")[0];
  const own = preferred.find((tag) => tag.toLowerCase().split("-")[0] === base);
  return own ?? pageLang;
}

/** An ISO 8601 time as the reader reads it; RangeError naming `iso` if it is no time. */
export function localTime(iso: string, locale: string, timeZone?: string): string {
  const when = new Date(iso);
  if (!/^\d{4}-\d{2}-\d{2}T/.test(iso) || Number.isNaN(when.getTime()))
    throw new RangeError(`iso: not an ISO 8601 time (got ${JSON.stringify(iso)})`);
  return new Intl.DateTimeFormat(locale, { ...SHORT, timeZone }).format(when);
}

/** Every <time datetime> of the page written for its reader (a bad one left as it is). */
export function localizeTimes(root: ParentNode, locale: string): void {
  for (const t of root.querySelectorAll<HTMLTimeElement>("time[datetime]")) {
    try {
      t.textContent = localTime(t.dateTime, locale);
      t.title = t.dateTime;
    } catch {
      /* not a time the server wrote: its text stays */
    }
  }
}

/** A <time> for a moment the server gives in seconds since the epoch, written for the
 * page's reader (the page's language, the browser's time zone). */
export function readerTime(seconds: number): HTMLTimeElement {
  const t = document.createElement("time");
  t.dateTime = new Date(seconds * 1000).toISOString();
  t.title = t.dateTime;
  t.textContent = localTime(
    t.dateTime,
    readerLocale(document.documentElement.lang, navigator.languages),
  );
  return t;
}
