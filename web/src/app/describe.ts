/**
 * Key D (issue 48): the scene in one sentence for the live region: the atoms, T and Tc, the
 * trap height, and what is happening (atoms leaving, close to condensing, condensed...).
 */
import { formatFixed, t } from "../i18n";
import type { GameLike } from "../runtime/remote";

/** "Leaving" means an atom left within this much play (frames: two seconds). */
const RECENT_FRAMES = 60;
/** "Close to condensing": T within this factor of Tc. */
const CLOSE = 1.25;

export class SceneWatch {
  /** Play time (frames) an atom was last seen to leave, and the count then. */
  private lastLeft = -Infinity;
  private n = -1;
  private generation = -1;

  /** A drawn frame. */
  frame(g: GameLike): void {
    const s = g.sim;
    if (g.generation !== this.generation)
      [this.generation, this.n, this.lastLeft] = [g.generation, s.nTrapped, -Infinity];
    if (s.nTrapped < this.n) this.lastLeft = s.time;
    this.n = s.nTrapped;
  }

  /** What is happening, in the active language. */
  happening(g: GameLike): string {
    const s = g.sim;
    if (g.won) return t("describe.condensed");
    if (g.score === null && g.tooFewAtoms() !== null) return t("describe.too_few");
    const leaving = s.time - this.lastLeft <= RECENT_FRAMES;
    const close = s.temperature <= CLOSE * s.criticalTemperature;
    if (leaving && close) return t("describe.leaving_close");
    if (close) return t("describe.close");
    if (leaving) return t("describe.leaving");
    return t(g.paused ? "describe.paused" : "describe.waiting");
  }

  /** The sentence. */
  sentence(g: GameLike): string {
    const s = g.sim;
    return t("describe.scene", {
      n: s.nTrapped,
      temp: formatFixed(s.temperature, 2),
      tc: formatFixed(s.criticalTemperature, 2),
      h: Math.round(g.trapHeight),
      what: this.happening(g),
    });
  }
}
