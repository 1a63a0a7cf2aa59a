/**
 * Panels over the play area: help, high scores, settings, the name box's frame and the
 * notices. Each draw returns the tap targets it drew (touch users have no keyboard).
 * Python's twin: `src/evapcool/app/overlays.py` (docs/twins.md).
 */
import { decimalMark, formatNumber, t, textDirection } from "../i18n";
import { formatSeconds, type Entry } from "../game/highscores";
import * as C from "./colors";
import { PLAY_RECT, rect, type Rect } from "./geometry";
import { frame, UNDER_MESSAGE } from "./scene";
import { drawText, fitSize, textWidth, wrap, type Anchor } from "./text";

export interface Target {
  rect: Rect;
  action: string;
  /** Its words for a screen reader (issue 48): a button's text, a row's label. */
  label?: string;
  /** A settings row's value as shown. */
  value?: string;
}

function overlay(ctx: CanvasRenderingContext2D, title: string, height: number): Rect {
  const w = PLAY_RECT.w - 24;
  const h = Math.min(height, PLAY_RECT.h - 8);
  const panel = rect(
    PLAY_RECT.x + (PLAY_RECT.w - w) / 2,
    PLAY_RECT.y + Math.floor((PLAY_RECT.h - h) / 2),
    w,
    h,
  );
  frame(ctx, panel);
  const size = fitSize(ctx, title, 34, panel.w - 20, 18);
  drawText(ctx, title, size, C.ACCENT, panel.x + panel.w / 2, panel.y + 12, "midtop", true);
  return panel;
}

/**
 * Where a line starts in the writing direction: left-to-right text starts at `x` in `box`,
 * right-to-left text (Arabic) at the mirrored place, anchored by its right end.
 */
function lineStart(box: Rect, x: number): [number, Anchor] {
  return textDirection() === "rtl" ? [2 * box.x + box.w - x, "topright"] : [x, "topleft"];
}

/** A small framed text button (tap target) inside an overlay. */
function textButton(
  ctx: CanvasRenderingContext2D,
  label: string,
  cx: number,
  y: number,
  action: string,
  out: Target[],
  h = 34,
): void {
  const size = Math.round((24 * h) / 34);
  const w = textWidth(ctx, label, size) + (28 * h) / 34;
  const r = rect(cx - w / 2, y, w, h);
  ctx.fillStyle = C.SELECTED_ROW;
  ctx.beginPath();
  ctx.roundRect(r.x, r.y, r.w, r.h, 6);
  ctx.fill();
  ctx.strokeStyle = C.ACCENT;
  ctx.lineWidth = 2;
  ctx.stroke();
  drawText(ctx, label, size, C.TEXT, cx, y + h / 2, "center", true);
  out.push({ rect: r, action, label });
}

/** Buttons in a row, centred on cx, h logical px tall. */
function buttonRow(
  ctx: CanvasRenderingContext2D,
  buttons: Array<[string, string]>,
  cx: number,
  y: number,
  out: Target[],
  h = 34,
): void {
  const size = Math.round((24 * h) / 34);
  // Right to left: the first button at the right.
  if (textDirection() === "rtl") buttons = [...buttons].reverse();
  const widths = buttons.map(([label]) => textWidth(ctx, label, size) + (28 * h) / 34);
  const gap = 16;
  let x = cx - (widths.reduce((a, b) => a + b, 0) + gap * (buttons.length - 1)) / 2;
  const first = out.length;
  buttons.forEach(([label, action], k) => {
    textButton(ctx, label, x + widths[k] / 2, y, action, out, h);
    x += widths[k] + gap;
  });
  // Listed in reading order (the keyboard's order): the first button first either way.
  if (textDirection() === "rtl") out.push(...out.splice(first).reverse());
}

/** The help as drawn: its tap targets and its row size (logical px; tests read it). */
export interface HelpDrawn {
  targets: Target[];
  size: number;
}

/**
 * The help: every control over the whole screen (issue 27.6), in two columns when the box
 * is wide (a projector), descriptions wrapped, at the largest size (to 44) that fits; never
 * below `minSize` (16 CSS px in logical px). `box`: the panel's room, logical px.
 */
