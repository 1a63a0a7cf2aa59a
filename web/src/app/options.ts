/** The settings screen (key O): a draft edited with the arrow keys or taps, saved or dropped. */
import type { GameConfig } from "../game/rules";
import {
  describe,
  FIELD_NAMES,
  sameSettings,
  step as stepSetting,
  tcExponent,
  type Settings,
} from "../game/settings";
import { loadSettings, saveSettings } from "../game/settingsStore";
import type { KeyValue } from "../game/store";
import type { Hints } from "./hints";

const NOT_SAVED = "Settings not saved: the changes were dropped.";
const ADDRESS_USES = (names: string) =>
  `This visit uses the address's ${names} until you save here.`;

export interface OptionsHost {
  storage: KeyValue;
  readonly hints: Hints;
  notify(text: string): void;
  say(text: string): void;
  /** The settings screen is closed (shown or not is the app's overlay). */
  closeOverlay(): void;
}

export class SettingsEditor {
  settings: Settings;
  draft: Settings;
  row = 0;

  constructor(
    private readonly host: OptionsHost,
    /** Settings for this visit from the address (not saved). */
    public overrides: Partial<Settings>,
  ) {
    const [saved, problems] = loadSettings(host.storage);
    problems.forEach((t) => host.notify(t));
    this.settings = saved;
    this.draft = saved;
  }

  /** The settings a restart plays: the saved ones under this visit's address options. */
  runSettings(): Settings {
    return { ...this.settings, ...this.overrides };
  }

  /** Open the screen on a fresh draft of the saved settings. */
  open(): void {
    this.draft = this.settings;
    this.row = 0;
    this.sayRow();
  }

  /** A key while the screen is open (lower-case KeyboardEvent.key). */
  key(key: string): void {
    const n = FIELD_NAMES.length;
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
    this.draft = stepSetting(this.draft, FIELD_NAMES[row], d);
    this.sayRow();
  }

  select(row: number): void {
    this.row = row;
    this.sayRow();
  }

  sayRow(): void {
    const [label, value] = describe(this.draft)[this.row];
    this.host.say(`${label} ${value}`);
  }

  close(save: boolean): void {
    this.host.closeOverlay();
    const draft = this.draft;
    if (sameSettings(draft, this.settings)) return;
    if (!save) {
      // A panel never drops changes silently (issue 27.1).
      this.host.notify(NOT_SAVED);
      return;
    }
    const base = this.settings;
    this.overrides = {}; // a choice made here beats the address for the rest of the visit
    // What was stored: this draft's changes over another tab's choices made meanwhile.
    const { saved, notices: problems } = saveSettings(this.host.storage, draft, base);
    this.settings = saved;
    problems.forEach((t) => this.host.notify(t));
    if (!problems.length) this.host.notify(this.host.hints.settingsSaved);
  }

  footer(): string[] {
    const lines = [...this.host.hints.settingsFooter];
    const names = Object.keys(this.overrides);
    if (names.length) lines.push(ADDRESS_USES(names.join(", ")));
    return lines;
  }
}

/** The game's configuration for settings s. */
export function configFor(s: Settings): Partial<GameConfig> {
  return { nAtoms: s.nAtoms, radius: s.radius, tcExponent: tcExponent(s), escape: s.escape };
}
