/**
 * The debrief's colour scale: viridis (dark violet to green-yellow), whose lightness rises
 * steadily along it, so it reads in greyscale and for colour-blind viewers. Its pale
 * yellow end is left off (SCALE_END): on the charts' white it would fade.
 */

/** Viridis at ten even steps of its scale (the published map's values, in sRGB). */
const STOPS: ReadonlyArray<readonly [number, number, number]> = [
  [68, 1, 84],
  [72, 40, 120],
  [62, 73, 137],
  [49, 104, 142],
  [38, 130, 142],
  [31, 158, 137],
  [53, 183, 121],
  [110, 206, 88],
  [181, 222, 43],
  [253, 231, 37],
];
/** The part of viridis used: 0 (no atom kept) .. SCALE_END (all kept). */
export const SCALE_END = 0.8;

/** The colour at x in 0..1 of the part used, as [r, g, b]. */
export function scaleRgb(x: number): [number, number, number] {
  const u = Math.min(1, Math.max(0, Number.isFinite(x) ? x : 0)) * SCALE_END;
  const pos = u * (STOPS.length - 1);
  const i = Math.min(STOPS.length - 2, Math.floor(pos));
  const f = pos - i;
  const [a, b] = [STOPS[i], STOPS[i + 1]];
  return [0, 1, 2].map((c) => Math.round(a[c] + f * (b[c] - a[c]))) as [number, number, number];
}

/** The CSS colour of a score of `max`. */
export function scoreColor(score: number, max: number): string {
  const [r, g, b] = scaleRgb(max > 0 ? score / max : 0);
  return `rgb(${r},${g},${b})`;
}

/** Relative luminance (WCAG) of an sRGB colour: what a greyscale copy keeps. */
export function luminance([r, g, b]: readonly [number, number, number]): number {
  const lin = (c: number) => {
    const s = c / 255;
    return s <= 0.04045 ? s / 12.92 : Math.pow((s + 0.055) / 1.055, 2.4);
  };
  return 0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b);
}