export function drawHelp(
  ctx: CanvasRenderingContext2D,
  rows: Array<[string, string]>,
  footer: string[],
  box: Rect,
  minSize = 14,
): HelpDrawn {
  const columns = box.w > 1.5 * box.h ? 2 : 1;
  const fit = helpFit(ctx, rows, box, columns, footer.length, minSize);
  const { size, step, keyWidth, lines, perColumn } = fit;
  const panel = rect(box.x, box.y + Math.max(0, (box.h - fit.height) / 2), box.w, fit.height);
  frame(ctx, panel);
  const title = size * 1.4;
  drawText(
    ctx,
    t("controls.title"),
    title,
    C.ACCENT,
    panel.x + panel.w / 2,
    panel.y + 12,
    "midtop",
    true,
  );
  const colW = (panel.w - 36) / columns;
  let line = 0;
  rows.forEach(([keys], k) => {
    const c = Math.floor(k / perColumn);
    if (k % perColumn === 0) line = 0;
    const x = panel.x + 18 + c * colW;
    const y = panel.y + title + 28 + step * line;
    // Right to left: the key column at the right, the words right-aligned beside it.
    const [kx, kAnchor] = lineStart(panel, x);
    drawText(ctx, keys, size, C.ACCENT, kx, y, kAnchor, true);
    const [wx, wAnchor] = lineStart(panel, x + keyWidth + size * 0.7);
    lines[k].forEach((text, n) => drawText(ctx, text, size, C.TEXT, wx, y + n * step, wAnchor));
    line += lines[k].length;
  });
  const small = Math.max(minSize, size * 0.85);
  footer.forEach((text, k) => {
    const y = panel.y + panel.h - 14 - (footer.length - k) * (small + 6);
    drawText(ctx, text, small, C.DIM_TEXT, panel.x + panel.w / 2, y, "midtop");
  });
  return { targets: [{ rect: panel, action: "close", label: t("button.close") }], size };
}

interface HelpFit {
  size: number;
  step: number;
  keyWidth: number;
  /** Each row's description, wrapped to its column. */
  lines: string[][];
  perColumn: number;
  height: number;
}

/** The largest row size (44 down to minSize) at which the wrapped rows fit the box. */
function helpFit(
  ctx: CanvasRenderingContext2D,
  rows: Array<[string, string]>,
  box: Rect,
  columns: number,
  footerLines: number,
  minSize: number,
): HelpFit {
  const perColumn = Math.ceil(rows.length / columns);
  for (let size = 44; ; size -= 1) {
    const step = Math.round(size * 1.2);
    const keyWidth = Math.max(...rows.map(([k]) => textWidth(ctx, k, size)));
    const colW = (box.w - 36) / columns;
    const textW = colW - keyWidth - size * 0.7 - (columns > 1 ? size : 0);
    const lines = rows.map(([, what]) => wrap(ctx, what, size, Math.max(textW, size * 4)));
    let tallest = 0;
    for (let c = 0; c < columns; c++) {
      const inColumn = lines.slice(c * perColumn, (c + 1) * perColumn);
      tallest = Math.max(
        tallest,
        inColumn.reduce((n, l) => n + l.length, 0),
      );
    }
    const footer = footerLines * (Math.max(minSize, size * 0.85) + 6);
    const height = size * 1.4 + 28 + step * tallest + footer + 30;
    if (height <= box.h || size <= minSize) {
      return { size, step, keyWidth, lines, perColumn, height: Math.min(height, box.h) };
    }
  }
}

/** A word of the score table and where it was drawn (tests check each lies whole in its column). */
export interface TableCell {
  text: string;
  rect: Rect;
}

/** Column headers of the score table and the text of an empty one. */
const TABLE_HEADS = ["table.rank", "table.name", "table.atoms", "table.time", "table.date"];
/** Sizes (desktop units) the rows may take: the largest at which every column fits whole. */
const ROW_SIZE_MAX = 24;
const ROW_SIZE_MIN = 14;
const COLUMN_GAP = 14;

/** Whatever the name box accepts shows whole: columns as wide as their widest word, the rows'
 * size the largest at which they all fit the panel (the date goes first if none does). */
