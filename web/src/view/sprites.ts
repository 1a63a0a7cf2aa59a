/**
 * Shaded cyan spheres for the atoms: one sprite per radius and device scale, rendered
 * once (Lambert + Phong from the upper left, like the desktop's) and drawn for every
 * atom in one pass of drawImage calls at whole device pixels.
 * Python's twin: `src/evapcool/view/sprites.py` (docs/twins.md).
 */
import * as C from "./colors";

const L = (() => {
  const v = [-0.45, -0.55, 0.7];
  const n = Math.hypot(v[0], v[1], v[2]);
  return v.map((c) => c / n);
})();

export interface Sprite {
  canvas: HTMLCanvasElement | OffscreenCanvas;
  /** Size in device px (square). */
  size: number;
}

/** Radii this close share a sprite (quarter pixels). */
export const spriteKey = (radius: number): number => Math.round(radius * 4) / 4;

/** RGBA pixels of a sphere of radius r device px on a (ceil(2r)+2)^2 square. */
export function spherePixels(
  r: number,
  rgb: readonly [number, number, number] = C.ATOM_RGB,
): { size: number; data: Uint8ClampedArray } {
  r = Math.max(r, 0.5);
  const size = Math.ceil(2 * r) + 2;
  const c = size / 2;
  const data = new Uint8ClampedArray(size * size * 4);
  for (let py = 0; py < size; py++) {
    for (let px = 0; px < size; px++) {
      const x = (px + 0.5 - c) / r;
      const y = (py + 0.5 - c) / r;
      const d2 = x * x + y * y;
      const z = Math.sqrt(Math.min(1, Math.max(0, 1 - d2)));
      const lambert = Math.min(1, Math.max(0, x * L[0] + y * L[1] + z * L[2]));
      const reflZ = 2 * lambert * z - L[2];
      const spec = Math.pow(Math.min(1, Math.max(0, reflZ)), 12);
      const alpha = Math.min(1, Math.max(0, (1 - Math.sqrt(d2)) * r + 0.5));
      const o = (py * size + px) * 4;
      for (let k = 0; k < 3; k++) {
        data[o + k] = rgb[k] * (0.38 + 0.62 * lambert) + 255 * 0.55 * spec;
      }
      data[o + 3] = alpha * 255 + 0.5;
    }
  }
  return { size, data };
}

function makeCanvas(size: number): HTMLCanvasElement | OffscreenCanvas {
  if (typeof OffscreenCanvas !== "undefined") return new OffscreenCanvas(size, size);
  const c = document.createElement("canvas");
  c.width = c.height = size;
  return c;
}

const cache = new Map<string, Sprite>();

/** The sprite of a sphere of `radius` logical px drawn at `scale` device px per logical px. */
export function atomSprite(radius: number, scale: number): Sprite {
  const key = `${spriteKey(radius)}@${scale.toFixed(4)}@${C.THEME}`;
  let sprite = cache.get(key);
  if (!sprite) {
    const { size, data } = spherePixels(spriteKey(radius) * scale);
    const canvas = makeCanvas(size);
    const ctx = canvas.getContext("2d") as CanvasRenderingContext2D | null;
    if (ctx)
      ctx.putImageData(new ImageData(data as Uint8ClampedArray<ArrayBuffer>, size, size), 0, 0);
    sprite = { canvas, size };
    if (cache.size > 64) cache.clear();
    cache.set(key, sprite);
  }
  return sprite;
}

/** Pixels of the sprite of `radius` at `scale`, as 32-bit RGBA words (little-endian). */
const wordsCache = new Map<string, { size: number; words: Uint32Array }>();
function spriteWords(radius: number, scale: number): { size: number; words: Uint32Array } {
  const key = `${spriteKey(radius)}@${scale.toFixed(4)}@${C.THEME}`;
  let w = wordsCache.get(key);
  if (!w) {
    const { size, data } = spherePixels(spriteKey(radius) * scale);
    w = { size, words: new Uint32Array(data.buffer, data.byteOffset, size * size) };
    if (wordsCache.size > 64) wordsCache.clear();
    wordsCache.set(key, w);
  }
  return w;
}

