/**
 * Words on the debrief's canvases: one font stack with the scripts of every language the
 * catalogs speak, each word shrunk to its box down to a floor, and where and how big each
 * was drawn kept (the tests measure them: readable at the back of a lecture hall).
 */

export const FONT_FAMILY =
  "'Liberation Sans', Arial, Helvetica, 'Noto Sans CJK SC', 'PingFang SC', 'Microsoft YaHei', " +
  "'Hiragino Sans', 'Malgun Gothic', 'Noto Sans Arabic', 'Noto Naskh Arabic', Tahoma, sans-serif";

export type Align = "left" | "center" | "right";

/** A word drawn: its text, its size in px (canvas), its box. */
export interface DrawnWord {
  text: string;
  size: number;
  x: number;
  y: number;
  w: number;
  h: number;
}

export function font(size: number): string {
  return `700 ${size}px ${FONT_FAMILY}`;
}

/** The largest size from `size` down to `floor` at which text fits `width`. */
export function fitted(
  ctx: CanvasRenderingContext2D,
  text: string,
  size: number,
  width: number,
  floor: number,
): number {
  let s = Math.floor(size);
  for (; s > floor; s--) {
    ctx.font = font(s);
    if (ctx.measureText(text).width <= width) return s;
  }
  return floor;
}

/** Draw text with its vertical middle at y, aligned at x; the word kept in `out`. */
export function word(
  ctx: CanvasRenderingContext2D,
  out: DrawnWord[],
  text: string,
  size: number,
  color: string,
  x: number,
  y: number,
  align: Align = "left",
): number {
  ctx.font = font(size);
  ctx.fillStyle = color;
  ctx.textAlign = align;
  ctx.textBaseline = "middle";
  ctx.fillText(text, x, y);
  const w = ctx.measureText(text).width;
  const left = align === "left" ? x : align === "center" ? x - w / 2 : x - w;
  out.push({ text, size, x: left, y: y - size / 2, w, h: size });
  return w;
}
