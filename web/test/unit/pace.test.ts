// The pace against real time and the slow-motion line (issue 24).
import fc from "fast-check";
import { describe, expect, test } from "vitest";
import { PaceMeter, SLOW_NOTE } from "../../src/app/pace";

/** Frames of `ms` wall time each, the physics advancing `pace` of real time at `speed`. */
function run(m: PaceMeter, frames: number, pace: number, speed = 1, ms = 16, from = [0, 0]) {
  let [now, time] = from;
  for (let k = 0; k < frames; k++) {
    now += ms;
    time += (ms / 1000) * 30 * speed * pace;
    m.add(now, time, speed, true, `${speed}|1`);
  }
  return [now, time];
}

describe("pace meter", () => {
  test("measures any steady pace over a second of play; the line below 0.95 only", () => {
    fc.assert(
      fc.property(
        fc.double({ min: 0.05, max: 1.2, noNaN: true }),
        fc.constantFrom(0.25, 0.5, 1, 2, 4),
        fc.integer({ min: 8, max: 1000 }),
        (pace, speed, ms) => {
          const m = new PaceMeter();
          run(m, Math.ceil(2500 / ms) + 2, pace, speed, ms);
          const close = Math.abs(m.pace - pace) < 1e-6;
          const line = m.note();
          return close && (pace < 0.95 ? line === SLOW_NOTE(m.pace.toFixed(2)) : line === null);
        },
      ),
    );
  });

  test("a pause, a new speed or a long gap starts over; the line leaves only from 0.98", () => {
    const m = new PaceMeter();
    let at = run(m, 200, 0.6);
    expect(m.note()).toBe("slow motion 0.60x: this device");
    at = run(m, 200, 0.96, 1, 16, at);
    expect(m.slow).toBe(true); // between 0.95 and 0.98: still slow
    run(m, 200, 1, 1, 16, at);
    expect(m.note()).toBeNull();
    // A gap of a hidden tab is not counted as slow play.
    const g = new PaceMeter();
    at = run(g, 100, 1);
    g.add(at[0] + 5000, at[1] + 1, 1, true, "1|1");
    run(g, 100, 1, 1, 16, [at[0] + 5000, at[1] + 1]);
    expect(g.slow).toBe(false);
    expect(g.pace).toBeCloseTo(1, 9);
    // A device throttled in play: frames of 300-400 ms each, none of them a stall.
    const d = new PaceMeter();
    at = run(d, 100, 1);
    for (let k = 0; k < 12; k++) at = run(d, 1, 0.1, 1, k % 2 ? 300 : 400, at);
    expect(d.note()).toBe("slow motion 0.10x: this device");
    // Paused frames start a new window.
    const p = new PaceMeter();
    p.add(0, 0, 1, true, "1|1");
    p.add(16, 0, 1, false, "1|1");
    p.add(2000, 0, 1, false, "1|1");
    run(p, 100, 1, 1, 16, [2000, 0]);
    expect(p.pace).toBeCloseTo(1, 9);
  });
});
