/**
 * The game's pace against real time: physics frames advanced per second of wall clock,
 * over the speed's 30 frames a second. Below 1 the device cannot keep up and the game
 * runs in slow motion (it never takes bigger steps, see MAX_WALL_STEP); the page says so.
 */
import { formatFixed, t } from "../i18n";
import { FPS } from "../game/engine";

/** The note while the pace is below real time (pace as "0.87"). */
export const SLOW_NOTE = (pace: string) => t("page.slow_motion", { pace });
/** Pace measured over windows of this much wall clock, ms. */
const WINDOW_MS = 1000;
/**
 * A gap between frames longer than GAP_MS and GAP_FACTOR times the frames' typical gap (a
 * stalled tab) starts a new window; a device whose every frame is slow is measured.
 */
const GAP_MS = 250;
const GAP_FACTOR = 4;
/** Weight of each new gap in the typical gap (an exponential average). */
const GAP_WEIGHT = 0.1;
/** Slow below ENTER, real time again from LEAVE (no flicker near the line). */
const ENTER = 0.95;
const LEAVE = 0.98;

export class PaceMeter {
  /** The last full window's pace (1 = real time). */
  pace = 1;
  slow = false;
  private startMs = NaN;
  private startTime = 0;
  private lastMs = NaN;
  private typicalGap = NaN;
  private key = "";

  /**
   * A frame at wall `nowMs` with the physics at `time` frames; `key` names what a window
   * must keep (speed, game, pause): a change starts a new window.
   */
  add(nowMs: number, time: number, speed: number, running: boolean, key: string): void {
    const gap = nowMs - this.lastMs;
    this.lastMs = nowMs;
    const typical = Number.isNaN(this.typicalGap) ? 0 : this.typicalGap;
    const stalled = !(gap < Math.max(GAP_MS, GAP_FACTOR * typical));
    if (gap >= 0) this.typicalGap = this.typical(gap);
    const fresh = Number.isNaN(this.startMs) || time < this.startTime;
    if (!running || key !== this.key || stalled || fresh) {
      this.key = key;
      this.startMs = running ? nowMs : NaN;
      this.startTime = time;
      return;
    }
    const span = nowMs - this.startMs;
    if (!(span >= WINDOW_MS)) return;
    this.pace = (time - this.startTime) / ((span / 1000) * FPS * speed);
    this.slow = this.slow ? this.pace < LEAVE : this.pace < ENTER;
    this.startMs = nowMs;
    this.startTime = time;
  }

  private typical(gap: number): number {
    const was = this.typicalGap;
    return Number.isNaN(was) ? gap : was + GAP_WEIGHT * (gap - was);
  }

  /** The line to show, or null at real time. */
  note(): string | null {
    return this.slow ? SLOW_NOTE(formatFixed(this.pace, 2)) : null;
  }
}
