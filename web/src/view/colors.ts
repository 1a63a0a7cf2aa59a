/** The original's colours (SPEC 1) and the desktop edition's additions, as CSS strings. */
export const BACKGROUND = "rgb(159,159,159)";
export const BORDER = "rgb(79,79,79)";
export const CUP_COLOR = "rgb(0,0,0)";
export const CUP_WIDTH = 6;
export const TEXT = "rgb(255,255,255)";
export const SHADOW = "rgb(30,30,30)";
export const MERCURY = "rgb(220,20,20)";
export const GLASS = "rgb(255,255,255)";
export const ACCENT = "rgb(250,215,40)";
export const DIM_TEXT = "rgb(220,220,220)";
export const OVERLAY_SHADE = "rgba(10,10,30,0.882)";
export const NOTICE_SHADE = "rgba(120,20,20,0.922)";
export const SELECTED_ROW = "rgb(60,60,110)";
export const YELLOW = "rgb(250,215,40)";
export const BLACK = "rgb(0,0,0)";
export const WHITE = "rgb(255,255,255)";
/** Button faces per look: idle yellow, lighter when hot, darker when pressed. */
export const FACE = { idle: "rgb(250,215,40)", hover: "rgb(255,236,120)", down: "rgb(222,180,20)" };
export const ATOM_RGB: readonly [number, number, number] = [30, 215, 245];
export const FOCUS_RING = "rgb(40,140,255)";
