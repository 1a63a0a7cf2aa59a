/**
 * Game settings (what Restart applies), validated with the desktop's rules and messages
 * (Python's `game/settings.py`): one clear message per bad value; a stored value that is
 * bad falls back to its default with a notice. No DOM here: `store.ts` persists them.
 */
import { t } from "../i18n";
import {
  ATOM_RADIUS,
  ESCAPE_RULES,
  N_ATOMS,
  TC_EXPONENT_CUP,
  TC_EXPONENT_SEED,
  type EscapeRule,
} from "./engine";
import { cupCapacity } from "./capacity";
import { APPLET_ATOMS, APPLET_RADIUS, pyG } from "../limits";

export const FORMAT_VERSION = 1;
export const TC_LAWS = { seed: TC_EXPONENT_SEED, cup: TC_EXPONENT_CUP } as const;
export type TcLaw = keyof typeof TC_LAWS;
const TC_LAW_NAMES = Object.keys(TC_LAWS) as TcLaw[];
/** The applet's ranges (the limits table's APPLET_RADIUS and APPLET_ATOMS). */
export const RADIUS_MIN = APPLET_RADIUS.low;
export const RADIUS_MAX = APPLET_RADIUS.high;
/** Hard cap whatever the radius; maxAtoms also caps by what fits in the cup. */
export const ATOMS_MAX = APPLET_ATOMS.high;

export interface Settings {
  nAtoms: number;
  radius: number;
  tcLaw: TcLaw;
  escape: EscapeRule;
}

export const DEFAULTS: Readonly<Settings> = Object.freeze({
  nAtoms: N_ATOMS,
  radius: ATOM_RADIUS,
  tcLaw: "seed",
  escape: "rim",
});

/** Field names as the desktop's settings file spells them, in screen order. */
export const FIELD_NAMES = ["n_atoms", "radius", "tc_law", "escape"] as const;
export type FieldName = (typeof FIELD_NAMES)[number];

export function tcExponent(s: Settings): number {
  return TC_LAWS[s.tcLaw];
}

/** Characters of a string, and items of a list or object, a message quotes at most (the
 * desktop's limits.shown shortens the same way: a stored megabyte stays one line). */
const REPR_CHARS = 40;
const REPR_ITEMS = 4;

/** A value as Python's repr writes it, shortened, so messages read the same in both editions. */
export function pyRepr(value: unknown): string {
  if (value === null || value === undefined) return "None";
  if (typeof value === "boolean") return value ? "True" : "False";
  if (typeof value === "string") {
    const cut = value.length > REPR_CHARS ? `${value.slice(0, 18)}...${value.slice(-19)}` : value;
    return `'${cut.replace(/\\/g, "\\\\").replace(/'/g, "\\'")}'`;
  }
  if (typeof value === "number") {
    if (Number.isNaN(value)) return "nan";
    if (!Number.isFinite(value)) return value > 0 ? "inf" : "-inf";
    return String(value);
  }
  const more = (n: number) => (n > REPR_ITEMS ? ", ..." : "");
  if (Array.isArray(value))
    return `[${value.slice(0, REPR_ITEMS).map(pyRepr).join(", ")}${more(value.length)}]`;
  if (typeof value === "object") {
    const items = Object.entries(value as Record<string, unknown>);
    const shown = items.slice(0, REPR_ITEMS).map(([k, v]) => `${pyRepr(k)}: ${pyRepr(v)}`);
    return `{${shown.join(", ")}${more(items.length)}}`;
  }
  return String(value);
}

/** Largest allowed atom count for this radius. */
export function maxAtoms(radius: number): number {
  return Math.min(ATOMS_MAX, cupCapacity(radius));
}

export function checkRadius(value: unknown, ranged = true): number {
  const ok =
    typeof value === "number" &&
    (ranged ? APPLET_RADIUS.contains(value) : Number.isFinite(value) && value > 0);
  const allowed = ranged ? APPLET_RADIUS.allowed() : "a positive number";
  if (!ok) throw new RangeError(`radius must be ${allowed} (got ${pyRepr(value)})`);
  return value;
}

export function checkNAtoms(value: unknown, radius: number, ranged = true): number {
  const top = ranged ? maxAtoms(radius) : null;
  const msg = ranged
    ? `n_atoms must be a whole number from 1 to ${top} for radius ${pyG(radius)}`
    : "n_atoms must be a whole number >= 1";
  const ok = typeof value === "number" && Number.isInteger(value) && value >= 1;
  if (!ok || (top !== null && value > top)) throw new RangeError(`${msg} (got ${pyRepr(value)})`);
  return value;
}

function checkChoice<T extends string>(name: string, value: unknown, allowed: readonly T[]): T {
  if (typeof value !== "string" || !(allowed as readonly string[]).includes(value)) {
    throw new RangeError(`${name} must be one of ${allowed.join(", ")} (got ${pyRepr(value)})`);
  }
  return value as T;
}

export const checkTcLaw = (v: unknown): TcLaw => checkChoice("tc_law", v, TC_LAW_NAMES);
export const checkEscape = (v: unknown): EscapeRule => checkChoice("escape", v, ESCAPE_RULES);

