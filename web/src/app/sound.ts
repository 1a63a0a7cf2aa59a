/**
 * Twin of Python's app/sound.py (docs/twins.md).
 * The page's sound (issue 48), synthesized by Web Audio (no audio files): each atom that
 * leaves a short tick whose pitch follows its energy (the m g h it needed to leave over the
 * rim at height h), the thermometer's approach to Tc a slow tone rising as T falls towards
 * Tc, the condensate a major chord, a lost game a falling tone. One graph: sources into a
 * master gain (the volume; 0 when muted) into the destination, so an OfflineAudioContext
 * renders exactly what the page plays (test/e2e/sound.test.mjs).
 */
import { HEIGHT_MAX, HEIGHT_MIN } from "../game/rules";

/** What the sound follows, read each drawn frame. */
export interface Heard {
  nTrapped: number;
  temperature: number;
  criticalTemperature: number;
  trapHeight: number;
  won: boolean;
  /** The game can no longer be won (too few atoms, or all gone). */
  lost: boolean;
  /** Bumped by each restart: no tick for the atoms a restart brings back. */
  generation: number;
}

/** At most this many ticks for one frame's departures (a crowd leaving is a burst). */
const TICKS_PER_FRAME_MAX = 6;
const TICK_S = 0.035;
const TICK_GAIN = 0.5;
/** The approach tone sounds from T = Tc / APPROACH_FROM down to Tc. */
const APPROACH_FROM = 0.45;
const DRONE_GAIN = 0.06;

/** A tick's pitch (Hz) for an atom leaving over a rim at height h: 300 Hz at the lowest
 * rim to 2 400 Hz at the highest, geometric in the energy m g h. */
export function tickPitch(h: number): number {
  const f =
    (Math.min(HEIGHT_MAX, Math.max(HEIGHT_MIN, h)) - HEIGHT_MIN) / (HEIGHT_MAX - HEIGHT_MIN);
  return 300 * 2 ** (3 * f);
}

export class Sound {
  private ctx: BaseAudioContext | null = null;
  private master: GainNode | null = null;
  private drone: { osc: OscillatorNode; gain: GainNode } | null = null;
  private last: Heard | null = null;
  on: boolean;
  volume: number;

  constructor(on: boolean, volume: number) {
    this.on = on;
    this.volume = volume;
  }

  get attached(): boolean {
    return this.ctx !== null;
  }

  /** Play into this context from now on (the page's, made on a first key or tap; or a test's
   * OfflineAudioContext). */
  attach(ctx: BaseAudioContext): void {
    this.ctx = ctx;
    this.master = ctx.createGain();
    this.master.connect(ctx.destination);
    this.setLevel();
    const osc = ctx.createOscillator();
    const gain = ctx.createGain();
    osc.type = "sine";
    gain.gain.value = 0;
    osc.connect(gain).connect(this.master);
    osc.start();
    this.drone = { osc, gain };
  }

  /** Sound on or off, and the volume (0 to 1): the master gain. */
  set(on: boolean, volume: number): void {
    this.on = on;
    this.volume = volume;
    this.setLevel();
  }

  private setLevel(): void {
    if (this.master) this.master.gain.value = this.on ? this.volume : 0;
  }

  /** One drawn frame: what changed since the last sounds at context time `at` (s). */
  frame(h: Heard, at?: number): void {
    const ctx = this.ctx;
    const last = this.last;
    this.last = { ...h };
    if (!ctx || !this.on) return;
    const now = at ?? ctx.currentTime;
    this.approach(h, now);
    if (!last || last.generation !== h.generation) return;
    const left = last.nTrapped - h.nTrapped;
    for (let k = 0; k < Math.min(left, TICKS_PER_FRAME_MAX); k++)
      this.tick(tickPitch(h.trapHeight), now + k * 0.012);
    if (h.won && !last.won) this.chord(now);
    if (h.lost && !last.lost) this.fall(now);
  }

  /** The slow tone: silent far above Tc, louder and higher as T comes down to it. */
  private approach(h: Heard, now: number): void {
    if (!this.drone) return;
    const ratio = h.temperature > 0 ? h.criticalTemperature / h.temperature : 0;
    const near =
      h.won || h.lost ? 0 : Math.min(1, Math.max(0, (ratio - APPROACH_FROM) / (1 - APPROACH_FROM)));
    this.drone.gain.gain.setTargetAtTime(DRONE_GAIN * near, now, 0.3);
    this.drone.osc.frequency.setTargetAtTime(110 * 2 ** (2 * near), now, 0.3);
  }

  private tone(
    type: OscillatorType,
    f0: number,
    f1: number,
    start: number,
    length: number,
    level: number,
  ): void {
    const ctx = this.ctx!;
    const osc = ctx.createOscillator();
    const env = ctx.createGain();
    osc.type = type;
    osc.frequency.setValueAtTime(f0, start);
    if (f1 !== f0) osc.frequency.exponentialRampToValueAtTime(f1, start + length);
    env.gain.setValueAtTime(0, start);
    env.gain.linearRampToValueAtTime(level, start + Math.min(0.005, length / 4));
    env.gain.exponentialRampToValueAtTime(0.0001, start + length);
    osc.connect(env).connect(this.master!);
    osc.start(start);
    osc.stop(start + length + 0.01);
  }

  tick(pitch: number, at: number): void {
    this.tone("triangle", pitch, pitch, at, TICK_S, TICK_GAIN);
  }

  /** The condensate: C, E, G and the octave, held and fading. */
  chord(at: number): void {
    for (const f of [261.63, 329.63, 392.0, 523.25]) this.tone("sine", f, f, at, 2.2, 0.12);
  }

  /** A lost game: a tone falling an octave and a half. */
  fall(at: number): void {
    this.tone("sawtooth", 440, 155, at, 1.4, 0.12);
  }
}
