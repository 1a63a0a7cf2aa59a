/**
 * Every game's recording (issue 22): at a win the game's moves, settings and seed become a
 * replay code the player can copy from the win screen (button or key C) into a chat or a
 * learning platform; `evapcool verify` and the page's verify panel check it by replaying.
 * Python's twin: `src/evapcool/app/replays.py` (docs/twins.md).
 */
import { t } from "../i18n";
import { recordingOf, type Recording } from "../game/replay";
import { encode } from "../game/replaycode";
import type { Game } from "../game/rules";
import { RemoteGame, type GameLike } from "../runtime/remote";

export interface ReplayHost {
  readonly game: GameLike;
  notify(text: string): void;
}

export class Replays {
  /** The newest win's code and the game (generation) it belongs to. */
  code: string | null = null;
  recording: Recording | null = null;
  private generation = -1;
  /** Called with each new win's code (class mode submits it). */
  readonly onCode: Array<(code: string, rec: Recording) => void> = [];
  /** Called once per game lost for good (class mode sends it when lost games count). */
  readonly onLost: Array<(rec: Recording) => void> = [];
  private lostGeneration = -1;

  constructor(private readonly host: ReplayHost) {}

  /** The code of the game just won (async: the worker's moves, then zlib). */
  async onWin(): Promise<void> {
    const g = this.host.game;
    const generation = g.generation;
    const runs = g instanceof RemoteGame ? await g.moves() : (g as Game).moves();
    const seed = g.config.seed;
    if (seed === null || g.generation !== generation) return;
    const rec = recordingOf(g.config, seed, runs, g.won, g.score);
    const code = await encode(rec);
    if (g.generation !== generation) return;
    // Not spoken: the win's own message is what the live region says now; the button and
    // key C are on the win screen and in the help.
    [this.code, this.recording, this.generation] = [code, rec, generation];
    for (const listener of this.onCode) listener(code, rec);
  }

  /** A game that can no longer win (too few atoms, for good): its recording so far, once
   * per game. */
  async onLoss(): Promise<void> {
    const g = this.host.game;
    const generation = g.generation;
    if (generation === this.lostGeneration || g.won) return;
    this.lostGeneration = generation;
    const runs = g instanceof RemoteGame ? await g.moves() : (g as Game).moves();
    const seed = g.config.seed;
    if (seed === null || g.generation !== generation || g.won) return;
    const rec = recordingOf(g.config, seed, runs, false, null);
    for (const listener of this.onLost) listener(rec);
  }

  /** The code of the game on screen, if it was won. */
  get current(): string | null {
    return this.host.game.generation === this.generation ? this.code : null;
  }

  /** Copy the code to the clipboard (the async API, else a selected text's copy command). */
  async copy(): Promise<void> {
    const code = this.current;
    if (!code) return;
    let copied = false;
    try {
      await navigator.clipboard.writeText(code);
      copied = true;
    } catch {
      copied = copyBySelection(code);
    }
    this.host.notify(
      copied ? t("page.code_copied", { n: code.length }) : t("page.code_by_hand", { code }),
    );
  }
}

/** The older way to copy: a selected, off-screen text and the copy command. */
export function copyBySelection(text: string): boolean {
  const area = document.createElement("textarea");
  area.value = text;
  area.setAttribute("readonly", "");
  area.style.position = "fixed";
  area.style.left = "-9999px";
  document.body.append(area);
  area.select();
  let ok = false;
  try {
    ok = document.execCommand("copy");
  } catch {
    ok = false;
  }
  area.remove();
  return ok;
}