/** The same settings checked; RangeError naming the first bad field. ranged=false: URL values. */
export function validate(s: Settings, ranged = true): Settings {
  const radius = checkRadius(s.radius, ranged);
  return {
    nAtoms: checkNAtoms(s.nAtoms, radius, ranged),
    radius,
    tcLaw: checkTcLaw(s.tcLaw),
    escape: checkEscape(s.escape),
  };
}

/** Settings from a parsed stored object: each bad value falls back with one notice. */
export function fromMapping(data: Record<string, unknown>): [Settings, string[]] {
  const notices: string[] = [];
  const known = new Set<string>([...FIELD_NAMES, "version"]);
  const unknown = Object.keys(data)
    .filter((k) => !known.has(k))
    .sort();
  if (unknown.length) {
    // Named as the stored file has them, shortened: the notice stays a line.
    const names = unknown.slice(0, REPR_ITEMS).map((k) => pyRepr(k).slice(1, -1));
    if (unknown.length > REPR_ITEMS) names.push("...");
    notices.push(t("notice.settings_unknown", { names: names.join(", ") }));
  }
  function take<T>(name: FieldName, check: (v: unknown) => T, fallback: T): T {
    if (!Object.hasOwn(data, name)) return fallback;
    try {
      return check(data[name]);
    } catch (err) {
      const problem = (err as Error).message;
      notices.push(t("notice.settings_bad_value", { problem, default: pyRepr(fallback) }));
      return fallback;
    }
  }
  const radius = take("radius", (v) => checkRadius(v), DEFAULTS.radius);
  const fallbackN = Math.min(DEFAULTS.nAtoms, maxAtoms(radius));
  const nAtoms = take("n_atoms", (v) => checkNAtoms(v, radius), fallbackN);
  const tcLaw = take("tc_law", checkTcLaw, DEFAULTS.tcLaw);
  const escape = take("escape", checkEscape, DEFAULTS.escape);
  return [{ nAtoms, radius, tcLaw, escape }, notices];
}

/** The stored form: the desktop's settings.json fields. */
export function toMapping(s: Settings): Record<string, unknown> {
  return {
    version: FORMAT_VERSION,
    n_atoms: s.nAtoms,
    radius: s.radius,
    tc_law: s.tcLaw,
    escape: s.escape,
  };
}

/** The settings screen's -/+ on one field: numbers move and clamp, choices cycle. */
export function step(s: Settings, name: FieldName, direction: number): Settings {
  const d = direction > 0 ? 1 : -1;
  if (name === "n_atoms") {
    const n = d > 0 ? s.nAtoms : s.nAtoms - 1;
    const inc = n < 20 ? 1 : n < 100 ? 5 : n < 500 ? 50 : 100;
    return { ...s, nAtoms: Math.max(1, Math.min(maxAtoms(s.radius), s.nAtoms + d * inc)) };
  }
  if (name === "radius") {
    // Python rounds half to even; radii on screen are whole numbers anyway.
    const r = Math.max(RADIUS_MIN, Math.min(RADIUS_MAX, roundHalfEven(s.radius) + d));
    return { ...s, radius: r, nAtoms: Math.min(s.nAtoms, maxAtoms(r)) };
  }
  if (name === "tc_law") {
    const i = TC_LAW_NAMES.indexOf(s.tcLaw);
    return { ...s, tcLaw: TC_LAW_NAMES[(i + d + TC_LAW_NAMES.length) % TC_LAW_NAMES.length] };
  }
  const i = ESCAPE_RULES.indexOf(s.escape);
  return { ...s, escape: ESCAPE_RULES[(i + d + ESCAPE_RULES.length) % ESCAPE_RULES.length] };
}

function roundHalfEven(v: number): number {
  const f = Math.floor(v);
  const diff = v - f;
  if (diff > 0.5) return f + 1;
  if (diff < 0.5) return f;
  return f % 2 === 0 ? f : f + 1;
}

/** (label, value) rows for the settings screen, in the active language. */
export function describe(s: Settings): Array<[string, string]> {
  return [
    [t("settings.atoms"), t("settings.atoms_value", { n: s.nAtoms, max: maxAtoms(s.radius) })],
    [t("settings.radius"), t("settings.radius_value", { radius: s.radius })],
    [t("settings.tc_law"), t(s.tcLaw === "seed" ? "settings.law_seed" : "settings.law_cup")],
    [t("settings.escape"), t(s.escape === "rim" ? "settings.escape_rim" : "settings.escape_knife")],
  ];
}

export function sameSettings(a: Settings, b: Settings): boolean {
  return (
    a.nAtoms === b.nAtoms && a.radius === b.radius && a.tcLaw === b.tcLaw && a.escape === b.escape
  );
}

/** A short name for a settings combination: high scores are kept per settings. */
export function settingsKey(s: Settings): string {
  return `${s.nAtoms}-r${pyG(s.radius)}-${s.tcLaw}-${s.escape}`;
}
