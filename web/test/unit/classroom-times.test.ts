// The console's times (web/src/classroom/times.ts): a past round's ISO time as its reader
// reads it, in their language and time zone; the DOM rewrite is walked in Chromium
// (test/e2e/console-phone.test.mjs).
import { describe, expect, it } from "vitest";
import { localTime, readerLocale } from "../../src/classroom/times";

const MONDAY = "2026-12-07T09:14:00Z";

describe("localTime", () => {
  it("writes weekday, day, month and minute in the reader's locale", () => {
    expect(localTime(MONDAY, "en-GB", "UTC")).toBe("Mon 7 Dec, 09:14");
    expect(localTime(MONDAY, "de", "UTC")).toBe("Mo., 7. Dez., 09:14");
  });

  it("moves the time to the reader's time zone (the day too)", () => {
    expect(localTime(MONDAY, "en-GB", "Europe/Berlin")).toBe("Mon 7 Dec, 10:14");
    expect(localTime("2026-12-07T23:30:00Z", "en-GB", "Asia/Tokyo")).toBe("Tue 8 Dec, 08:30");
  });

  it("writes Arabic in Arabic", () => {
    const text = localTime(MONDAY, "ar", "UTC");
    expect(text).toContain("ديسمبر");
    expect(text).toContain("الاثنين");
  });

  it("refuses what is not an ISO time, naming it", () => {
    expect(() => localTime("yesterday", "en", "UTC")).toThrow(RangeError);
    expect(() => localTime("2026-13-45T99:00:00Z", "en", "UTC")).toThrow(/^iso: /);
    expect(() => localTime("1733562840", "en", "UTC")).toThrow(/iso/);
  });
});

describe("readerLocale", () => {
  it("takes the reader's own variant of the page's language", () => {
    expect(readerLocale("en", ["en-GB", "en"])).toBe("en-GB");
    expect(readerLocale("de", ["en-GB", "de-AT"])).toBe("de-AT");
    expect(readerLocale("pt-BR", ["pt-PT"])).toBe("pt-PT");
  });

  it("keeps the page's language when the browser names no variant of it", () => {
    expect(readerLocale("ar", ["en-GB", "de"])).toBe("ar");
    expect(readerLocale("ja", [])).toBe("ja");
  });
});
