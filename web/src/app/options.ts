/**
 * The settings screen (key O): a draft edited with the arrow keys or taps, saved or dropped.
 * Python's twin: `src/evapcool/app/options.py` (docs/twins.md).
 */
import type { GameConfig } from "../game/rules";
import {
  describe,
  FIELD_NAMES,
  type FieldName,
  sameSettings,
  step as stepSetting,
  tcExponent,
  type Settings,
} from "../game/settings";
import { loadSettings, saveSettings } from "../game/settingsStore";
import type { KeyValue } from "../game/store";
import { languageNames, STORAGE_KEY, t, useLocale } from "../i18n";
import type { Hints } from "./hints";
import {
  loadPrefs,
  PREF_ROWS,
  prefRows,
  samePrefs,
  savePrefs,
  stepPref,
  type PagePrefs,
} from "./prefs";

/** The sound's row on the settings screen (an on/off box for a screen reader). */
export const SOUND_ROW = FIELD_NAMES.length + 2;

/** The language row's value meaning "the browser's languages, then the address's". */
export const AUTO_LANGUAGE = "auto";

export interface OptionsHost {
  storage: KeyValue;
  readonly hints: Hints;
  /** The language the page starts in when the row says "as the browser". */
  readonly browserLocale: string;
  notify(text: string): void;
  say(text: string): void;
  /** The settings screen is closed (shown or not is the app's overlay). */
  closeOverlay(): void;
  /** A settings row a link locked (issue 48). */
  fieldLocked(field: FieldName): boolean;
  /** The sound's default here (no choice stored): off in class mode. */
  readonly soundByDefault: boolean;
  /** The page's preferences changed (saved): theme and sound follow. */
  prefsChanged(p: PagePrefs): void;
}

export class SettingsEditor {
  settings: Settings;
  draft: Settings;
  /** The language menu's saved choice and draft: a shipped tag or AUTO_LANGUAGE. */
  language: string;
  languageDraft: string;
  row = 0;
  /** The theme, sound and volume: saved, and the screen's draft. */
  prefs: PagePrefs;
  prefsDraft: PagePrefs;

  constructor(
    private readonly host: OptionsHost,
    /** Settings for this visit from the address (not saved). */
    public overrides: Partial<Settings>,
  ) {
    const [saved, problems] = loadSettings(host.storage);
    problems.forEach((t) => host.notify(t));
    this.settings = saved;
    this.draft = saved;
    this.language = host.storage.getItem(STORAGE_KEY) ?? AUTO_LANGUAGE;
    this.languageDraft = this.language;
    this.prefs = this.prefsDraft = loadPrefs(host.storage);
  }

  /** The sound on now (the choice saved, else the default here). */
  get soundOn(): boolean {
    return this.prefs.sound ?? this.host.soundByDefault;
  }

  /** The sound as the screen's draft has it. */
  get soundDraftOn(): boolean {
    return this.prefsDraft.sound ?? this.host.soundByDefault;
  }

  /** The screen's rows: the game's settings, then the language menu. */
  rows(): Array<[string, string]> {
    const choice = this.languageDraft;
    const name = languageNames().find((l) => l.tag === choice)?.name;
    const value = name ?? t("settings.language_browser");
    const game = describe(this.draft).map(([label, v], k): [string, string] =>
      this.host.fieldLocked(FIELD_NAMES[k])
        ? [label, t("link.locked_value", { value: v })]
        : [label, v],
    );
    const prefs = prefRows(this.prefsDraft, this.host.soundByDefault);
    return [...game, [t("settings.language"), value], ...prefs];
  }

  /** The settings a restart plays: the saved ones under this visit's address options. */
  runSettings(): Settings {
    return { ...this.settings, ...this.overrides };
  }

  /** Open the screen on a fresh draft of the saved settings. */
  open(): void {
    this.draft = this.settings;
    this.languageDraft = this.language;
    this.prefsDraft = this.prefs;
    this.row = 0;
    this.sayRow();
  }

