/** Rectangles, the scene's fixed positions (SPEC 1) and the two layouts (wide and tall). */
import { BORDER_BOTTOM, BORDER_LEFT, BORDER_RIGHT, BORDER_TOP, WINDOW } from "./screen";

export interface Rect {
  x: number;
  y: number;
  w: number;
  h: number;
}

export const rect = (x: number, y: number, w: number, h: number): Rect => ({ x, y, w, h });
export const contains = (r: Rect, px: number, py: number): boolean =>
  px >= r.x && px < r.x + r.w && py >= r.y && py < r.y + r.h;
export const centerOf = (r: Rect): [number, number] => [r.x + r.w / 2, r.y + r.h / 2];

/** Grow r around its centre so each side is at least `min`. */
export function atLeast(r: Rect, min: number): Rect {
  const w = Math.max(r.w, min);
  const h = Math.max(r.h, min);
  return rect(r.x - (w - r.w) / 2, r.y - (h - r.h) / 2, w, h);
}

export const SCENE_W = WINDOW[0];
export const SCENE_H = WINDOW[1];
export const PLAY_RECT = rect(
  BORDER_LEFT,
  BORDER_TOP,
  SCENE_W - BORDER_LEFT - BORDER_RIGHT,
  SCENE_H - BORDER_TOP - BORDER_BOTTOM,
);
export const PAUSE_RECT = rect(64, 592, 64, 64);
export const RESTART_RECT = rect(144, 592, 64, 64);
export const SLIDER_RECT = rect(240, 611, 272, 8);
export const CHART_BUTTON_RECT = rect(528, 600, 40, 40);
export const KNOB_RADIUS = 10;
/** Width of the chart column beside the scene (logical px), as on the desktop. */
export const COLUMN_WIDTH = 520;
/** Touch targets: at least this many CSS px on a side (WCAG 2.5.5). */
export const MIN_TARGET_CSS = 44;

/** The tool buttons (help, scores, settings, full screen): not in the original. */
export const TOOLS = ["help", "table", "settings", "fullscreen"] as const;
export type Tool = (typeof TOOLS)[number];

export type ControlName = "pause" | "restart" | "chart" | Tool;

export interface Layout {
  mode: "wide" | "tall";
  /** Logical size of everything drawn. */
  width: number;
  height: number;
  /** CSS px per logical px, and where the logical origin sits in the viewport (CSS px). */
  scale: number;
  offsetX: number;
  offsetY: number;
  /** Scene rows drawn (the tall layout cuts the bottom border under the thermometer). */
  sceneHeight: number;
  buttons: Record<ControlName, Rect>;
  slider: Rect;
  knobRadius: number;
  /** The strip under the scene in the tall layout (null in the wide one). */
  strip: Rect | null;
  /** Chart rectangles, logical px. */
  charts: { energy?: Rect; path?: Rect };
}

/** Rows of the scene kept above the controls in the tall layout (the bulb ends at 618). */
export const TALL_SCENE_H = 626;
const STRIP_H = 236;

export interface ChartsShown {
  energy: boolean;
  path: boolean;
}

/** Largest scale fitting w x h into the viewport with the aspect kept, centred. */
export function fit(
  w: number,
  h: number,
  viewW: number,
  viewH: number,
): { scale: number; offsetX: number; offsetY: number } {
  const scale = Math.max(1e-3, Math.min(viewW / w, viewH / h));
  return { scale, offsetX: (viewW - w * scale) / 2, offsetY: (viewH - h * scale) / 2 };
}

function wideLayout(charts: ChartsShown): Omit<Layout, "scale" | "offsetX" | "offsetY"> {
  const shown = (["energy", "path"] as const).filter((k) => charts[k]);
  const width = SCENE_W + (shown.length ? COLUMN_WIDTH : 0);
  const chartRects: Layout["charts"] = {};
  shown.forEach((name, k) => {
    const h = Math.floor(SCENE_H / shown.length);
    chartRects[name] = rect(SCENE_W, k * h, COLUMN_WIDTH, h);
  });
  const tool = (k: number) => rect(470 + 42 * k, 6, 36, 36);
  return {
    mode: "wide",
    width,
    height: SCENE_H,
    sceneHeight: SCENE_H,
    buttons: {
      pause: PAUSE_RECT,
      restart: RESTART_RECT,
      chart: CHART_BUTTON_RECT,
      help: tool(0),
      table: tool(1),
      settings: tool(2),
      fullscreen: tool(3),
    },
    slider: SLIDER_RECT,
    knobRadius: KNOB_RADIUS,
    strip: null,
    charts: chartRects,
  };
}

