/**
 * The original applet's physical constants (SPEC section 1) and the model's fixed numbers
 * (docs/model.md); the screen is the view's (view/screen.ts), the room physics/room.ts.
 */

/** Frames per second of the original; physics time is measured in frames. */
export const FPS = 30;
/** g, px / frame^2, pointing down the screen. */
export const GRAVITY = 10 / 30;
/** a of the cup y = a x^2, per px. */
export const CURVATURE = 0.01;
export const ATOM_RADIUS = 12;
export const N_ATOMS = 49;
/** The slider's start, px above the lowest centre position. */
export const TRAP_HEIGHT = 400;
/** p in Tc(N) = Tc0 (N / N0)^p: the seed's 3D-box law (seed Eq. 46)... */
export const TC_EXPONENT_SEED = 2 / 3;
/** ...or the ideal Bose gas with this cup's density of states g(E) ~ E^(3/2) (SPEC 4). */
export const TC_EXPONENT_CUP = 2 / 5;

/** An elastic bounce leaves the wall at least this fast along the normal, px / frame. */
export const WALL_MIN_NORMAL_SPEED = 1e-3;

export type EscapeRule = "rim" | "knife";
export const ESCAPE_RULES: readonly EscapeRule[] = ["rim", "knife"];

/** Atom lifecycle (SPEC 2.3): trapped -> escaped -> gone. */
export const TRAPPED = 0;
export const ESCAPED = 1;
export const GONE = 2;
export const STATUS_NAMES = ["trapped", "escaped", "gone"] as const;
export type StatusName = (typeof STATUS_NAMES)[number];

/** Event kinds of the event log by their codes (core/model.h), as Python's world.EVENT_NAMES. */
export const EVENT_NAMES = ["pair", "wall", "escape", "gone", "knife"] as const;
export type EventName = (typeof EVENT_NAMES)[number];
