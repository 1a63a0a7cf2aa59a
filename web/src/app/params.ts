/**
 * Settings from the page address, e.g. `?atoms=10000&radius=1&seed=3&speed=2`: for this
 * visit only, never saved (like the desktop's command-line options). One notice per bad
 * option, naming the option as typed, what is allowed and what was typed (shortened, like
 * the desktop's); the option is then ignored. Only plain decimal numbers count as numbers
 * (not `0x20`, not `Infinity`), and an option given twice is refused, not half-read.
 */
import { RADIUS, SEED } from "../limits";
import linkOptions from "../link-options.json";
import { availableLocales, bestMatch, t } from "../i18n";
import { HEIGHT_MAX, HEIGHT_MIN, SPEED_MAX, SPEED_MIN } from "../game/rules";
import { ESCAPE_RULES } from "../game/engine";
import { TC_LAWS, maxAtoms, RADIUS_MAX, RADIUS_MIN, type Settings } from "../game/settings";

export interface PageParams {
  overrides: Partial<Settings>;
  seed: number | null;
  speed: number;
  /** A replay code to watch (checked when decoded), or null. */
  replay: string | null;
  /** The language asked for (a shipped one, checked), or null. */
  lang: string | null;
  /** The trap's start height (px above the cup's bottom), or null: the game's own. */
  trap: number | null;
  /** Controls shown but not changeable (link-options.json's lock values). */
  lock: string[];
  /** Buttons (and the panels they open) left out. */
  hide: string[];
  theme: "dark" | "projector" | null;
  /** Sound asked on or off, or null: the page's default. */
  sound: boolean | null;
  notices: string[];
}

/** Physics' own limit on a count in the browser: beyond this a frame cannot keep up. */
export const URL_ATOMS_MAX = 100_000;
/** One option of the address as `link-options.json` lists it (shared with the desktop and
 * docs/teach.md's table). */
export interface LinkOption {
  name: string;
  kind: "whole" | "number" | "one_of" | "list" | "code" | "locale";
  low?: number;
  high?: number;
  range?: string;
  unit?: string;
  values?: string[];
  key: string;
}
export const LINK_OPTIONS = linkOptions.options as LinkOption[];
/** The options the address knows, in the order the notices name them. */
export const ADDRESS_OPTIONS: readonly string[] = LINK_OPTIONS.map((o) => o.name);
/** The values a list or one-of option allows, from the shared file. */
export function allowedValues(name: string): readonly string[] {
  const values = LINK_OPTIONS.find((o) => o.name === name)?.values;
  if (values === undefined) throw new Error(`link-options.json lists no values for ${name}`);
  return values;
}
/** The game's parameter names as the address spells them (for the physics' refusals). */
export const ADDRESS_NAMES: Readonly<Record<string, string>> = {
  nAtoms: "atoms",
  radius: "radius",
  tcExponent: "tc-law",
  escape: "escape",
};
/** A typed value or option name is shown up to this many characters. */
const SHOWN_CHARS = 24;
/** The seed the shared start generator takes: limits.py's SEED range (up to 2^53 - 1). */
const SEED_MAX = SEED.high;

const DECIMAL = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;

/** What the person typed, quoted and shortened: "abc", "99999999999999999999…" (400 characters). */
export function typed(text: string): string {
  const chars = [...text];
  if (chars.length <= SHOWN_CHARS) return JSON.stringify(text);
  const cut = JSON.stringify(chars.slice(0, SHOWN_CHARS - 4).join("") + "…");
  return t("page.typed_long", { text: cut, n: chars.length });
}

/** A plain decimal number, or null (hex, words, empty, Infinity are not numbers here). */
function decimal(text: string): number | null {
  const t = text.trim();
  if (!DECIMAL.test(t)) return null;
  const v = Number(t);
  return Number.isFinite(v) ? v : null;
}

const refusal = (option: string, allowed: string, raw: string): string =>
  t("page.address_refused", { option, allowed, got: typed(raw) });

/** "a whole number from 1 to 100000" in the active language; limits as typed in an address. */
const whole = (low: number, high: number) => t("page.allowed_whole", { low, high: `${high}` });
const oneOf = (names: readonly string[]) => t("page.allowed_one_of", { list: names.join(", ") });

