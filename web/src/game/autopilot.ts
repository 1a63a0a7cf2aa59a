/**
 * The autopilot in the page (twin of evapcool/game/autopilot.py): the demo strategy that
 * ships with the package (src/evapcool/data/demo_strategy.json, bundled here) moves the
 * trap each frame from what the player sees, until the player touches the trap.
 */
import { strategy as demoStrategy } from "../../../src/evapcool/data/demo_strategy.json";
import { clampHeight } from "./rules";
import type { SimLike } from "./sim";

/** kT of the cup's equilibrium gas is 2/5 of the mean energy per atom (SPEC 4). */
const KT_PER_MEAN_ENERGY = 0.4;

/** What the player sees at one frame: clock, thermometer, atom count (and gravity). */
export interface Reading {
  frame: number;
  temperature: number;
  criticalTemperature: number;
  nTrapped: number;
  gravity: number;
  mass: number;
}

/** A game's stateful rule: reading -> trap height (px, clamped to the slider). */
export type Controller = (r: Reading) => number;

export function readSim(sim: SimLike, mass = 1): Reading {
  const n = sim.nTrapped;
  return {
    frame: sim.time,
    temperature: sim.temperature,
    criticalTemperature: n ? sim.criticalTemperature : 0,
    nTrapped: n,
    gravity: sim.gravity,
    mass,
  };
}

/** H(t) through points (frame, H), linear between them, held outside (Python's Ramp). */
export function rampHeight(points: Array<[number, number]>, frame: number): number {
  if (frame <= points[0][0]) return clampHeight(points[0][1]);
  for (let k = 1; k < points.length; k++) {
    const [f0, h0] = points[k - 1];
    const [f1, h1] = points[k];
    if (frame <= f1) {
      const w = (frame - f0) / (f1 - f0);
      return clampHeight((1 - w) * h0 + w * h1);
    }
  }
  return clampHeight(points[points.length - 1][1]);
}

/** ln(T/Tc): how far the gas is from condensing (0 or less: it wins). */
function gap(r: Reading): number {
  if (r.nTrapped === 0 || r.temperature <= 0 || r.criticalTemperature <= 0) return 0;
  return Math.log(r.temperature / r.criticalTemperature);
}

const GUARDED_DEFAULTS: Record<string, number> = {
  h0: 425,
  h1: 162,
  duration: 1788,
  eta_cap: 12,
  gain: 10,
  eta_lo: 2,
  eta_floor: 0,
  rescue_from: 1800,
  rescue_rate: 0,
  rescue_gap: 0,
  budget: 1800,
};

/** A linear ramp cut lower when the win is far for the time left, with the rescue guard. */
function guarded(p: Record<string, number>): Controller {
  const ramp: Array<[number, number]> = [
    [0, p.h0],
    [Math.max(p.duration, 1), p.h1],
  ];
  const last = { h: Infinity, frame: 0 };
  return (r) => {
    let h = rampHeight(ramp, r.frame);
    if (r.nTrapped > 0 && r.temperature > 0 && r.criticalTemperature > 0) {
      const left = Math.max(1 - r.frame / p.budget, 0.01);
      const u = Math.max(Math.log(r.temperature / r.criticalTemperature), 0) / left;
      const eta = Math.max(p.eta_lo, p.eta_cap - p.gain * u);
      const unit = (KT_PER_MEAN_ENERGY * r.temperature) / (r.mass * r.gravity);
      h = clampHeight(Math.max(Math.min(h, eta * unit), p.eta_floor * unit));
    }
    if (r.frame > p.rescue_from && p.rescue_rate > 0) {
      const dt = Math.max(r.frame - Math.max(last.frame, p.rescue_from), 0);
      const behind = gap(r) > p.rescue_gap * Math.max(1 - r.frame / p.budget, 0);
      h = clampHeight(Math.min(h, last.h - (behind ? p.rescue_rate * dt : 0)));
    }
    last.h = h;
    last.frame = r.frame;
    return h;
  };
}

/** A strategy's text: a ramp "400@0,140@1800" or "guarded:name=value,...". */
export function parseStrategy(text: string): () => Controller {
  const s = text.trim();
  const policy = /^([a-z]+)\s*:(.*)$/.exec(s);
  if (policy) {
    if (policy[1] !== "guarded")
      throw new RangeError(`strategy: the page plays ramps and guarded policies, not ${policy[1]}`);
    const params = { ...GUARDED_DEFAULTS };
    for (const part of policy[2].split(",").filter((x) => x.trim())) {
      const [name, value] = part.split("=").map((x) => x.trim());
      if (!Object.hasOwn(GUARDED_DEFAULTS, name) || !Number.isFinite(Number(value)))
        throw new RangeError(`strategy: ${part.trim()} is not a guarded policy's name=number`);
      params[name] = Number(value);
    }
    return () => guarded(params);
  }
  const points: Array<[number, number]> = s.split(",").map((part) => {
    const [h, f] = part.split("@").map(Number);
    if (!Number.isFinite(h) || !Number.isFinite(f ?? 0))
      throw new RangeError(`strategy: ${part.trim()} is not height@frame`);
    return [f ?? 0, h];
  });
  return () => (r) => rampHeight(points, r.frame);
}

/** Steers a game (`setTrapHeight`) each frame until the player takes over. */
export interface Steered {
  readonly sim: SimLike;
  readonly paused: boolean;
  readonly won: boolean;
  setTrapHeight(h: number): boolean;
}

/**
 * Plays a strategy: `steer(game)` before each advance sets the trap for the frame from the
 * gas as it is; touching the trap calls `takeOver()`; `flew` says whether it moved the trap
 * in this game (its score is then the autopilot's, not a player's).
 */
export class Autopilot {
  engaged = true;
  flew = false;
  private control: Controller | null = null;

  constructor(
    private readonly build: () => Controller,
    readonly name = "demo",
  ) {}

  static demo(): Autopilot {
    return new Autopilot(parseStrategy(demoStrategy), "demo");
  }

  newGame(): void {
    this.control = null;
    this.flew = false;
  }

  engage(): void {
    this.engaged = true;
    this.control = null;
  }

  takeOver(): void {
    this.engaged = false;
  }

  /** The height set, or null when hands off, paused mid-game, won or empty. */
  steer(game: Steered): number | null {
    const sim = game.sim;
    const running = sim.time > 0;
    if (!this.engaged || game.won || sim.nTrapped === 0 || (game.paused && running)) return null;
    this.control ??= this.build();
    const h = this.control(readSim(sim));
    game.setTrapHeight(h);
    this.flew ||= running;
    return h;
  }
}
