/**
 * The key table: the README's controls (the help overlay lists exactly these rows).
 * Keys are KeyboardEvent.key values, compared without case.
 */
import { HEIGHT_MAX, HEIGHT_MIN, SPEED_MAX, SPEED_MIN } from "../game/rules";
import { formatNumber, t } from "../i18n";

export const HEIGHT_STEP = 5;

export type Action =
  | "pause"
  | "restart"
  | "lower"
  | "raise"
  | "step"
  | "faster"
  | "slower"
  | "energy"
  | "path"
  | "table"
  | "clear"
  | "next"
  | "settings"
  | "fullscreen"
  | "help"
  | "autopilot"
  | "copycode"
  | "verify"
  | "mute"
  | "describe"
  | "copylink"
  | "saverun"
  | "escape";

export interface Binding {
  keys: string[];
  /** The key's name: a help.key.* message, or the key cap itself (R, F11). */
  label: string;
  /** The help row's message key (help.*). */
  help: string;
  action: Action;
  more?: string[];
}

export const BINDINGS: Binding[] = [
  { keys: [" "], label: "help.key.space", help: "help.space", action: "pause" },
  { keys: ["r"], label: "R", help: "help.restart", action: "restart" },
  {
    keys: ["arrowleft", "arrowdown"],
    label: "help.key.left_down",
    help: "help.lower",
    action: "lower",
  },
  {
    keys: ["arrowright", "arrowup"],
    label: "help.key.right_up",
    help: "help.raise",
    action: "raise",
  },
  { keys: ["s"], label: "S", help: "help.step", action: "step" },
  { keys: ["+", "="], label: "+", help: "help.faster", action: "faster" },
  { keys: ["-", "_"], label: "-", help: "help.slower", action: "slower" },
  { keys: ["e"], label: "E", help: "help.energy", action: "energy" },
  { keys: ["g"], label: "G", help: "help.path", action: "path" },
  { keys: ["a"], label: "A", help: "help.autopilot_page", action: "autopilot" },
  { keys: ["t"], label: "T", help: "help.table", action: "table" },
  {
    keys: ["delete", "x"],
    label: "help.key.delete_x",
    help: "help.clear",
    action: "clear",
    more: ["help.clear_more"],
  },
  { keys: ["c"], label: "C", help: "help.copy", action: "copycode" },
  { keys: ["v"], label: "V", help: "help.verify", action: "verify" },
  { keys: ["enter"], label: "help.key.enter", help: "help.next", action: "next" },
  {
    keys: ["o"],
    label: "O",
    help: "help.settings",
    action: "settings",
    more: ["help.choose_change_save"],
  },
  { keys: ["m"], label: "M", help: "help.mute", action: "mute" },
  { keys: ["d"], label: "D", help: "help.describe", action: "describe" },
  { keys: ["l"], label: "L", help: "help.copylink", action: "copylink" },
  { keys: ["w"], label: "W", help: "help.saverun", action: "saverun" },
  { keys: ["f11"], label: "F11", help: "help.fullscreen", action: "fullscreen" },
  { keys: ["h", "f1"], label: "H, F1", help: "help.help", action: "help" },
  { keys: ["escape"], label: "help.key.esc", help: "help.escape_page", action: "escape" },
];

const KEYMAP = new Map<string, Action>(BINDINGS.flatMap((b) => b.keys.map((k) => [k, b.action])));

/** The action of a key (KeyboardEvent.key), or undefined. */
export function actionFor(key: string): Action | undefined {
  return KEYMAP.get(key.toLowerCase());
}

/** Rows of the help overlay in the active language: every binding, then the pointer's. */
export function helpRows(): Array<[string, string]> {
  const args = {
    height: 400,
    step: HEIGHT_STEP,
    fast: SPEED_MAX,
    slow: formatNumber(SPEED_MIN),
    low: HEIGHT_MIN,
    high: HEIGHT_MAX,
  };
  const rows: Array<[string, string]> = [];
  for (const b of BINDINGS) {
    rows.push([b.label.startsWith("help.") ? t(b.label) : b.label, t(b.help, args)]);
    for (const line of b.more ?? []) rows.push(["", t(line)]);
  }
  rows.push([t("controls.mouse_touch"), t("help.mouse_page")]);
  rows.push(["", t("help.mouse_page_more", args)]);
  return rows;
}
