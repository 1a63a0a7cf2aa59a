/**
 * Text on the canvas at the desktop's sizes. The desktop uses pygame's bundled bold sans
 * at size s, which pygame renders at 0.6875 s px; its "bold" is emboldened once more.
 */
import { textDirection } from "../i18n";

// Chinese, Japanese, Korean and Arabic letters come from the system's fonts named after
// Helvetica (the page's own font has Latin only): never boxes where any of these exists.
export const FONT_FAMILY =
  "EvapSans, 'Liberation Sans', Arial, Helvetica, 'Noto Sans CJK SC', 'PingFang SC', " +
  "'Microsoft YaHei', 'Hiragino Sans', 'Yu Gothic', 'Malgun Gothic', 'Noto Sans Arabic', " +
  "'Noto Naskh Arabic', Tahoma, sans-serif";
const PYGAME_SCALE = 0.6875;

/** Letters of right-to-left scripts (Hebrew, Arabic and their presentation forms). */
const RIGHT_TO_LEFT = /[\u0590-\u08ff\ufb1d-\ufdff\ufe70-\ufeff]/;

export type Anchor =
  | "center"
  | "midleft"
  | "midright"
  | "midtop"
  | "midbottom"
  | "topleft"
  | "topright"
  | "bottomleft"
  | "bottomright";

/** Canvas font for a desktop size. */
export function fontFor(size: number): string {
  return `700 ${(size * PYGAME_SCALE).toFixed(2)}px ${FONT_FAMILY}`;
}

/** Draw text anchored at (x, y) like pygame's get_rect(anchor=...); returns its width. */
export function drawText(
  ctx: CanvasRenderingContext2D,
  text: string,
  size: number,
  color: string,
  x: number,
  y: number,
  anchor: Anchor = "topleft",
  bold = false,
): number {
  ctx.font = fontFor(size);
  ctx.fillStyle = color;
  // Arabic lines run right to left (bidi order); the anchor still says where the box lies.
  // Lines without Arabic letters (a key cap, "<", a number) stay left to right: a lone "<"
  // in a right-to-left run would be drawn mirrored.
  ctx.direction = textDirection() === "rtl" && RIGHT_TO_LEFT.test(text) ? "rtl" : "ltr";
  ctx.textAlign = anchor.endsWith("left") ? "left" : anchor.endsWith("right") ? "right" : "center";
  ctx.textBaseline =
    anchor.startsWith("top") || anchor === "midtop"
      ? "top"
      : anchor.startsWith("bottom") || anchor === "midbottom"
        ? "bottom"
        : "middle";
  // pygame's line box is a little taller than the em box: shift top/bottom anchors to match.
  const em = size * PYGAME_SCALE;
  const dy = ctx.textBaseline === "top" ? em * 0.12 : ctx.textBaseline === "bottom" ? -em * 0.1 : 0;
  ctx.fillText(text, x, y + dy);
  if (bold) {
    ctx.lineWidth = Math.max(0.5, em * 0.045);
    ctx.strokeStyle = color;
    ctx.lineJoin = "round";
    ctx.strokeText(text, x, y + dy);
  }
  return ctx.measureText(text).width;
}

/** The largest size from `size` down to `min` at which `text` fits `width` (a long
 * translation shrinks instead of leaving its box). */
export function fitSize(
  ctx: CanvasRenderingContext2D,
  text: string,
  size: number,
  width: number,
  min: number,
): number {
  let s = size;
  while (s > min && textWidth(ctx, text, s) > width) s -= 1;
  return s;
}

export function textWidth(ctx: CanvasRenderingContext2D, text: string, size: number): number {
  ctx.font = fontFor(size);
  return ctx.measureText(text).width;
}

/** Chinese, Japanese and Korean characters: a line may break between any two of them. */
const CJK = /[\u3040-\u30ff\u3400-\u9fff\uac00-\ud7af\uf900-\ufaff\uff00-\uffef]/;

/** The pieces a line may break between: words, and each CJK character of a word. */
export function breakUnits(text: string): Array<{ piece: string; space: boolean }> {
  const out: Array<{ piece: string; space: boolean }> = [];
  for (const word of text.split(/\s+/).filter(Boolean)) {
    if (!CJK.test(word)) {
      out.push({ piece: word, space: true });
      continue;
    }
    let latin = "";
    [...word].forEach((ch, k) => {
      if (CJK.test(ch)) {
        if (latin) out.push({ piece: latin, space: false });
        latin = "";
        out.push({ piece: ch, space: k === 0 });
      } else latin += ch;
    });
    if (latin) out.push({ piece: latin, space: false });
  }
  return out;
}

/** Greedy word wrap to a width (a word wider than that gets its own row); CJK text breaks
 * between characters. */
export function wrap(
  ctx: CanvasRenderingContext2D,
  text: string,
  size: number,
  width: number,
): string[] {
  const rows: string[] = [];
  let row = "";
  for (const { piece, space } of breakUnits(text)) {
    const word = piece;
    const candidate = row ? `${row}${space ? " " : ""}${word}` : word;
    if (row && textWidth(ctx, candidate, size) > width) {
      rows.push(row);
      row = word;
    } else {
      row = candidate;
    }
  }
  if (row) rows.push(row);
  return rows.length ? rows : [""];
}
