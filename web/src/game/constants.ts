/**
 * The original applet's numbers the game uses (SPEC section 1): the physics' own constants,
 * not copies (issue 26.3), through the game's one door to the physics (engine.ts).
 */
export {
  ATOM_RADIUS,
  CURVATURE,
  ESCAPE_RULES,
  FPS,
  GRAVITY,
  N_ATOMS,
  TC_EXPONENT_CUP,
  TC_EXPONENT_SEED,
  type EscapeRule,
} from "./engine";