/**
 * Thousands of atoms: the sprites are copied into one image of the play area in plain
 * typed-array loops (edges blended), then that image is drawn once. Far cheaper than a
 * drawImage call per atom when there are many small ones.
 */
export class AtomLayer {
  private image: ImageData | null = null;
  private words: Uint32Array = new Uint32Array(0);
  private canvas: HTMLCanvasElement | OffscreenCanvas | null = null;
  private dirty = true;

  /** Start a frame covering w x h device px. */
  begin(w: number, h: number): void {
    w = Math.max(1, Math.ceil(w));
    h = Math.max(1, Math.ceil(h));
    if (!this.image || this.image.width !== w || this.image.height !== h) {
      this.image = new ImageData(w, h);
      this.words = new Uint32Array(this.image.data.buffer);
      this.canvas =
        typeof OffscreenCanvas !== "undefined"
          ? new OffscreenCanvas(w, h)
          : Object.assign(document.createElement("canvas"), { width: w, height: h });
    } else if (this.dirty) {
      this.words.fill(0);
    }
    this.dirty = false;
  }

  /** Add atoms whose centres are at device px (x0 + sx * x, y0 - sy * y) of the layer. */
  add(
    xs: Float64Array,
    ys: Float64Array,
    radii: Float64Array,
    count: number,
    scale: number,
    x0: number,
    y0: number,
  ): void {
    if (count === 0 || !this.image) return;
    this.dirty = true;
    const W = this.image.width;
    const H = this.image.height;
    const dst = this.words;
    let key = NaN;
    let sp = spriteWords(radii[0], scale);
    for (let i = 0; i < count; i++) {
      if (radii[i] !== key) {
        key = radii[i];
        sp = spriteWords(key, scale);
      }
      const size = sp.size;
      const left = Math.floor(x0 + xs[i] * scale - size / 2 + 0.5);
      const top = Math.floor(y0 - ys[i] * scale - size / 2 + 0.5);
      if (left >= W || top >= H || left + size <= 0 || top + size <= 0) continue;
      const sx0 = Math.max(0, -left);
      const sy0 = Math.max(0, -top);
      const sx1 = Math.min(size, W - left);
      const sy1 = Math.min(size, H - top);
      const src = sp.words;
      for (let sy = sy0; sy < sy1; sy++) {
        let d = (top + sy) * W + left + sx0;
        let s = sy * size + sx0;
        for (let sx = sx0; sx < sx1; sx++, d++, s++) {
          const p = src[s];
          const a = p >>> 24;
          if (a === 0) continue;
          const q = dst[d];
          if (a === 255 || q === 0) {
            dst[d] = p;
            continue;
          }
          dst[d] = over(p, q, a);
        }
      }
    }
  }

  /** Draw the layer with its top-left at device px (x, y). */
  draw(ctx: CanvasRenderingContext2D, x: number, y: number, alpha = 1): void {
    if (!this.image || !this.canvas) return;
    const c = this.canvas.getContext("2d") as CanvasRenderingContext2D;
    c.putImageData(this.image, 0, 0);
    const m = ctx.getTransform();
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.globalAlpha = alpha;
    ctx.drawImage(this.canvas, x, y);
    ctx.globalAlpha = 1;
    ctx.setTransform(m);
  }
}

/** Source-over of RGBA word p (alpha a) onto q, unpremultiplied. */
function over(p: number, q: number, a: number): number {
  const b = q >>> 24;
  const fa = a / 255;
  const fb = (b / 255) * (1 - fa);
  const out = fa + fb;
  const ch = (shift: number) =>
    Math.round((((p >>> shift) & 255) * fa + ((q >>> shift) & 255) * fb) / out) & 255;
  return ((Math.round(out * 255) << 24) | (ch(16) << 16) | (ch(8) << 8) | ch(0)) >>> 0;
}
