import { readFileSync } from "node:fs";
import { resolve } from "node:path";
import { describe, expect, it } from "vitest";
import golden from "./golden/i18n.json";
import { pageCatalogs } from "../scripts/catalogs-plugin.mjs";
import {
  CATALOGS,
  PSEUDO,
  availableLocales,
  bestMatch,
  chooseLocale,
  createTranslator,
  missingKeys,
  parseMessage,
  placeholders,
  pluralSelectors,
} from "../src/i18n";

const english = CATALOGS.en.messages;
const tags = Object.keys(CATALOGS);

describe("catalogs", () => {
  it.each(tags)("%s is complete with the English placeholders", (tag) => {
    const messages = CATALOGS[tag].messages;
    expect(Object.keys(messages).sort()).toEqual(Object.keys(english).sort());
    for (const [key, text] of Object.entries(messages)) {
      const wanted = [...placeholders(parseMessage(english[key as keyof typeof english], key))];
      expect([...placeholders(parseMessage(text, key))].sort(), key).toEqual(wanted.sort());
    }
  });

  it.each(tags)("%s plurals cover Intl's categories", (tag) => {
    const categories = new Intl.PluralRules(tag).resolvedOptions().pluralCategories;
    for (const [key, text] of Object.entries(CATALOGS[tag].messages)) {
      for (const offered of pluralSelectors(parseMessage(text, key))) {
        for (const c of categories) expect(offered.has(c), `${key} ${c}`).toBe(true);
      }
    }
  });
});

describe("what the page carries", () => {
  const folder = resolve(import.meta.dirname, "../../src/evapcool/locales");

  it("each catalog's meta and messages, never the hashes of the English they translate", () => {
    const files = pageCatalogs(folder);
    expect(files.length).toBe(tags.length);
    for (const file of files) {
      expect(Object.keys(file).sort()).toEqual(["messages", "meta"]);
      const onDisk = JSON.parse(readFileSync(resolve(folder, `${file.meta.tag}.json`), "utf8"));
      // The translated files do keep them (tests/test_i18n_stale.py reads them).
      expect("sources" in onDisk).toBe(file.meta.tag !== "en");
    }
  });
});

describe("formatting", () => {
  it.each(golden.outputs)("$locale $key $args as Python formats it", (row) => {
    const args = row.args as unknown as Record<string, string | number>;
    expect(createTranslator(row.locale).t(row.key, args)).toBe(row.expected);
  });

  it("falls back to English and records the missing key", () => {
    const t = createTranslator("de");
    const saved = CATALOGS.de.messages["lose.too_few"];
    delete (CATALOGS.de.messages as Record<string, string>)["lose.too_few"];
    missingKeys.clear();
    try {
      expect(t.t("lose.too_few")).toBe("Too few atoms left");
      expect([...(missingKeys.get("de") ?? [])]).toEqual(["lose.too_few"]);
    } finally {
      (CATALOGS.de.messages as Record<string, string>)["lose.too_few"] = saved;
    }
  });

  it("names the bad locale in one line", () => {
    expect(() => createTranslator("tlh")).toThrow(/locale must be one of .* \(got 'tlh'\)/);
  });

  it("Arabic is right to left", () => {
    expect(createTranslator("ar-EG").direction).toBe("rtl");
    expect(createTranslator("de").direction).toBe("ltr");
  });
});

describe("choosing", () => {
  it.each(golden.matches)("$wanted -> $expected", ({ wanted, expected }) => {
    expect(bestMatch(wanted, availableLocales())).toBe(expected);
  });

  it("the saved choice beats ?lang= beats the browser", () => {
    expect(chooseLocale(["ja-JP", "en"], "", null)).toBe("ja");
    expect(chooseLocale(["ja-JP"], "?lang=de-AT", null)).toBe("de");
    expect(chooseLocale(["ja-JP"], "?lang=de", "ar")).toBe("ar");
    expect(chooseLocale(["sv"], "?lang=xx", null)).toBe("en");
  });
});

describe("pseudo-locale", () => {
  it("is 40 % longer, bracketed, placeholders kept", () => {
    const t = createTranslator(PSEUDO);
    const plain = createTranslator("en");
    // Every placeholder the catalog uses gets a short value (numbers where formatted).
    const names = Object.values(english).flatMap((m) =>
      [...m.matchAll(/\{(\w+)/g)].map((x) => x[1]),
    );
    const args = {
      ...Object.fromEntries(names.map((name) => [name, "x"])),
      ...{ n: 3, p: 0.5, height: 4, percent: 5, problem: "x", radius: 1, name: "B" },
    };
    for (const key of Object.keys(english)) {
      const fake = t.t(key, { ...args, mode: "a" });
      expect(fake.startsWith("[") && fake.endsWith("]"), key).toBe(true);
      expect(fake.length, key).toBeGreaterThanOrEqual(
        1.4 * plain.t(key, { ...args, mode: "a" }).length,
      );
    }
    expect(t.t("win.score", { n: 3 }).startsWith("[Šçöré: 3 àtömš")).toBe(true);
  });
});
