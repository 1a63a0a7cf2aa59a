/**
 * What the page tells a player to do, in the words of the device at hand (issue 27.2): keys
 * for a keyboard, taps for a touch screen ("tap restart", not "press R"); every word from the
 * active catalog (issue 23), so a change of language changes them at once.
 */
import { t } from "../i18n";

export interface Hints {
  /** A touch screen's words (no keys named). */
  touch: boolean;
  /** `reason`: a lose.* message key (Game.tooFewAtoms). */
  tooFewSpoken(reason: string): string;
  readonly tooFewLine: string;
  notTop(score: number): string;
  stored(rank: number): string;
  readonly notStored: string;
  readonly tableFooter: string;
  readonly nextFooter: string;
  readonly confirmClear: string;
  readonly confirmClearSpoken: string;
  readonly hiddenPause: string;
  readonly settingsSaved: string;
  readonly settingsFooter: string[];
  autopilotPlays(name: string): string;
  readonly youHaveTheTrap: string;
}

/** Each hint's message: [for a keyboard, for a touch screen]. */
const WORDS = {
  tooFewSpoken: ["hint.too_few", "hint.touch.too_few"],
  tooFewLine: ["lose.try_again", "hint.touch.try_again"],
  notTop: ["notice.not_top10", "hint.touch.not_top10"],
  stored: ["hint.stored", "hint.touch.stored"],
  notStored: ["win.not_stored", "hint.touch.not_stored"],
  tableFooter: ["table.footer", "hint.touch.table_footer"],
  nextFooter: ["win.next_player", "hint.touch.next_player"],
  confirmClear: ["table.clear_confirm", "hint.touch.clear_confirm"],
  confirmClearSpoken: ["scores.clear_confirm", "hint.touch.clear_confirm_spoken"],
  hiddenPause: ["status.paused_hidden", "hint.touch.paused_hidden"],
  settingsSaved: ["settings.saved", "hint.touch.settings_saved"],
  choose: ["help.choose_change", "hint.touch.choose_change"],
  saveCancel: ["settings.save_cancel", "hint.touch.save_cancel"],
  autopilotPlays: ["notice.autopilot_plays", "hint.touch.autopilot_plays"],
  youHaveTheTrap: ["notice.you_have_trap", "hint.touch.you_have_trap"],
} as const;

/** The hints of one kind of device, read from the active catalog each time they are asked. */
class DeviceHints implements Hints {
  constructor(readonly touch: boolean) {}

  private say(which: keyof typeof WORDS, args?: Record<string, string | number>): string {
    return t(WORDS[which][this.touch ? 1 : 0], args);
  }

  tooFewSpoken(reason: string): string {
    return this.say("tooFewSpoken", { reason: t(reason) });
  }
  get tooFewLine() {
    return this.say("tooFewLine");
  }
  notTop(n: number): string {
    return this.say("notTop", { n });
  }
  stored(rank: number): string {
    return this.say("stored", { rank });
  }
  get notStored() {
    return this.say("notStored");
  }
  get tableFooter() {
    return this.say("tableFooter");
  }
  get nextFooter() {
    return this.say("nextFooter");
  }
  get confirmClear() {
    return this.say("confirmClear");
  }
  get confirmClearSpoken() {
    return this.say("confirmClearSpoken");
  }
  get hiddenPause() {
    return this.say("hiddenPause");
  }
  get settingsSaved() {
    return this.say("settingsSaved");
  }
  get settingsFooter() {
    return [this.say("choose"), this.say("saveCancel")];
  }
  autopilotPlays(name: string): string {
    return this.say("autopilotPlays", { name: t("autopilot.label", { name }) });
  }
  get youHaveTheTrap() {
    return this.say("youHaveTheTrap");
  }
}

export const KEY_HINTS: Hints = new DeviceHints(false);
export const TOUCH_HINTS: Hints = new DeviceHints(true);