/** Charts below the scene in the tall layout: logical height each, least and most. */
const TALL_CHART_MIN = 300;
const TALL_CHART_MAX = 420;

/**
 * Portrait screens: the scene at the top, the controls at the bottom edge (within the
 * thumb's reach), the charts between them when shown. The layout is as tall as the screen
 * is at the scene's width (`viewAspect` = height / width), so no band is left empty: without
 * charts the strip of controls grows upward to meet the scene.
 */
function tallLayout(
  charts: ChartsShown,
  viewAspect: number,
): Omit<Layout, "scale" | "offsetX" | "offsetY"> {
  const shown = (["energy", "path"] as const).filter((k) => charts[k]);
  const least = TALL_SCENE_H + STRIP_H + shown.length * TALL_CHART_MIN;
  const height = Math.max(least, Math.floor(SCENE_W * viewAspect));
  const room = height - TALL_SCENE_H - STRIP_H;
  const chartH = shown.length ? Math.min(TALL_CHART_MAX, room / shown.length) : 0;
  const chartRects: Layout["charts"] = {};
  shown.forEach((name, k) => {
    chartRects[name] = rect(0, TALL_SCENE_H + k * chartH, SCENE_W, chartH);
  });
  const stripTop = TALL_SCENE_H + shown.length * chartH;
  const strip = rect(0, stripTop, SCENE_W, height - stripTop);
  // The slider and the buttons keep their places from the strip's bottom edge.
  const top = height - STRIP_H;
  const names: ControlName[] = ["pause", "restart", "chart", "help", "table", "settings"];
  names.push("fullscreen");
  const size = 80;
  const gap = (SCENE_W - names.length * size) / (names.length + 1);
  const buttons = {} as Record<ControlName, Rect>;
  names.forEach((name, k) => {
    buttons[name] = rect(gap + k * (size + gap), top + 136, size, size);
  });
  return {
    mode: "tall",
    width: SCENE_W,
    height,
    sceneHeight: TALL_SCENE_H,
    buttons,
    slider: rect(56, top + 46, SCENE_W - 112, 12),
    knobRadius: 24,
    strip,
    charts: chartRects,
  };
}

/**
 * The layout for a viewport (CSS px): the desktop's scene with the charts to its right
 * when the window is wide enough for it, else (portrait phones) the scene above the
 * charts, a strip of big controls at the bottom edge.
 */
export function layoutFor(viewW: number, viewH: number, charts: ChartsShown): Layout {
  const wide = wideLayout(charts);
  const tall = tallLayout(charts, viewH / viewW);
  const fw = fit(wide.width, wide.height, viewW, viewH);
  const ft = fit(tall.width, tall.height, viewW, viewH);
  // Portrait screens: the tall layout when it draws the scene at least as large and the
  // wide one would make buttons too small to touch.
  const wideButtonCss = PAUSE_RECT.w * fw.scale;
  const useTall = viewH > viewW && (ft.scale >= fw.scale || wideButtonCss < MIN_TARGET_CSS);
  if (useTall) return { ...tall, ...ft };
  return toolsBeside({ ...wide, ...fw }, viewW);
}

/** CSS px of a tool button put beside the scene, and of the gap around it. */
const SIDE_TOOL_CSS = 52;
const SIDE_GAP_CSS = 10;

/**
 * A small landscape screen (a phone on its side) draws the top border's tool buttons and
 * the chart button too small to touch; when the space beside the scene allows, they move
 * there at 52 CSS px.
 */
function toolsBeside(l: Layout, viewW: number): Layout {
  const room = viewW - (l.offsetX + l.width * l.scale);
  // In the top border they sit 42 px apart: below 44 CSS px their touch areas would overlap.
  if (l.scale * 42 >= MIN_TARGET_CSS || room < SIDE_TOOL_CSS + 2 * SIDE_GAP_CSS) return l;
  const size = SIDE_TOOL_CSS / l.scale;
  const gap = SIDE_GAP_CSS / l.scale;
  const buttons = { ...l.buttons };
  const names: ControlName[] = [...TOOLS, "chart"];
  if (gap + names.length * (size + gap) > l.height) return l;
  names.forEach((name, k) => {
    buttons[name] = rect(l.width + gap, gap + k * (size + gap), size, size);
  });
  return { ...l, buttons };
}
