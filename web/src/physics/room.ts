/**
 * The room around the cup (issue 26.3), twin of src/evapcool/physics/room.py: where escaped
 * atoms are removed, and how high the loader may fill the cup. The model knows the cup and
 * this room, never the window: which window shows them, and where, is the view's business
 * (view/screen.ts).
 */
import { badValue, WINDOW_SIDE } from "../limits";

/**
 * Distances (px) from the cup wall's lowest point to the room's edges. An escaped atom that
 * leaves through the left, right or bottom edge is gone (SPEC 1: the window's edges); a
 * trapped one never is. The loader fills the cup row by row below the room's top.
 */
export interface Room {
  readonly left: number;
  readonly right: number;
  readonly below: number;
  readonly above: number;
}

/** The original applet's room (SPEC 1): the cup's lowest point at (296, 544) in 640 x 672. */
export const CLASSIC_ROOM: Room = Object.freeze({ left: 296, right: 344, below: 128, above: 544 });

/** The room's top in trap coordinates, whose origin lies originLift above the wall's lowest point. */
export function roomTop(room: Room, originLift: number): number {
  return room.above - originLift;
}

/** [xLeft, xRight, yBottom]: the edges where escaped atoms are gone, trap coordinates. */
export function escapeBox(room: Room, originLift: number): [number, number, number] {
  return [-room.left, room.right, roomTop(room, originLift) - (room.above + room.below)];
}

/** room if it has finite sides >= 0 and a width and height within limits' WINDOW_SIDE. */
export function checkRoom(name: string, value: unknown): Room {
  const r = value as Room;
  const sides = r && typeof r === "object" ? [r.left, r.right, r.below, r.above] : [];
  const ok =
    sides.length === 4 &&
    sides.every((s) => typeof s === "number" && Number.isFinite(s) && s >= 0) &&
    WINDOW_SIDE.contains(r.left + r.right) &&
    WINDOW_SIDE.contains(r.below + r.above);
  if (!ok)
    throw badValue(name, `a room of sides >= 0 px, ${WINDOW_SIDE.span()} wide and high`, value);
  return { left: r.left, right: r.right, below: r.below, above: r.above };
}
