// The web engine's rooms pair with the Python physics by name (issue 26): every file of
// web/src/physics has a twin of the same stem in src/evapcool/physics/ or physics/fast/, and
// the tables' fields carry Python's field names (PLAN_PARTNER_COUNT for partner_count).
import { readdirSync, readFileSync } from "node:fs";
import { resolve } from "node:path";
import { expect, test } from "vitest";
import * as calendar from "../../src/physics/calendar";
import * as tables from "../../src/physics/tables";

const WEB = resolve(import.meta.dirname, "../../src/physics");
const PY = resolve(import.meta.dirname, "../../../src/evapcool/physics");

/** Web files with no Python twin of the same stem, and why. */
const NO_TWIN: Record<string, string> = {
  "index.ts": "the package's entry (Python's physics/__init__.py)",
  "constants.ts":
    "the applet's constants; Python keeps them in constants.py, world.py and limits.py",
  "wasm.ts": "the WebAssembly core's wrapper; its C rooms in web/wasm/ mirror physics/fast",
  "wasm-core.d.ts": "the type of the core the build inlines (web/scripts/wasm-plugin.mjs)",
};

function stems(dir: string, ext: string): Set<string> {
  return new Set(
    readdirSync(dir)
      .filter((f) => f.endsWith(ext) && !f.startsWith("_"))
      .map((f) => f.slice(0, -ext.length)),
  );
}

/** The field names of record `name` in fast/tables.py: the ("field", "format") pairs. */
function pythonFields(name: string): string[] {
  const text = readFileSync(resolve(PY, "fast/tables.py"), "utf8");
  const start = text.indexOf(`${name} = _record(`);
  expect(start, `tables.py defines ${name}`).toBeGreaterThanOrEqual(0);
  const block = text.slice(start, text.indexOf("\n)", start));
  return [...block.matchAll(/\("(\w+)", "[a-z]\d"\)/g)].map((m) => m[1]);
}

/** The fields of a web table: its module's constants TABLE_FIELD (offsets), as field -> offset. */
function webFields(module: Record<string, unknown>, table: string): Record<string, number> {
  const out: Record<string, number> = {};
  for (const [name, value] of Object.entries(module))
    if (name.startsWith(`${table}_`) && name !== `${table}_WIDTH` && typeof value === "number")
      out[name.slice(table.length + 1).toLowerCase()] = value;
  return out;
}

const STATE = webFields(tables, "STATE");
const PLAN = webFields(tables, "PLAN");
const QUEUED = webFields(tables, "QUEUED");
const KEYED = webFields(calendar, "KEYED");

test("every web physics file has a Python twin of the same stem", () => {
  const python = new Set([...stems(PY, ".py"), ...stems(resolve(PY, "fast"), ".py")]);
  const web = readdirSync(WEB).filter((f) => f.endsWith(".ts"));
  for (const file of ["tables.ts", "calendar.ts", "grid.ts", "predict.ts", "events.ts"])
    expect(web).toContain(file);
  for (const file of ["driver.ts", "engine.ts", "kernels.ts"]) expect(web).toContain(file);
  const orphans = web.filter((f) => !(f in NO_TWIN) && !python.has(f.slice(0, -3)));
  expect(orphans).toEqual([]);
  for (const file of Object.keys(NO_TWIN)) expect(web, `${file} is still there`).toContain(file);
});

test("the tables' fields carry Python's names", () => {
  const cases: [string, Record<string, number>, string[]][] = [
    ["STATE", STATE, pythonFields("STATE")],
    ["PLAN", PLAN, pythonFields("PLAN")],
    ["QUEUED", QUEUED, pythonFields("QUEUED")],
    // the calendar keeps the key parts (PLAN's in Python) beside the links (QUEUED's)
    ["KEYED", KEYED, [...pythonFields("PLAN"), ...pythonFields("QUEUED")]],
  ];
  for (const [table, fields, python] of cases) {
    expect(python.length, `${table}: Python fields read`).toBeGreaterThan(3);
    expect(Object.keys(fields).length, `${table}: web fields read`).toBeGreaterThan(3);
    for (const field of Object.keys(fields))
      expect(python, `${table}_${field.toUpperCase()} in tables.py`).toContain(field);
  }
});

test("the field offsets of a table are distinct and fit its row", () => {
  const widths: [Record<string, number>, number][] = [
    [STATE, tables.STATE_WIDTH],
    [PLAN, tables.PLAN_WIDTH],
    [QUEUED, tables.QUEUED_WIDTH],
    [KEYED, calendar.KEYED_WIDTH],
  ];
  for (const [fields, width] of widths) {
    const offsets = Object.values(fields);
    expect(new Set(offsets).size).toBe(offsets.length);
    for (const o of offsets) expect(o >= 0 && o < width).toBe(true);
  }
});
