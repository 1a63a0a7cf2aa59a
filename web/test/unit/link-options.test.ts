// The address's options live in one file (src/link-options.json, issue 48) that the page's
// parser, the desktop's links and docs/teach.md's table read: its values are the code's own.
import { readFileSync } from "node:fs";
import { resolve } from "node:path";
import { expect, test } from "vitest";
import table from "../../src/limits.json";
import { DEFAULTS, TC_LAWS } from "../../src/game/settings";
import { ESCAPE_RULES } from "../../src/game/engine";
import { HEIGHT_MAX, HEIGHT_MIN } from "../../src/game/rules";
import { CONTROL_ORDER } from "../../src/view/geometry";
import { ADDRESS_OPTIONS, LINK_OPTIONS, parseParams, URL_ATOMS_MAX } from "../../src/app/params";

const english = JSON.parse(
  readFileSync(resolve(import.meta.dirname, "../../../src/evapcool/locales/en.json"), "utf8"),
).messages as Record<string, string>;
const option = (name: string) => LINK_OPTIONS.find((o) => o.name === name)!;

test("the parser knows exactly the file's options, each described in the catalog", () => {
  expect(ADDRESS_OPTIONS).toEqual(LINK_OPTIONS.map((o) => o.name));
  expect(ADDRESS_OPTIONS).toContain("trap");
  for (const o of LINK_OPTIONS) {
    expect(english[o.key], o.name).toBeTypeOf("string");
    if (o.range !== undefined) expect(Object.keys(table.ranges), o.name).toContain(o.range);
  }
});

test("the file's values are the code's", () => {
  expect(option("tc-law").values).toEqual(Object.keys(TC_LAWS));
  expect(option("escape").values).toEqual([...ESCAPE_RULES]);
  expect(option("hide").values).toEqual(CONTROL_ORDER);
  expect([option("trap").low, option("trap").high]).toEqual([HEIGHT_MIN, HEIGHT_MAX]);
  expect([option("atoms").low, option("atoms").high]).toEqual([1, URL_ATOMS_MAX]);
});

test("new options parse, and a bad one is one notice naming it", () => {
  const p = parseParams(
    "?trap=300&lock=atoms,trap&hide=help,table&theme=projector&sound=off",
    DEFAULTS,
  );
  expect(p.notices).toEqual([]);
  expect(p.trap).toBe(300);
  expect(p.lock).toEqual(["atoms", "trap"]);
  expect(p.hide).toEqual(["help", "table"]);
  expect(p.theme).toBe("projector");
  expect(p.sound).toBe(false);
  const bad = parseParams("?trap=9999&lock=atoms,nope&hide=x&theme=pink&sound=loud", DEFAULTS);
  expect(bad.notices).toHaveLength(5);
  ["trap", "lock", "hide", "theme", "sound"].forEach((name, i) =>
    expect(bad.notices[i]).toContain(name),
  );
  expect(bad.trap).toBeNull();
  expect(bad.lock).toEqual([]);
});
