/**
 * The condensate moment: after the win the atoms merge into one glowing wave packet at
 * the bottom of the cup, sized by the atoms left (the desktop's picture). It fades in
 * over 1.5 s and as the atoms settle; with reduced motion it neither breathes nor drifts.
 * Python's twin: `src/evapcool/view/condensate.py` (docs/twins.md).
 */
import type { AtomArrays, SimLike } from "../game/sim";
import { screenOrigin } from "./screen";

const EDGE = [255, 120, 40];
const CORE = [255, 250, 215];
/** The packet holds this fraction of the area the N disks would cover. */
const SHRINK = 0.35;
export const FADE_SECONDS = 1.5;
const SETTLED_SPEED = 1;

/** (half width, height) in trap px of the packet holding n atoms of radius r. */
export function packetSize(n: number, r: number, a: number): [number, number] {
  if (n <= 0) return [0, 0];
  const area = SHRINK * Math.PI * r * r * n;
  const h = Math.pow(0.75 * area * Math.sqrt(a), 2 / 3);
  return [Math.sqrt(h / a) + r, h + 2 * r];
}

export class Condensate {
  private gen = -1;
  private tWin: number | null = null;
  level = 0;
  private image: ImageData | null = null;
  private canvas: HTMLCanvasElement | OffscreenCanvas | null = null;

  /** Advance the fade for this frame and return it (0 before the win, up to 1). */
  update(sim: SimLike, atoms: AtomArrays, generation: number, t: number): number {
    if (generation !== this.gen) {
      this.gen = generation;
      this.tWin = null;
      this.level = 0;
    }
    if (!sim.won) return 0;
    if (this.tWin === null) this.tWin = t;
    const byTime = (t - this.tWin) / FADE_SECONDS;
    let speed = 0;
    for (let i = 0; i < atoms.count; i++) speed += Math.hypot(atoms.vx[i], atoms.vy[i]);
    speed = atoms.count ? speed / atoms.count : 0;
    const bySpeed = (3 * SETTLED_SPEED - speed) / (2 * SETTLED_SPEED);
    this.level = Math.max(this.level, Math.min(1, Math.max(0, Math.min(byTime, bySpeed))));
    return this.level;
  }

  /** Draw the packet with opacity `strength` at animation time t (s), logical px. */
  draw(
    ctx: CanvasRenderingContext2D,
    sim: SimLike,
    meanRadius: number,
    t: number,
    strength: number,
    still: boolean,
  ): void {
    const n = sim.nTrapped;
    if (n === 0 || strength <= 0) return;
    const r = meanRadius || 1;
    let [halfW, height] = packetSize(n, r, sim.curvature);
    const breathe = still ? 1 : 1 + 0.04 * Math.sin((2 * Math.PI * t) / 1.3);
    halfW *= breathe;
    const halfH = 0.5 * height * breathe;
    const [ox, oy] = screenOrigin(sim);
    const cx = ox;
    const cy = oy - (-r + 0.9 * halfH);
    // The image at logical resolution: a soft glow scales up smoothly.
    const gw = Math.max(4, Math.floor(2.6 * halfW));
    const gh = Math.max(4, Math.floor(2.6 * halfH));
    if (!this.image || this.image.width !== gw || this.image.height !== gh) {
      this.image = new ImageData(gw, gh);
      this.canvas =
        typeof OffscreenCanvas !== "undefined"
          ? new OffscreenCanvas(gw, gh)
          : Object.assign(document.createElement("canvas"), { width: gw, height: gh });
    }
    const data = this.image.data;
    const wavelength = Math.max(3, 1.6 * r);
    const phase = still ? 0 : 4 * t;
    for (let py = 0; py < gh; py++) {
      const v = (py - gh / 2 + 0.5) / halfH;
      for (let px = 0; px < gw; px++) {
        const x = px - gw / 2 + 0.5;
        const u = x / halfW;
        const envelope = Math.exp(-3 * (u * u + v * v));
        const fringes = 0.82 + 0.18 * Math.cos((2 * Math.PI * x) / wavelength - phase);
        const level = Math.min(1, Math.max(0, envelope * fringes * 1.5));
        const mix = level * level;
        const o = (py * gw + px) * 4;
        data[o] = EDGE[0] * (1 - mix) + CORE[0] * mix;
        data[o + 1] = EDGE[1] * (1 - mix) + CORE[1] * mix;
        data[o + 2] = EDGE[2] * (1 - mix) + CORE[2] * mix;
        data[o + 3] = 255 * strength * level;
      }
    }
    const c = this.canvas!.getContext("2d") as CanvasRenderingContext2D;
    c.putImageData(this.image, 0, 0);
    ctx.drawImage(this.canvas!, Math.round(cx - gw / 2), Math.round(cy - gh / 2));
  }
}
