/**
 * Frame times the page records itself: work per frame (physics + drawing) and display rate.
 * Python's twin: `src/evapcool/app/stats.py` (docs/twins.md).
 */

export interface FrameSummary {
  frames: number;
  medianMs: number;
  p95Ms: number;
  fps: number;
}

export function quantile(sorted: ArrayLike<number>, q: number): number {
  if (sorted.length === 0) return 0;
  const pos = (sorted.length - 1) * q;
  const lo = Math.floor(pos);
  const hi = Math.min(sorted.length - 1, lo + 1);
  return sorted[lo] + (sorted[hi] - sorted[lo]) * (pos - lo);
}

export class FrameStats {
  private work: Float64Array;
  private stamps: Float64Array;
  private count = 0;

  constructor(readonly capacity = 1200) {
    this.work = new Float64Array(capacity);
    this.stamps = new Float64Array(capacity);
  }

  add(now: number, workMs: number): void {
    const k = this.count % this.capacity;
    this.work[k] = workMs;
    this.stamps[k] = now;
    this.count++;
  }

  reset(): void {
    this.count = 0;
  }

  /** Median and 95th percentile of the work per frame, and frames per second, over the last n. */
  summary(n = 120): FrameSummary {
    const m = Math.min(n, this.count, this.capacity);
    if (m === 0) return { frames: 0, medianMs: 0, p95Ms: 0, fps: 0 };
    const work = new Float64Array(m);
    for (let k = 0; k < m; k++) {
      const idx = (this.count - m + k) % this.capacity;
      work[k] = this.work[idx];
    }
    work.sort();
    const first = this.stamps[(this.count - m) % this.capacity];
    const last = this.stamps[(this.count - 1) % this.capacity];
    return {
      frames: m,
      medianMs: quantile(work, 0.5),
      p95Ms: quantile(work, 0.95),
      // Frames shown per second over the span (a slow frame counts for its whole length).
      fps: last > first ? ((m - 1) * 1000) / (last - first) : 0,
    };
  }
}
