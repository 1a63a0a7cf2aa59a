/**
 * The key table: the README's controls (the help overlay lists exactly these rows).
 * Keys are KeyboardEvent.key values, compared without case.
 */
import { HEIGHT_MAX, HEIGHT_MIN } from "../game/rules";

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
  | "escape";

export interface Binding {
  keys: string[];
  label: string;
  help: string;
  action: Action;
  more?: string[];
}

export const BINDINGS: Binding[] = [
  { keys: [" "], label: "Space", help: "pause / play", action: "pause" },
  { keys: ["r"], label: "R", help: "restart: new atoms, trap at 400, paused", action: "restart" },
  {
    keys: ["arrowleft", "arrowdown"],
    label: "Left, Down",
    help: `lower the trap by ${HEIGHT_STEP} px`,
    action: "lower",
  },
  {
    keys: ["arrowright", "arrowup"],
    label: "Right, Up",
    help: `raise the trap by ${HEIGHT_STEP} px`,
    action: "raise",
  },
  { keys: ["s"], label: "S", help: "one frame forward (while paused)", action: "step" },
  { keys: ["+", "="], label: "+", help: "faster (up to 4x)", action: "faster" },
  { keys: ["-", "_"], label: "-", help: "slower (down to 0.25x)", action: "slower" },
  { keys: ["e"], label: "E", help: "energy chart on / off", action: "energy" },
  { keys: ["g"], label: "G", help: "path-to-condensation chart on / off", action: "path" },
  { keys: ["a"], label: "A", help: "autopilot on / off (the demo strategy)", action: "autopilot" },
  { keys: ["t"], label: "T", help: "high-score table on / off", action: "table" },
  {
    keys: ["delete", "x"],
    label: "Delete, X",
    help: "clear the high-score table...",
    action: "clear",
    more: ["...asks first: Y clears it, N or Esc keeps it"],
  },
  { keys: ["c"], label: "C", help: "after a win: copy its replay code", action: "copycode" },
  { keys: ["v"], label: "V", help: "verify replay codes (a class's results)", action: "verify" },
  { keys: ["enter"], label: "Enter", help: "after a name is stored: next player", action: "next" },
  {
    keys: ["o"],
    label: "O",
    help: "settings (R restarts with them)",
    action: "settings",
    more: ["Up/Down choose, Left/Right change, Enter/O save"],
  },
  { keys: ["f11"], label: "F11", help: "full screen on / off", action: "fullscreen" },
  { keys: ["h", "f1"], label: "H, F1", help: "this help on / off", action: "help" },
  { keys: ["escape"], label: "Esc", help: "close a panel or leave full screen", action: "escape" },
];

const KEYMAP = new Map<string, Action>(BINDINGS.flatMap((b) => b.keys.map((k) => [k, b.action])));

/** The action of a key (KeyboardEvent.key), or undefined. */
export function actionFor(key: string): Action | undefined {
  return KEYMAP.get(key.toLowerCase());
}

/** Rows of the help overlay: every binding, then the pointer controls. */
export function helpRows(): Array<[string, string]> {
  const rows: Array<[string, string]> = [];
  for (const b of BINDINGS) {
    rows.push([b.label, b.help]);
    for (const line of b.more ?? []) rows.push(["", line]);
  }
  rows.push(["Mouse, touch", "buttons; drag the slider: trap height"]);
  rows.push(["", `${HEIGHT_MIN} to ${HEIGHT_MAX} px; tap a panel to use it`]);
  return rows;
}