function tableColumns(
  ctx: CanvasRenderingContext2D,
  rows: string[][],
  inner: number,
): { size: number; widths: number[] } {
  const measure = (size: number, n: number) =>
    Array.from({ length: n }, (_, c) =>
      Math.max(
        textWidth(ctx, t(TABLE_HEADS[c]), size - 2) + 2,
        ...rows.map((r) => textWidth(ctx, r[c], size) + 2),
      ),
    );
  const total = (w: number[]) => w.reduce((a, b) => a + b, 0) + COLUMN_GAP * (w.length - 1);
  for (const n of [5, 4])
    for (let size = ROW_SIZE_MAX; size >= ROW_SIZE_MIN; size--) {
      const widths = measure(size, n);
      if (total(widths) <= inner) return { size, widths };
    }
  return { size: ROW_SIZE_MIN, widths: measure(ROW_SIZE_MIN, 4) };
}

export function drawTable(
  ctx: CanvasRenderingContext2D,
  title: string,
  entries: Entry[],
  highlight: number | null,
  footer: string[],
  buttons: Array<[string, string]>,
): { targets: Target[]; cells: TableCell[] } {
  const targets: Target[] = [];
  const cells: TableCell[] = [];
  const rows = Math.max(1, entries.length);
  const panel = overlay(ctx, t("scores.title"), 130 + 30 * (rows + 1 + footer.length) + 44);
  drawText(ctx, title, 20, C.DIM_TEXT, panel.x + panel.w / 2, panel.y + 48, "midtop");
  const texts = entries.map((e, k) => [
    formatNumber(k + 1),
    e.name,
    formatNumber(e.score),
    formatSeconds(e.seconds).replace(".", decimalMark()),
    e.date.slice(0, 10),
  ]);
  const { size, widths } = tableColumns(ctx, texts, panel.w - 32);
  const cols: number[] = [];
  let x = panel.x + 16;
  for (const w of widths) {
    cols.push(x);
    x += w + COLUMN_GAP;
  }
  const y0 = panel.y + 76;
  // Right to left: the rank column at the right, each word right-aligned in its column.
  cols.forEach((cx, c) => {
    const [hx, anchor] = lineStart(panel, cx);
    drawText(ctx, t(TABLE_HEADS[c]), size - 2, C.ACCENT, hx, y0, anchor, true);
  });
  const [ex, eAnchor] = lineStart(panel, cols[1]);
  if (!entries.length) drawText(ctx, t("scores.empty"), 24, C.TEXT, ex, y0 + 32, eAnchor);
  texts.forEach((row, k) => {
    const y = panel.y + 108 + 30 * k;
    const mine = highlight === k + 1;
    const color = mine ? C.ACCENT : C.TEXT;
    cols.forEach((cx, c) => {
      const [px, anchor] = lineStart(panel, cx);
      const w = drawText(ctx, row[c], size, color, px, y, anchor, mine);
      cells.push({ text: row[c], rect: rect(anchor === "topright" ? px - w : px, y, w, 30) });
    });
  });
  let y = panel.y + 108 + 30 * rows + 14;
  for (const line of footer) {
    drawText(ctx, line, 24, C.ACCENT, panel.x + panel.w / 2, y, "midtop", true);
    y += 30;
  }
  buttonRow(ctx, buttons, panel.x + panel.w / 2, y + 4, targets);
  return { targets, cells };
}

