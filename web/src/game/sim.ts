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

export function emptyAtoms(): AtomArrays {
  const z = () => new Float64Array(0);
  return { x: z(), y: z(), vx: z(), vy: z(), radius: z(), mass: z(), count: 0 };
}
