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

/** The buttons for what the keyboard alone did before (issue 27.2): S, -, +, G, A. */
export const EXTRAS = ["step", "slower", "faster", "path", "autopilot"] as const;
export type Extra = (typeof EXTRAS)[number];

export type ControlName = "pause" | "restart" | "chart" | Tool | Extra;
/** Every control, in the order the tall and side layouts draw them (rows, left to right). */
export const CONTROL_ORDER: ControlName[] = [
  "pause",
  "restart",
  "step",
  "slower",
  "faster",
  "autopilot",
  "chart",
  "path",
  ...TOOLS,
];

export interface Layout {
  /** wide: the desktop's scene; tall: a phone upright; side: a phone on its side. */
  mode: "wide" | "tall" | "side";
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
  /** The controls' own ground: under the scene (tall), beside it (wide, side). */
  strip: Rect | null;
  /** Where a tall screen's spare height shows the atom count and temperature large, or null. */
  readout: Rect | null;
  /** Chart rectangles, logical px. */
  charts: { energy?: Rect; path?: Rect };
}

/** Rows of the scene kept above the controls in the tall layout (the bulb ends at 618). */
export const TALL_SCENE_H = 626;
/** The tall layout's strip: the slider and its label, two rows of six 80 px buttons. */
const STRIP_H = 330;
const TALL_BUTTON = 80;
/** The wide layout's extra buttons: a column in the left border, 40 px each. */
const TOOLBAR_BUTTON = 40;

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
  const width = SCENE_W + (shownCharts(charts).length ? COLUMN_WIDTH : 0);
  const tool = (k: number) => rect(470 + 42 * k, 6, 36, 36);
  const extra = (k: number) =>
    rect(
      (BORDER_LEFT - TOOLBAR_BUTTON) / 2,
      BORDER_TOP + 12 + 50 * k,
      TOOLBAR_BUTTON,
      TOOLBAR_BUTTON,
    );
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
      ...(Object.fromEntries(EXTRAS.map((name, k) => [name, extra(k)])) as Record<Extra, Rect>),
    },
    slider: SLIDER_RECT,
    knobRadius: KNOB_RADIUS,
    strip: null,
    readout: null,
    charts: chartColumn(charts, SCENE_W, SCENE_H),
  };
}

function shownCharts(charts: ChartsShown): Array<"energy" | "path"> {
  return (["energy", "path"] as const).filter((k) => charts[k]);
}

/** The charts shown, stacked in a column at x, sharing its height. */
function chartColumn(charts: ChartsShown, x: number, height: number): Layout["charts"] {
  const shown = shownCharts(charts);
  const out: Layout["charts"] = {};
  shown.forEach((name, k) => {
    const h = Math.floor(height / shown.length);
    out[name] = rect(x, k * h, COLUMN_WIDTH, h);
  });
  return out;
}

/** The tall layout's readout: shown from this much spare height (logical px) on, and its
 * margin inside the strip. */
const READOUT_MIN = 140;
const READOUT_MARGIN = 16;

/** Charts below the scene in the tall layout: logical height each, least and most. */
const TALL_CHART_MIN = 280;
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
  // A tall phone's spare height above the slider: the atom count and temperature, large.
  const spare = top - stripTop - 2 * READOUT_MARGIN;
  const m = READOUT_MARGIN;
  const readout = spare >= READOUT_MIN ? rect(m, stripTop + m, SCENE_W - 2 * m, spare) : null;
  const perRow = CONTROL_ORDER.length / 2;
  const size = TALL_BUTTON;
  const gap = (SCENE_W - perRow * size) / (perRow + 1);
  const buttons = {} as Record<ControlName, Rect>;
  CONTROL_ORDER.forEach((name, k) => {
    const [row, col] = [Math.floor(k / perRow), k % perRow];
    buttons[name] = rect(gap + col * (size + gap), top + 140 + row * (size + 16), size, size);
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
    readout,
    charts: chartRects,
  };
}

/** The side layout's panel right of the scene: a tall slider, then a grid of buttons. */
const SIDE_PANEL_W = 430;
const SIDE_BUTTON = 84;
const SIDE_COLUMNS = 3;

/**
 * A phone on its side: the scene (its bottom border cut, as in the tall layout) at the
 * left edge, then a panel with the trap slider standing upright over most of the screen's
 * height (a thumb's sweep; up is a higher rim) and the buttons in a grid of 52 CSS px or
 * more, then the charts when shown.
 */
function sideLayout(charts: ChartsShown): Omit<Layout, "scale" | "offsetX" | "offsetY"> {
  const height = TALL_SCENE_H;
  const x0 = SCENE_W;
  const rows = Math.ceil(CONTROL_ORDER.length / SIDE_COLUMNS);
  const gap = 18;
  const gridTop = (height - rows * SIDE_BUTTON - (rows - 1) * gap) / 2;
  const buttons = {} as Record<ControlName, Rect>;
  CONTROL_ORDER.forEach((name, k) => {
    const [row, col] = [Math.floor(k / SIDE_COLUMNS), k % SIDE_COLUMNS];
    const x = x0 + 140 + col * (SIDE_BUTTON + gap);
    buttons[name] = rect(x, gridTop + row * (SIDE_BUTTON + gap), SIDE_BUTTON, SIDE_BUTTON);
  });
  const hasCharts = shownCharts(charts).length > 0;
  return {
    mode: "side",
    width: x0 + SIDE_PANEL_W + (hasCharts ? COLUMN_WIDTH : 0),
    height,
    sceneHeight: TALL_SCENE_H,
    buttons,
    slider: rect(x0 + 64, 84, 12, height - 84 - 34),
    knobRadius: 26,
    strip: rect(x0, 0, SIDE_PANEL_W, height),
    readout: null,
    charts: chartColumn(charts, x0 + SIDE_PANEL_W, height),
  };
}

/**
 * The layout for a viewport (CSS px): the desktop's scene with the charts to its right
 * when the window is large enough for its buttons to be touched (44 CSS px), else a phone's:
 * upright, the scene above the charts and a strip of big controls at the bottom edge; on its
 * side, the scene at the left and a panel of big controls beside it.
 */
export function layoutFor(viewW: number, viewH: number, charts: ChartsShown): Layout {
  const wide = wideLayout(charts);
  const fw = fit(wide.width, wide.height, viewW, viewH);
  const wideButtonCss = PAUSE_RECT.w * fw.scale;
  if (viewH > viewW) {
    const tall = tallLayout(charts, viewH / viewW);
    const ft = fit(tall.width, tall.height, viewW, viewH);
    // The tall layout when it draws the scene at least as large, or wide buttons are too small.
    if (ft.scale >= fw.scale || wideButtonCss < MIN_TARGET_CSS) return { ...tall, ...ft };
  } else if (wideButtonCss < MIN_TARGET_CSS) {
    const side = sideLayout(charts);
    return { ...side, ...fit(side.width, side.height, viewW, viewH) };
  }
  return { ...wide, ...fw };
}