/** The address's options, each checked once; bad ones named in notices and ignored. */
export function parseParams(search: string, saved: Settings): PageParams {
  const q = new URLSearchParams(search);
  const out: PageParams = {
    overrides: {},
    seed: null,
    speed: 1,
    replay: null,
    lang: null,
    trap: null,
    lock: [],
    hide: [],
    theme: null,
    sound: null,
    notices: [],
  };
  const known = new Set<string>(ADDRESS_OPTIONS);
  const seen = new Set<string>();
  for (const key of q.keys()) {
    if (seen.has(key)) continue;
    seen.add(key);
    if (!known.has(key))
      out.notices.push(
        t("page.address_unknown", { got: typed(key), known: ADDRESS_OPTIONS.join(", ") }),
      );
    else if (q.getAll(key).length > 1)
      out.notices.push(t("page.address_twice", { option: key, n: q.getAll(key).length }));
  }
  const value = (key: string): string | null =>
    q.getAll(key).length === 1 ? (q.get(key) as string) : null;

  let radius = saved.radius;
  const r = value("radius");
  if (r !== null) {
    const v = decimal(r);
    if (v !== null && RADIUS.contains(v)) radius = out.overrides.radius = v;
    else
      out.notices.push(
        refusal(
          "radius",
          t("page.allowed_px", { low: `${RADIUS.low}`, high: `${RADIUS.high}` }),
          r,
        ),
      );
  }
  const n = value("atoms");
  if (n !== null) {
    // Whether they fit the cup at this radius is the loader's word (named by ADDRESS_NAMES).
    const v = decimal(n);
    if (v !== null && Number.isInteger(v) && v >= 1 && v <= URL_ATOMS_MAX) out.overrides.nAtoms = v;
    else out.notices.push(refusal("atoms", whole(1, URL_ATOMS_MAX), n));
  } else if (out.overrides.radius !== undefined && radius >= RADIUS_MIN && radius <= RADIUS_MAX) {
    // Bigger atoms than saved: the saved count may not fit; take what does.
    out.overrides.nAtoms = Math.min(saved.nAtoms, maxAtoms(radius));
  }
  const law = value("tc-law");
  if (law !== null) {
    if (Object.hasOwn(TC_LAWS, law)) out.overrides.tcLaw = law as keyof typeof TC_LAWS;
    else out.notices.push(refusal("tc-law", oneOf(Object.keys(TC_LAWS)), law));
  }
  const escape = value("escape");
  if (escape !== null) {
    const rule = ESCAPE_RULES.find((e) => e === escape);
    if (rule !== undefined) out.overrides.escape = rule;
    else out.notices.push(refusal("escape", oneOf(ESCAPE_RULES), escape));
  }
  const s = value("seed");
  if (s !== null) {
    const v = decimal(s);
    if (v !== null && Number.isInteger(v) && v >= 0 && v <= SEED_MAX) out.seed = v;
    else out.notices.push(refusal("seed", whole(0, SEED_MAX), s));
  }
  const speed = value("speed");
  if (speed !== null) {
    const v = decimal(speed);
    if (v !== null && v >= SPEED_MIN && v <= SPEED_MAX) out.speed = v;
    else
      out.notices.push(
        refusal(
          "speed",
          t("page.allowed_number", { low: `${SPEED_MIN}`, high: `${SPEED_MAX}` }),
          speed,
        ),
      );
  }
  out.replay = value("replay");
  const lang = value("lang");
  if (lang !== null) {
    const tags = availableLocales();
    if (bestMatch([lang], tags) !== null) out.lang = lang;
    else out.notices.push(refusal("lang", oneOf(tags), lang));
  }
  parseNew(out, value);
  return out;
}

/** The options of issue 48: the start height, locks, hidden buttons, theme, sound. */
function parseNew(out: PageParams, value: (key: string) => string | null): void {
  const trap = value("trap");
  if (trap !== null) {
    const v = decimal(trap);
    if (v !== null && v >= HEIGHT_MIN && v <= HEIGHT_MAX) out.trap = v;
    else
      out.notices.push(
        refusal(
          "trap",
          t("page.allowed_px", { low: `${HEIGHT_MIN}`, high: `${HEIGHT_MAX}` }),
          trap,
        ),
      );
  }
  for (const name of ["lock", "hide"] as const) {
    const raw = value(name);
    if (raw === null) continue;
    const allowed = allowedValues(name);
    const items = raw.split(",").map((x) => x.trim());
    const list = items.length === 1 && items[0] === "" ? [] : items;
    if (list.every((x) => allowed.includes(x))) out[name] = [...new Set(list)];
    else out.notices.push(refusal(name, t("page.allowed_list", { list: allowed.join(", ") }), raw));
  }
  const theme = value("theme");
  if (theme !== null) {
    if (theme === "dark" || theme === "projector") out.theme = theme;
    else out.notices.push(refusal("theme", oneOf(allowedValues("theme")), theme));
  }
  const sound = value("sound");
  if (sound !== null) {
    if (sound === "on" || sound === "off") out.sound = sound === "on";
    else out.notices.push(refusal("sound", oneOf(allowedValues("sound")), sound));
  }
}
