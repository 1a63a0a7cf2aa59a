/**
 * The win's name entry and the high-score table, for one visit of the page.
 * Python's twin: `src/evapcool/app/scoring.py` (docs/twins.md).
 */
import { graphemes, HighScoreTable, scoresKey } from "../game/highscores";
import { settingsKey, type Settings } from "../game/settings";
import type { KeyValue } from "../game/store";
import { nameField } from "../view/overlays";
import { t } from "../i18n";
import type { Hints } from "./hints";
import type { Screen } from "./layout";
import type { GameLike } from "../runtime/remote";

const WON = (n: number) => t("page.won_spoken", { n });

export interface ScoringHost {
  readonly game: GameLike;
  readonly storage: KeyValue;
  readonly screen: Screen;
  readonly nameInput: HTMLInputElement;
  readonly canvas: HTMLCanvasElement;
  /** The words of the device at hand (keys or taps). */
  readonly hints: Hints;
  /** Who won if not the player (the autopilot, a replay): the win's notice; else null. */
  notAPlayer(score: number): string | null;
  notify(text: string): void;
  say(text: string): void;
  /** Drop a trap height still waiting to be spoken. */
  quiet(): void;
  /** The name box closed with the focus in it: focus the control that goes on (restart). */
  focusNext(): void;
  /** Show the table (or nothing) over the play area. */
  showTable(shown: boolean): void;
}

export class Scoreboard {
  table!: HighScoreTable;
  nameBoxOpen = false;
  storedRank: number | null = null;
  readyForNext = false;
  confirmReset = false;

  constructor(private readonly host: ScoringHost) {}

  /** The table of these settings (kept if it is already the open one). */
  openTable(s: Settings): void {
    const key = scoresKey(settingsKey(s));
    if (this.table?.key === key) return;
    this.table = new HighScoreTable(this.host.storage, key);
    this.takeNotices();
  }

  /** Another tab stored a score: show the table as it is now. */
  reload(): void {
    this.table.load();
    this.takeNotices();
  }

  private takeNotices(): void {
    this.table.takeNotices().forEach((t) => this.host.notify(t));
  }

  /** A new game: no name entry, no stored rank, no question pending. */
  newGame(): void {
    this.closeNameBox();
    this.readyForNext = false;
    this.storedRank = null;
    this.confirmReset = false;
  }

  onWin(): void {
    const g = this.host.game;
    const score = g.score ?? 0;
    const seconds = g.wonAt ?? 0;
    // The win is what matters now: a trap height still waiting to be spoken is dropped.
    this.host.quiet();
    this.host.say(WON(score));
    const other = this.host.notAPlayer(score);
    if (other !== null) {
      if (other) this.host.notify(other);
      this.readyForNext = true;
    } else if (this.table.qualifies(score, seconds)) {
      this.host.showTable(false); // the name box must be seen
      this.openNameBox();
    } else {
      this.host.notify(this.host.hints.notTop(score));
      this.readyForNext = true;
    }
  }

  private openNameBox(): void {
    this.nameBoxOpen = true;
    const input = this.host.nameInput;
    input.value = "";
    input.hidden = false;
    this.placeNameBox();
    input.focus({ preventScroll: true });
  }

  closeNameBox(): void {
    if (!this.nameBoxOpen) return;
    this.nameBoxOpen = false;
    const input = this.host.nameInput;
    const hadFocus = document.activeElement === input;
    input.hidden = true;
    // A control, not the whole canvas: its focus ring frames one button (issue 27.12).
    if (hadFocus) this.host.focusNext();
  }

  placeNameBox(): void {
    const screen = this.host.screen;
    if (!this.nameBoxOpen || !screen.layout) return;
    const input = this.host.nameInput;
    screen.place(input, nameField());
    // 16 CSS px at least: iOS Safari zooms the page into a smaller field (issue 27.9).
    input.style.fontSize = `${Math.max(16, 32 * 0.6875 * screen.layout.scale)}px`;
  }

  /** Letters typed in the name box (the frame drawn round it counts them). */
  nameLength(): number {
    return graphemes(this.host.nameInput.value).length;
  }

  storeName(name: string): void {
    const g = this.host.game;
    this.closeNameBox();
    this.storedRank = this.table.add(name, g.score ?? 0, g.wonAt ?? 0);
    this.takeNotices();
    this.host.showTable(true);
    this.readyForNext = true;
    if (this.storedRank !== null) this.host.say(this.host.hints.stored(this.storedRank));
  }

  skipName(): void {
    this.closeNameBox();
    this.host.notify(this.host.hints.notStored);
    this.readyForNext = true;
  }

  clearTable(yes: boolean): void {
    this.confirmReset = false;
    if (!yes) return;
    this.storedRank = null;
    if (this.table.reset()) this.host.notify(t("scores.cleared"));
    this.takeNotices();
  }

  footer(): string[] {
    const hints = this.host.hints;
    if (this.confirmReset) return [hints.confirmClear];
    if (this.readyForNext) return [hints.nextFooter];
    return [hints.tableFooter];
  }

  buttons(): Array<[string, string]> {
    if (this.confirmReset)
      return [
        [t("scores.clear_yes"), "yes"],
        [t("button.no"), "no"],
      ];
    if (this.readyForNext)
      return [
        [t("button.next_player"), "next"],
        [t("button.close"), "tableclose"],
      ];
    return [
      [t("button.close"), "tableclose"],
      [t("scores.clear"), "clear"],
      [t("button.verify_codes"), "verifycodes"],
    ];
  }
}

/** The settings a table belongs to, in words (its title). */
export function describeRun(s: Settings): string {
  const law = s.tcLaw === "seed" ? "Tc ~ N^(2/3)" : "Tc ~ N^(2/5)";
  return t("page.run", { n: s.nAtoms, radius: s.radius, law, escape: s.escape });
}
