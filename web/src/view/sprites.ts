/**
 * Shaded cyan spheres for the atoms: one sprite per radius and device scale, rendered
 * once (Lambert + Phong from the upper left, like the desktop's) and drawn for every
 * atom in one pass of drawImage calls at whole device pixels.
 */
import { ATOM_RGB } from "./colors";

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
  rgb: readonly [number, number, number] = ATOM_RGB,
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
  const key = `${spriteKey(radius)}@${scale.toFixed(4)}`;
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
