/**
 * What the game and the view read from the physics: the camelCase shape of Python's
 * `Simulation` (SPEC section 3). `engine.ts` opens the physics to the game, so nothing else
 * imports the physics directly.
 */
import type { AtomSnapshot, Simulation } from "./engine";

/**
 * Per-atom columns in trap coordinates (x right, y up, px; velocities px / frame), `count`
 * of them valid (arrays may be longer and reused): the physics' AtomSnapshot without its
 * index and energy columns, one type for both (issue 26.3).
 */
export type AtomArrays = Pick<AtomSnapshot, "count" | "x" | "y" | "vx" | "vy" | "radius" | "mass">;

/**
 * What the game and the view read of a simulation: the physics' Simulation's own members
 * (SPEC section 3, in camelCase), so a mirror of one in the page (runtime/remote.ts) has its shape.
 */
export interface SimLike extends Pick<
  Simulation,
  | "time"
  | "nAtoms"
  | "nTrapped"
  | "nEscaped"
  | "trapHeight"
  | "rimHalfWidth"
  | "curvature"
  | "gravity"
  | "temperature"
  | "initialTemperature"
  | "criticalTemperature"
  | "tcExponent"
  | "won"
  | "winRule"
  | "collisionCount"
  | "room"
  | "originLift"
  | "advance"
> {
  /** The trapped atoms now (a snapshot reused by the next call). */
  trapped(): AtomArrays;
  /** The escaped atoms still falling inside the window (reused likewise). */
  escaped(): AtomArrays;
}

/**
 * A simulation the game plays: its clock with the moves, the win and score, the replay, its
 * path and the reach rule are the core's (core/play.c, game.c, the same C in both editions):
 * every edition ends and scores a game alike.
 */
export interface GameSim
  extends
    SimLike,
    Pick<
      Simulation,
      | "playTo"
      | "askHeight"
      | "askedHeight"
      | "hold"
      | "moves"
      | "winFrame"
      | "score"
      | "replay"
      | "path"
      | "outOfReach"
    > {}

export function emptyAtoms(): AtomArrays {
  const z = () => new Float64Array(0);
  return { x: z(), y: z(), vx: z(), vy: z(), radius: z(), mass: z(), count: 0 };
}