export function drawSettings(
  ctx: CanvasRenderingContext2D,
  rows: Array<[string, string]>,
  selected: number,
  footer: string[],
): Target[] {
  const targets: Target[] = [];
  // Rows closer together when many (the page's own preferences, issue 48): all fit the cup.
  const extra: Array<[string, string]> = [
    [t("link.copy"), "copylink"],
    [t("run.save"), "saverun"],
  ];
  const wide = extra.reduce((w, [label]) => w + textWidth(ctx, label, 21) + 40, 0);
  const stacked = wide > PLAY_RECT.w - 24 - 16;
  const pitch = rows.length <= 6 ? 40 : stacked ? 30 : 32;
  const high = 110 + pitch * rows.length + 28 * footer.length + 48 + (stacked ? 86 : 48);
  const panel = overlay(ctx, t("settings.title"), high);
  const rtl = textDirection() === "rtl";
  rows.forEach(([label, value], k) => {
    const y = panel.y + 60 + pitch * k;
    const row = rect(panel.x + 8, y - 5, panel.w - 16, pitch - 4);
    if (k === selected) {
      ctx.fillStyle = C.SELECTED_ROW;
      ctx.beginPath();
      ctx.roundRect(row.x, row.y, row.w, row.h, 4);
      ctx.fill();
      const [mx, mAnchor] = lineStart(panel, panel.x + 14);
      drawText(ctx, rtl ? "<" : ">", 26, C.ACCENT, mx, y, mAnchor, true);
    }
    // "< value >" at the row's end (its left end when right to left): "<" lowers, ">" raises.
    const vw = textWidth(ctx, value, 24);
    const block = vw + 62;
    const right = rtl ? panel.x + 16 + block : panel.x + panel.w - 16;
    // "<" and ">" on every row so a finger can change any value directly.
    drawText(ctx, ">", 24, C.ACCENT, right, y, "topright", true);
    drawText(ctx, value, 24, C.ACCENT, right - 26, y, "topright", true);
    // The label shrinks (to 12 at least) to leave the value its room, as on the desktop.
    const size = fitSize(ctx, label, 24, panel.w - 34 - vw - 62, 12);
    const [lx, lAnchor] = lineStart(panel, panel.x + 34);
    drawText(ctx, label, size, C.TEXT, lx, y + (24 - size) / 3, lAnchor, k === selected);
    drawText(ctx, "<", 24, C.ACCENT, right - 26 - vw - 10, y, "topright", true);
    const half = Math.max(40, (vw + 40) / 2);
    targets.push({ rect: rect(right - 2 * half, row.y, half, row.h), action: `dec:${k}` });
    targets.push({ rect: rect(right - half, row.y, half + 8, row.h), action: `inc:${k}` });
    targets.push({ rect: row, action: `row:${k}`, label, value });
  });
  let y = panel.y + 72 + pitch * rows.length;
  for (const line of footer) {
    drawText(ctx, line, 22, C.TEXT, panel.x + panel.w / 2, y, "midtop");
    y += 28;
  }
  buttonRow(
    ctx,
    [
      [t("button.save"), "save"],
      [t("button.cancel"), "cancel"],
    ],
    panel.x + panel.w / 2,
    y + 6,
    targets,
  );
  // What the teacher takes away (issue 48): the setup's link, the run's numbers; one under
  // the other where the two do not fit side by side.
  const cx = panel.x + panel.w / 2;
  if (!stacked) buttonRow(ctx, extra, cx, y + 48, targets, 30);
  else extra.forEach((b, k) => buttonRow(ctx, [b], cx, y + 48 + 38 * k, targets, 30));
  return targets;
}

/** The ring around the target that has the keyboard's focus (an element over it, issue 48). */
export function drawFocusRing(ctx: CanvasRenderingContext2D, targets: Target[], action: unknown) {
  const r = targets.find((x) => x.action === action)?.rect;
  if (!r) return;
  ctx.strokeStyle = C.FOCUS_RING;
  ctx.lineWidth = 4;
  ctx.beginPath();
  ctx.roundRect(r.x - 4, r.y - 4, r.w + 8, r.h + 8, 8);
  ctx.stroke();
}

/** The name box's hint for a keyboard; a touch screen gets only the Store and Skip buttons. */
const nameButtons = (): Array<[string, string]> => [
  [t("button.store"), "store"],
  [t("button.skip"), "skip"],
];

/**
 * The name box's frame, prompt, length, hint and its Store and Skip buttons under the
 * score; returns the buttons' targets. coarse: a finger, not a keyboard (no key hint);
 * buttonHeight: logical px (44 CSS px on a touch screen).
 */
