/**
 * What the page tells a player to do, in the words of the device at hand (issue 27.2): keys
 * for a keyboard, taps for a touch screen ("tap restart", not "press R").
 */
export interface Hints {
  /** A touch screen's words (no keys named). */
  touch: boolean;
  tooFewSpoken(reason: string): string;
  tooFewLine: string;
  notTop(score: number): string;
  stored(rank: number): string;
  notStored: string;
  tableFooter: string;
  nextFooter: string;
  confirmClear: string;
  confirmClearSpoken: string;
  hiddenPause: string;
  settingsSaved: string;
  settingsFooter: string[];
  autopilotPlays(name: string): string;
  youHaveTheTrap: string;
}

export const KEY_HINTS: Hints = {
  touch: false,
  tooFewSpoken: (reason) => `Too few atoms left. ${reason} Press R to try again.`,
  tooFewLine: "Press R (or restart) to try again.",
  notTop: (score) => `Score ${score} is not in the top 10 this time. Enter: next player.`,
  stored: (rank) => `Stored at place ${rank}. Enter: next player`,
  notStored: "Score not stored. Enter: next player.",
  tableFooter: "T: close   Delete or X: clear the table",
  nextFooter: "Enter: next player",
  confirmClear: "Clear all scores?  Y: yes   N or Esc: no",
  confirmClearSpoken: "Clear all scores? Y: yes, N or Escape: no",
  hiddenPause: "Paused while the page was hidden. Space or play: go on.",
  settingsSaved: "Settings saved. Press R (restart) to play with them.",
  settingsFooter: ["Up/Down choose, Left/Right change", "Enter or O: save   Esc: cancel"],
  autopilotPlays: (name) =>
    `Autopilot (${name}) plays: touch the slider to take over, A to hand back`,
  youHaveTheTrap: "You have the trap. A: autopilot again",
};

export const TOUCH_HINTS: Hints = {
  touch: true,
  tooFewSpoken: (reason) => `Too few atoms left. ${reason} Tap restart to try again.`,
  tooFewLine: "Tap restart to try again.",
  notTop: (score) => `Score ${score} is not in the top 10 this time. Tap restart: next player.`,
  stored: (rank) => `Stored at place ${rank}. Tap Next player`,
  notStored: "Score not stored. Tap restart: next player.",
  tableFooter: "Tap Close, or Clear... to empty the table",
  nextFooter: "Tap Next player",
  confirmClear: "Clear all scores?",
  confirmClearSpoken: "Clear all scores? Tap Yes, clear or No",
  hiddenPause: "Paused while the page was hidden. Tap play to go on.",
  settingsSaved: "Settings saved. Tap restart to play with them.",
  settingsFooter: ["Tap a row, then - or + to change it", "Tap Save, or Cancel"],
  autopilotPlays: (name) =>
    `Autopilot (${name}) plays: touch the slider to take over, the wheel to hand back`,
  youHaveTheTrap: "You have the trap. Tap the wheel: autopilot again",
};
