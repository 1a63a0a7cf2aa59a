/**
 * What the game and the view read from the physics: the camelCase shape of Python's
 * `Simulation` (SPEC section 3). `engine.ts` adapts the engine in `../physics` to it, so
 * nothing else imports the physics directly.
 */
import type { AtomSnapshot, Room } from "./engine";

/**
 * Per-atom columns in trap coordinates (x right, y up, px; velocities px / frame), `count`
 * of them valid (arrays may be longer and reused): the physics' AtomSnapshot without its
 * index and energy columns, one type for both (issue 26.3).
 */
export type AtomArrays = Pick<AtomSnapshot, "count" | "x" | "y" | "vx" | "vy" | "radius" | "mass">;

export interface SimLike {
  /** Simulation time in frames (1/30 s). */
  readonly time: number;
  readonly nAtoms: number;
  readonly nTrapped: number;
  readonly nEscaped: number;
  /** Rim height H, px above the lowest centre position. */
  trapHeight: number;
  readonly rimHalfWidth: number;
  readonly curvature: number;
  readonly gravity: number;
  readonly temperature: number;
  readonly initialTemperature: number;
  readonly criticalTemperature: number;
  readonly tcExponent: number;
  readonly won: boolean;
  /** False if the game's win rule is off (the gas stays a gas below Tc). */
  readonly winRule: boolean;
  readonly collisionCount: number;
  /** The room around the cup (the view places it: view/screen.ts). */
  readonly room: Room;
  /** The trap origin's height above the cup wall's lowest point (the first atom's radius). */
  readonly originLift: number;
  advance(dt: number): void;
  /** The trapped atoms now (a snapshot reused by the next call). */
  trapped(): AtomArrays;
  /** The escaped atoms still falling inside the window (reused likewise). */
  escaped(): AtomArrays;
}

/**
 * A simulation the game plays: the frame step, its win and score and the replay are the
 * core's (core/game.c, the same C in both editions), so every edition scores a game alike.
 */
export interface GameSim extends SimLike {
  /** One whole frame from a whole frame, the trap at `height` during it (from its start, not
   * after the win), then its end: the win seen, the score fixed. */
  frame(height: number): void;
  /** The end of a whole frame reached by advance: the win seen, the score fixed. */
  frameEnd(): void;
  /** Atoms trapped at the end of the whole frame the win was seen in; null before. */
  readonly score: number | null;
  /** [height, frames] runs from a whole frame, up to the win or `limit` frames: the frames
   * played. */
  replay(runs: ReadonlyArray<readonly [number, number]>, limit: number): number;
}

export function emptyAtoms(): AtomArrays {
  const z = () => new Float64Array(0);
  return { x: z(), y: z(), vx: z(), vy: z(), radius: z(), mass: z(), count: 0 };
}
