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

const pilot = (name: string) => t("autopilot.label", { name });

export const KEY_HINTS: Hints = {
  touch: false,
  tooFewSpoken: (reason) => t("hint.too_few", { reason: t(reason) }),
  get tooFewLine() {
    return t("lose.try_again");
  },
  notTop: (n) => t("notice.not_top10", { n }),
  stored: (rank) => t("hint.stored", { rank }),
  get notStored() {
    return t("win.not_stored");
  },
  get tableFooter() {
    return t("table.footer");
  },
  get nextFooter() {
    return t("win.next_player");
  },
  get confirmClear() {
    return t("table.clear_confirm");
  },
  get confirmClearSpoken() {
    return t("scores.clear_confirm");
  },
  get hiddenPause() {
    return t("status.paused_hidden");
  },
  get settingsSaved() {
    return t("settings.saved");
  },
  get settingsFooter() {
    return [t("help.choose_change"), t("settings.save_cancel")];
  },
  autopilotPlays: (name) => t("notice.autopilot_plays", { name: pilot(name) }),
  get youHaveTheTrap() {
    return t("notice.you_have_trap");
  },
};

export const TOUCH_HINTS: Hints = {
  touch: true,
  tooFewSpoken: (reason) => t("hint.touch.too_few", { reason: t(reason) }),
  get tooFewLine() {
    return t("hint.touch.try_again");
  },
  notTop: (n) => t("hint.touch.not_top10", { n }),
  stored: (rank) => t("hint.touch.stored", { rank }),
  get notStored() {
    return t("hint.touch.not_stored");
  },
  get tableFooter() {
    return t("hint.touch.table_footer");
  },
  get nextFooter() {
    return t("hint.touch.next_player");
  },
  get confirmClear() {
    return t("hint.touch.clear_confirm");
  },
  get confirmClearSpoken() {
    return t("hint.touch.clear_confirm_spoken");
  },
  get hiddenPause() {
    return t("hint.touch.paused_hidden");
  },
  get settingsSaved() {
    return t("hint.touch.settings_saved");
  },
  get settingsFooter() {
    return [t("hint.touch.choose_change"), t("hint.touch.save_cancel")];
  },
  autopilotPlays: (name) => t("hint.touch.autopilot_plays", { name: pilot(name) }),
  get youHaveTheTrap() {
    return t("hint.touch.you_have_trap");
  },
};
