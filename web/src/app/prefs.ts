/**
 * The page's own preferences (issue 48), kept in the browser beside the game's settings: the
 * theme, the sound on or off, its volume. Rows of the settings screen, saved with them.
 */
import { THEMES, type ThemeName } from "../view/colors";
import { PREFIX, type KeyValue } from "../game/store";
import { t } from "../i18n";

export interface PagePrefs {
  theme: ThemeName;
  /** Sound on or off as chosen, or null: the page's default (off in class mode). */
  sound: boolean | null;
  /** 0 to 1 in tenths. */
  volume: number;
  /** A saved run's rows: one a frame (else one a second of play). */
  everyFrame: boolean;
}

export const PREFS_KEY = `${PREFIX}page`;
export const DEFAULT_PREFS: PagePrefs = {
  theme: "dark",
  sound: null,
  volume: 0.6,
  everyFrame: false,
};
/** The rows this file adds to the settings screen. */
export const PREF_ROWS = 4;

/** The stored preferences; anything unusable falls back to the default, silently per field. */
export function loadPrefs(kv: KeyValue): PagePrefs {
  let data: unknown = null;
  try {
    data = JSON.parse(kv.getItem(PREFS_KEY) ?? "null");
  } catch {
    data = null;
  }
  const d = (typeof data === "object" && data !== null ? data : {}) as Record<string, unknown>;
  const theme = THEMES.find((x) => x === d.theme) ?? DEFAULT_PREFS.theme;
  const sound = typeof d.sound === "boolean" ? d.sound : null;
  const v = d.volume;
  const volume = typeof v === "number" && v >= 0 && v <= 1 ? Math.round(v * 10) / 10 : 0.6;
  return { theme, sound, volume, everyFrame: d.everyFrame === true };
}

export function savePrefs(kv: KeyValue, p: PagePrefs): void {
  try {
    kv.setItem(PREFS_KEY, JSON.stringify(p));
  } catch {
    // Kept for this visit: the store has already said why it cannot keep data.
  }
}

/** The rows: colours, sound, volume. `soundOn`: what null means here. */
export function prefRows(p: PagePrefs, soundOn: boolean): Array<[string, string]> {
  const on = p.sound ?? soundOn;
  return [
    [t("theme.row"), t(p.theme === "projector" ? "theme.projector" : "theme.dark")],
    [t("sound.row"), t(on ? "sound.on" : "sound.off")],
    [t("sound.volume"), t("sound.volume_value", { percent: Math.round(p.volume * 100) })],
    [t("run.rows"), t(p.everyFrame ? "run.every_frame" : "run.every_second")],
  ];
}

/** Row k of prefRows changed one step in direction d. */
export function stepPref(p: PagePrefs, k: number, d: number, soundOn: boolean): PagePrefs {
  if (k === 0) return { ...p, theme: p.theme === "dark" ? "projector" : "dark" };
  if (k === 1) return { ...p, sound: !(p.sound ?? soundOn) };
  if (k === 3) return { ...p, everyFrame: !p.everyFrame };
  const volume = Math.round(Math.min(10, Math.max(0, p.volume * 10 + (d > 0 ? 1 : -1)))) / 10;
  return { ...p, volume };
}

export const samePrefs = (a: PagePrefs, b: PagePrefs): boolean =>
  a.theme === b.theme &&
  a.sound === b.sound &&
  a.volume === b.volume &&
  a.everyFrame === b.everyFrame;
