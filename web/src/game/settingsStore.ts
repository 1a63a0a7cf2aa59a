/** Settings in the browser's storage: the desktop's settings.json, under one key. */
import { DEFAULTS, fromMapping, toMapping, validate, type Settings } from "./settings";
import { PREFIX, readKey, setAside, writeKey, type KeyValue } from "./store";

export const SETTINGS_KEY = `${PREFIX}settings`;

/** Saved settings (defaults if none) and notices about anything that was wrong. */
export function loadSettings(kv: KeyValue): [Settings, string[]] {
  const notices: string[] = [];
  const text = readKey(kv, SETTINGS_KEY, notices);
  if (text === null) return [{ ...DEFAULTS }, notices];
  let data: unknown;
  try {
    data = JSON.parse(text);
  } catch {
    return [{ ...DEFAULTS }, [...notices, damaged(kv, text, "not valid JSON")]];
  }
  if (typeof data !== "object" || data === null || Array.isArray(data)) {
    return [{ ...DEFAULTS }, [...notices, damaged(kv, text, "not a JSON object")]];
  }
  const [settings, problems] = fromMapping(data as Record<string, unknown>);
  if (problems.length) {
    // Keep what was stored before its bad values are overwritten by the next save.
    const moved = setAside(kv, SETTINGS_KEY, text);
    if (moved) problems.push(`The stored settings were kept as "${moved}".`);
    writeKey(kv, SETTINGS_KEY, JSON.stringify(toMapping(settings)), "Settings", problems);
  }
  return [settings, [...notices, ...problems]];
}

function damaged(kv: KeyValue, text: string, why: string): string {
  const moved = setAside(kv, SETTINGS_KEY, text);
  return moved
    ? `The stored settings were damaged (${why}); they were kept as "${moved}"; using defaults.`
    : `The stored settings are damaged (${why}); using defaults.`;
}

/** Validate and store; returns notices (empty on success). */
export function saveSettings(kv: KeyValue, settings: Settings): string[] {
  const s = validate(settings);
  const notices: string[] = [];
  writeKey(kv, SETTINGS_KEY, JSON.stringify(toMapping(s)), "Settings", notices);
  return notices;
}