export function drawNameFrame(
  ctx: CanvasRenderingContext2D,
  prompt: string,
  length: number,
  maxLength: number,
  coarse: boolean,
  buttonHeight = 34,
): Target[] {
  const f = rect(PLAY_RECT.x + 30, UNDER_MESSAGE, PLAY_RECT.w - 60, 142 + buttonHeight);
  frame(ctx, f);
  drawText(ctx, prompt, 26, C.ACCENT, f.x + f.w / 2, f.y + 10, "midtop", true);
  const field = nameField();
  const below = field.y + field.h + 8;
  const full = length >= maxLength;
  const count = `${length}/${maxLength}`;
  // The count sits at the line's end: the right in left-to-right text, the left in Arabic.
  const rtl = textDirection() === "rtl";
  const [cx, cAnchor]: [number, Anchor] = rtl
    ? [field.x, "topleft"]
    : [field.x + field.w, "topright"];
  const shown = full ? t("win.name_full", { count }) : count;
  drawText(ctx, shown, 22, full ? C.ACCENT : C.TEXT, cx, below, cAnchor, full);
  const [hx, hAnchor] = lineStart(field, field.x);
  if (!coarse) drawText(ctx, t("win.store_or_skip"), 22, C.TEXT, hx, below, hAnchor);
  const targets: Target[] = [];
  buttonRow(ctx, nameButtons(), f.x + f.w / 2, below + 34, targets, buttonHeight);
  return targets;
}

/** Where the name is typed (an input element over the canvas), logical px. */
export function nameField(): Rect {
  return rect(PLAY_RECT.x + 50, UNDER_MESSAGE + 40, PLAY_RECT.w - 100, 44);
}

/** Notices at the bottom of the play area, wrapped; returns their box (or null). */
export function drawNotices(ctx: CanvasRenderingContext2D, lines: string[]): Rect | null {
  if (!lines.length) return null;
  const width = PLAY_RECT.w - 32;
  const rows = lines.flatMap((line) => wrap(ctx, line, 22, width));
  const h = 12 + 20 * rows.length;
  const box = rect(PLAY_RECT.x + 6, PLAY_RECT.y + PLAY_RECT.h - 6 - h, PLAY_RECT.w - 12, h);
  ctx.fillStyle = C.NOTICE_SHADE;
  ctx.fillRect(box.x, box.y, box.w, box.h);
  rows.forEach((row, k) => {
    const [x, anchor] = lineStart(box, box.x + 10);
    drawText(ctx, row, 22, C.TEXT, x, box.y + 6 + 20 * k, anchor);
  });
  return box;
}

/** Text buttons in a row under the win's message (e.g. "Copy replay code"); their targets. */
export function drawMessageButtons(
  ctx: CanvasRenderingContext2D,
  buttons: Array<[string, string]>,
  height = 34,
): Target[] {
  const targets: Target[] = [];
  buttonRow(ctx, buttons, PLAY_RECT.x + PLAY_RECT.w / 2, UNDER_MESSAGE, targets, height);
  return targets;
}

/** The verify panel: title, the paste box's frame (a text area lies over it), the buttons
 * and the ranked results (wrapped to the panel). */
export function drawVerify(
  ctx: CanvasRenderingContext2D,
  paste: Rect,
  lines: string[],
  busy: boolean,
  buttonHeight = 34,
): Target[] {
  const panel = overlay(ctx, t("verify.title"), PLAY_RECT.h - 8);
  ctx.strokeStyle = C.ACCENT;
  ctx.lineWidth = 2;
  ctx.strokeRect(paste.x - 2, paste.y - 2, paste.w + 4, paste.h + 4);
  const targets: Target[] = [];
  const y = paste.y + paste.h + 12;
  const buttons: Array<[string, string]> = busy
    ? [[t("button.close"), "close"]]
    : [
        [t("button.verify"), "verifyrun"],
        [t("button.close"), "close"],
      ];
  buttonRow(ctx, buttons, panel.x + panel.w / 2, y, targets, buttonHeight);
  const rows = lines.flatMap((line) => wrap(ctx, line, 20, panel.w - 36));
  const top = y + buttonHeight + 14;
  const fit = Math.max(0, Math.floor((panel.y + panel.h - 12 - top) / 24));
  const shown =
    rows.length > fit
      ? [...rows.slice(0, fit - 1), t("page.more_lines", { n: rows.length - fit + 1 })]
      : rows;
  const [vx, vAnchor] = lineStart(panel, panel.x + 18);
  shown.forEach((row, k) => drawText(ctx, row, 20, C.TEXT, vx, top + 24 * k, vAnchor));
  return targets;
}
