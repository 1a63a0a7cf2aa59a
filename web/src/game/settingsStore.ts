/** Settings in the browser's storage: the desktop's settings.json, under one key. */
import { t } from "../i18n";
import { DEFAULTS, fromMapping, toMapping, validate, type Settings } from "./settings";
import { PREFIX, readKey, setAside, writeKey, type KeyValue } from "./store";

export const SETTINGS_KEY = `${PREFIX}settings`;

/** Saved settings (defaults if none) and notices about anything that was wrong. */
export function loadSettings(kv: KeyValue): [Settings, string[]] {
  const notices: string[] = [];
  const text = readKey(kv, SETTINGS_KEY, notices);
  if (text === null) return [{ ...DEFAULTS }, notices];
  const data = storedObject(text);
  if (typeof data === "string") return [{ ...DEFAULTS }, [...notices, damaged(kv, text, data)]];
  const [settings, problems] = fromMapping(data);
  if (problems.length) {
    // Keep what was stored before its bad values are overwritten by the next save.
    const moved = setAside(kv, SETTINGS_KEY, text);
    if (moved) problems.push(t("page.settings_kept", { name: moved }));
    writeKey(kv, SETTINGS_KEY, JSON.stringify(toMapping(settings)), "settings", problems);
  }
  return [settings, [...notices, ...problems]];
}

/** The stored text's JSON object, or why it is none. */
function storedObject(text: string): Record<string, unknown> | string {
  let data: unknown;
  try {
    data = JSON.parse(text);
  } catch {
    return "not valid JSON";
  }
  if (typeof data !== "object" || data === null || Array.isArray(data)) return "not a JSON object";
  return data as Record<string, unknown>;
}

function damaged(kv: KeyValue, text: string, why: string): string {
  const moved = setAside(kv, SETTINGS_KEY, text);
  return moved
    ? t("page.settings_damaged", { why, name: moved })
    : t("page.settings_damaged_kept", { why });
}

/**
 * Validate and store; returns the settings now in force and notices (none on success).
 * `base`: the settings this visit
 * read or last saved; given, only the fields that differ from it are written over the
 * stored ones, so choices another tab saved meanwhile stay (the desktop does the same).
 */
export function saveSettings(
  kv: KeyValue,
  settings: Settings,
  base?: Settings,
): { saved: Settings; notices: string[] } {
  const mine = validate(settings);
  const s = base ? merged(kv, mine, base) : mine;
  const notices: string[] = [];
  const ok = writeKey(kv, SETTINGS_KEY, JSON.stringify(toMapping(s)), "settings", notices);
  return { saved: ok ? s : mine, notices };
}

/** The stored settings with the fields this visit changed (mine != base) on top. */
function merged(kv: KeyValue, mine: Settings, base: Settings): Settings {
  let text: string | null = null;
  try {
    text = kv.getItem(SETTINGS_KEY);
  } catch {
    return mine;
  }
  const data = text === null ? "absent" : storedObject(text);
  if (typeof data === "string") return mine;
  const [theirs] = fromMapping(data);
  const out: Settings = {
    nAtoms: mine.nAtoms !== base.nAtoms ? mine.nAtoms : theirs.nAtoms,
    radius: mine.radius !== base.radius ? mine.radius : theirs.radius,
    tcLaw: mine.tcLaw !== base.tcLaw ? mine.tcLaw : theirs.tcLaw,
    escape: mine.escape !== base.escape ? mine.escape : theirs.escape,
  };
  try {
    return validate(out);
  } catch {
    return mine; // their atom count does not fit my new radius, or the like
  }
}