  /** A key while the screen is open (lower-case KeyboardEvent.key). */
  key(key: string): void {
    const n = FIELD_NAMES.length + 1 + PREF_ROWS;
    if (key === "arrowup") this.row = (this.row + n - 1) % n;
    else if (key === "arrowdown") this.row = (this.row + 1) % n;
    else if (key === "arrowleft" || key === "arrowright") {
      this.change(this.row, key === "arrowright" ? 1 : -1);
      return;
    } else if (key === "enter" || key === "o") {
      this.close(true);
      return;
    } else if (key === "escape") {
      this.close(false);
      return;
    } else return;
    this.sayRow();
  }

  change(row: number, d: number): void {
    this.row = row;
    if (row < FIELD_NAMES.length && this.host.fieldLocked(FIELD_NAMES[row])) {
      this.host.notify(t("link.locked", { name: this.rows()[row][0] }));
      return;
    }
    if (row < FIELD_NAMES.length) this.draft = stepSetting(this.draft, FIELD_NAMES[row], d);
    else if (row > FIELD_NAMES.length) {
      const k = row - FIELD_NAMES.length - 1;
      this.prefsDraft = stepPref(this.prefsDraft, k, d, this.host.soundByDefault);
    } else {
      const choices = [AUTO_LANGUAGE, ...languageNames().map((l) => l.tag)];
      const i = Math.max(0, choices.indexOf(this.languageDraft));
      this.languageDraft = choices[(i + d + choices.length) % choices.length];
    }
    this.sayRow();
  }

  select(row: number): void {
    this.row = row;
    this.sayRow();
  }

  sayRow(): void {
    const [label, value] = this.rows()[this.row];
    this.host.say(`${label} ${value}`);
  }

  close(save: boolean): void {
    this.host.closeOverlay();
    const draft = this.draft;
    const newLanguage = this.languageDraft !== this.language;
    const newPrefs = !samePrefs(this.prefsDraft, this.prefs);
    if (sameSettings(draft, this.settings) && !newLanguage && !newPrefs) return;
    if (!save) {
      // A panel never drops changes silently (issue 27.1).
      this.host.notify(t("page.settings_dropped"));
      return;
    }
    if (newLanguage) this.saveLanguage();
    if (newPrefs) {
      this.prefs = this.prefsDraft;
      savePrefs(this.host.storage, this.prefs);
      this.host.prefsChanged(this.prefs);
    }
    if (sameSettings(draft, this.settings)) {
      this.host.notify(t(newLanguage ? "page.language_saved" : "settings.prefs_saved"));
      return;
    }
    const base = this.settings;
    // A choice made here beats the address for the rest of the visit; a locked one stays.
    this.overrides = Object.fromEntries(
      FIELD_NAMES.filter((f) => this.host.fieldLocked(f))
        .map((f) => ({ n_atoms: "nAtoms", radius: "radius", tc_law: "tcLaw", escape: "escape" })[f])
        .filter((k) => k in this.overrides)
        .map((k) => [k, this.overrides[k as keyof Settings]]),
    );
    // What was stored: this draft's changes over another tab's choices made meanwhile.
    const { saved, notices: problems } = saveSettings(this.host.storage, draft, base);
    this.settings = saved;
    problems.forEach((t) => this.host.notify(t));
    if (!problems.length) this.host.notify(this.host.hints.settingsSaved);
  }

  /** The language menu's choice from now on: kept in the browser, the page's words switch. */
  private saveLanguage(): void {
    const choice = this.languageDraft;
    this.language = choice;
    try {
      if (choice === AUTO_LANGUAGE) this.host.storage.removeItem(STORAGE_KEY);
      else this.host.storage.setItem(STORAGE_KEY, choice);
    } catch {
      // Kept for this visit: the store has already said why it cannot keep data.
    }
    useLocale(choice === AUTO_LANGUAGE ? this.host.browserLocale : choice);
  }

  footer(): string[] {
    const lines = [...this.host.hints.settingsFooter];
    const names = Object.keys(this.overrides);
    if (names.length) lines.push(t("page.address_uses", { names: names.join(", ") }));
    return lines;
  }
}

/** The game's configuration for settings s. */
export function configFor(s: Settings): Partial<GameConfig> {
  return { nAtoms: s.nAtoms, radius: s.radius, tcExponent: tcExponent(s), escape: s.escape };
}
