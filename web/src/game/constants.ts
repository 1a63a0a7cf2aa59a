/** The original applet's numbers (SPEC section 1), shared by the game and the view. */

export const FPS = 30;
export const WINDOW: readonly [number, number] = [640, 672];
export const BORDER_LEFT = 48;
export const BORDER_RIGHT = 96;
export const BORDER_TOP = 48;
export const BORDER_BOTTOM = 96;
/** px between the drawn cup bottom and the play-area bottom. */
export const CUP_DROP = 32;
export const N_ATOMS = 49;
export const ATOM_RADIUS = 12;
export const CURVATURE = 0.01;
export const GRAVITY = 10 / 30;
export const TC_EXPONENT_SEED = 2 / 3;
export const TC_EXPONENT_CUP = 2 / 5;
export const ESCAPE_RULES = ["rim", "knife"] as const;
export type EscapeRule = (typeof ESCAPE_RULES)[number];

/** Screen position of the drawn cup's lowest point: (296, 544) in 640 x 672. */
export function cupVertex(window: readonly [number, number] = WINDOW): [number, number] {
  const playW = window[0] - BORDER_LEFT - BORDER_RIGHT;
  return [BORDER_LEFT + playW / 2, window[1] - BORDER_BOTTOM - CUP_DROP];
}
