/**
 * The page's colours as CSS strings, per theme (issue 48): "dark", the original's colours
 * (SPEC 1) and the desktop edition's additions; "projector", a light high-contrast set with
 * thick lines and larger numbers for hall projectors. Every text and line stands at 7:1 or
 * more against its background in both (test/e2e/themes.test.mjs measures it in pixels).
 * The exports are live bindings: useTheme() switches them for the next frame.
 */
export type ThemeName = "dark" | "projector";
export const THEMES: readonly ThemeName[] = ["dark", "projector"];

const DARK = {
  BACKGROUND: "rgb(159,159,159)",
  BORDER: "rgb(79,79,79)",
  STRIP_LINE: "rgb(60,60,60)",
  CUP_COLOR: "rgb(0,0,0)",
  CUP_WIDTH: 6,
  TEXT: "rgb(255,255,255)",
  SHADOW: "rgb(30,30,30)",
  /** Behind a message over the play area (its words 7:1 against it). */
  PLATE: "rgba(25,25,25,0.82)",
  MERCURY: "rgb(220,20,20)",
  GLASS: "rgb(255,255,255)",
  GLASS_EDGE: "",
  TICK: "rgb(70,70,70)",
  ACCENT: "rgb(250,215,40)",
  DIM_TEXT: "rgb(240,240,240)",
  OVERLAY_SHADE: "rgba(10,10,30,0.882)",
  NOTICE_SHADE: "rgba(120,20,20,0.922)",
  SELECTED_ROW: "rgb(60,60,110)",
  /** Around a control button's face (none: the original's). */
  BUTTON_EDGE: "",
  PAGE: "rgb(0,0,0)",
  ATOM_RGB: [30, 215, 245] as readonly [number, number, number],
  /** Numbers and labels drawn this much larger. */
  TEXT_SCALE: 1,
};
type Palette = typeof DARK;
const PROJECTOR: Palette = {
  BACKGROUND: "rgb(255,255,255)",
  BORDER: "rgb(236,236,236)",
  STRIP_LINE: "rgb(0,0,0)",
  CUP_COLOR: "rgb(0,0,0)",
  CUP_WIDTH: 10,
  TEXT: "rgb(0,0,0)",
  SHADOW: "rgb(215,215,215)",
  PLATE: "rgba(255,255,255,0.92)",
  MERCURY: "rgb(185,0,0)",
  GLASS: "rgb(255,255,255)",
  GLASS_EDGE: "rgb(0,0,0)",
  TICK: "rgb(0,0,0)",
  ACCENT: "rgb(0,45,150)",
  DIM_TEXT: "rgb(25,25,25)",
  OVERLAY_SHADE: "rgba(255,255,255,0.97)",
  NOTICE_SHADE: "rgba(255,235,235,0.97)",
  SELECTED_ROW: "rgb(205,220,255)",
  BUTTON_EDGE: "rgb(0,0,0)",
  PAGE: "rgb(255,255,255)",
  ATOM_RGB: [0, 110, 235],
  TEXT_SCALE: 1.25,
};

export let BACKGROUND = DARK.BACKGROUND;
export let BORDER = DARK.BORDER;
export let STRIP_LINE = DARK.STRIP_LINE;
export let CUP_COLOR = DARK.CUP_COLOR;
export let CUP_WIDTH = DARK.CUP_WIDTH;
export let TEXT = DARK.TEXT;
export let SHADOW = DARK.SHADOW;
export let PLATE = DARK.PLATE;
export let MERCURY = DARK.MERCURY;
export let GLASS = DARK.GLASS;
export let GLASS_EDGE = DARK.GLASS_EDGE;
export let TICK = DARK.TICK;
export let ACCENT = DARK.ACCENT;
export let DIM_TEXT = DARK.DIM_TEXT;
export let OVERLAY_SHADE = DARK.OVERLAY_SHADE;
export let NOTICE_SHADE = DARK.NOTICE_SHADE;
export let SELECTED_ROW = DARK.SELECTED_ROW;
export let BUTTON_EDGE = DARK.BUTTON_EDGE;
export let PAGE = DARK.PAGE;
export let ATOM_RGB = DARK.ATOM_RGB;
export let TEXT_SCALE = DARK.TEXT_SCALE;
/** The theme in use; sprites drawn in another are drawn again. */
export let THEME: ThemeName = "dark";
export const YELLOW = "rgb(250,215,40)";
export const BLACK = "rgb(0,0,0)";
export const WHITE = "rgb(255,255,255)";
/** Button faces per look: idle yellow, lighter when hot, darker when pressed. */
export const FACE = { idle: "rgb(250,215,40)", hover: "rgb(255,236,120)", down: "rgb(222,180,20)" };
export const FOCUS_RING = "rgb(40,140,255)";

/** Draw from now on in theme `name`. */
export function useTheme(name: ThemeName): void {
  const p = name === "projector" ? PROJECTOR : DARK;
  THEME = name;
  ({ BACKGROUND, BORDER, STRIP_LINE, CUP_COLOR, CUP_WIDTH, TEXT, SHADOW, PLATE } = p);
  ({ MERCURY, GLASS, GLASS_EDGE, TICK, ACCENT, DIM_TEXT, OVERLAY_SHADE, NOTICE_SHADE } = p);
  ({ SELECTED_ROW, BUTTON_EDGE, PAGE, ATOM_RGB, TEXT_SCALE } = p);
}
