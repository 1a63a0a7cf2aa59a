/**
 * The win and the name box, and the lines over the play area before it: the score at the
 * win (with the replay code's button, or the name box's frame when the score makes the
 * table), the too-few message when the gas can no longer condense, the start hint.
 * Python's twin: `src/evapcool/app/winscreen.py` (docs/twins.md).
 */
import { NAME_MAX } from "../game/highscores";
import { t } from "../i18n";
import { MIN_TARGET_CSS } from "../view/geometry";
import { drawMessageButtons, drawNameFrame, type Target } from "../view/overlays";
import type { Scene } from "../view/scene";
import type { Hints } from "./hints";
import type { Screen } from "./layout";
import type { Play } from "./play";
import type { Replays } from "./replays";
import type { Scoreboard } from "./scoring";

/** The rooms the win screen shows and tells. */
export interface WinRooms {
  readonly play: Play;
  readonly scores: Scoreboard;
  readonly replays: Replays;
  readonly scene: Scene;
  readonly screen: Screen;
  /** A touch screen: buttons of 44 CSS px at least, taps named in the hints. */
  readonly coarse: boolean;
  readonly hints: Hints;
  say(text: string): void;
}

export class WinScreen {
  private saidTooFew: string | null = null;
  /** "Press Space to start" before the first frame; off where no one has keys (a replay
   * presented on the projector, issue 45). */
  startHint = true;

  constructor(private readonly rooms: WinRooms) {}

  /** A win: the scores (name or not), and the game's replay code. */
  won(): void {
    this.rooms.scores.onWin();
    void this.rooms.replays.onWin().catch((err: unknown) => {
      console.warn(`evapcool: no replay code for this game (${(err as Error).message})`);
    });
  }

  /** The score, the too-few message or the start hint, and the win's buttons or the name
   * box's frame; their tap targets. `panelOpen`: a panel covers the play area. */
  draw(ctx: CanvasRenderingContext2D, panelOpen: boolean): Target[] {
    const { play, scores, replays, scene, hints, coarse } = this.rooms;
    const g = play.game;
    const tooFew = g.score === null ? g.tooFewAtoms() : null;
    if (g.score !== null) scene.drawScore(ctx, g.score);
    else if (tooFew !== null) {
      scene.drawTooFew(ctx, t(tooFew), hints.tooFewLine);
      if (tooFew !== this.saidTooFew) this.rooms.say(hints.tooFewSpoken(tooFew));
      // Lost for good (lowering the trap cannot help): a class may count the game.
      if (tooFew !== this.saidTooFew && tooFew !== "lose.stuck_here") void replays.onLoss();
    } else if (g.paused && g.sim.time === 0 && !panelOpen && this.startHint) {
      scene.drawStartHint(ctx, coarse);
    }
    this.saidTooFew = tooFew;
    const h = coarse ? Math.max(34, MIN_TARGET_CSS / this.rooms.screen.layout.scale) : 34;
    if (scores.nameBoxOpen)
      return drawNameFrame(ctx, t("win.top10"), scores.nameLength(), NAME_MAX, coarse, h);
    if (g.won && replays.current && !panelOpen)
      return drawMessageButtons(ctx, [[t("page.copy_code"), "copycode"]], h);
    return [];
  }
}
