/**
 * The frame loop and its clock: one display frame per animation frame, the physics
 * advanced by the time since the last one, then drawn if the picture changed. A frame
 * that throws is kept in `errors` (not rethrown: one bad frame is not fatal).
 */
import { FrameStats } from "./stats";

/** What the loop runs each frame. */
export interface Animated {
  /** Set by any input: the next frame draws. */
  dirty: boolean;
  /** Advance the game and the applet's clock by dt seconds of wall clock. */
  advance(dt: number): void;
  /** What the picture depends on besides input; "" means animated (draw every frame). */
  pictureKey(): string;
  draw(): void;
  /** Playing (not paused, not won): only these frames count for the display rate. */
  running(): boolean;
}

/** Errors kept for the console and the tests. */
const ERRORS_KEPT = 20;

export class FrameLoop {
  /** Every drawn frame (a paused applet draws only when something changes). */
  readonly stats = new FrameStats();
  /** Frames drawn while playing: the display rate the help reports (issue 27.5). */
  readonly playStats = new FrameStats();
  readonly errors: string[] = [];
  /** Display frames run so far. */
  frames = 0;
  private lastTime: number | null = null;
  private rafId = 0;
  private lastPicture = "";
  private drawnAt = -1;
  private wasRunning = false;

  constructor(private readonly target: Animated) {}

  start(): void {
    const loop = (now: number) => {
      this.rafId = requestAnimationFrame(loop);
      this.frame(now);
    };
    this.rafId = requestAnimationFrame(loop);
  }

  stop(): void {
    cancelAnimationFrame(this.rafId);
  }

  /** The next frame advances nothing (after the page was hidden, say). */
  resetClock(): void {
    this.lastTime = null;
  }

  /** One display frame at time `now` (ms): physics to now, then drawing. */
  frame(now: number): void {
    const t0 = performance.now();
    this.frames += 1;
    const dt = this.lastTime === null ? 0 : Math.max(0, (now - this.lastTime) / 1000);
    this.lastTime = now;
    const target = this.target;
    try {
      target.advance(dt);
      const key = target.pictureKey();
      if (!target.dirty && key !== "" && key === this.lastPicture) return; // nothing changed
      this.lastPicture = key;
      target.dirty = false;
      this.drawnAt = now;
      target.draw();
    } catch (err) {
      const text = `${(err as Error).name}: ${(err as Error).message}`;
      if (this.errors.length < ERRORS_KEPT) this.errors.push(text);
      if (this.errors.length === 1) console.error(err);
    }
    // The display rate is of play: a paused applet draws only when something changes.
    const running = target.running();
    if (running && !this.wasRunning) this.playStats.reset();
    this.wasRunning = running;
    if (this.drawnAt !== now) return;
    this.stats.add(now, performance.now() - t0);
    if (running) this.playStats.add(now, performance.now() - t0);
  }
}
