/**
 * Where the view puts the cup in the window (issue 26.3), twin of src/evapcool/view/screen.py:
 * trap coordinates (y up) to window pixels (y down). The original's layout (SPEC 1): a 640 x 672
 * window, a play area inside borders of 48 px (left, top) and 96 px (right, bottom), the cup's
 * lowest point drawn 32 px above the play area's bottom and in its middle. The physics knows
 * only the room this gives (physics/room.ts).
 */
import type { Room } from "../game/engine";

/** The original window (SPEC 1), px. */
export const WINDOW: readonly [number, number] = [640, 672];
export const BORDER_LEFT = 48;
export const BORDER_RIGHT = 96;
export const BORDER_TOP = 48;
export const BORDER_BOTTOM = 96;
/** px between the drawn cup bottom and the play area's bottom. */
export const CUP_DROP = 32;

/** Screen position of the drawn cup's lowest point: (296, 544) in 640 x 672. */
export function cupVertex(window: readonly [number, number] = WINDOW): [number, number] {
  const playW = window[0] - BORDER_LEFT - BORDER_RIGHT;
  return [BORDER_LEFT + playW / 2, window[1] - BORDER_BOTTOM - CUP_DROP];
}

/** The room a window of this size gives the physics: its edges around the cup. */
export function windowRoom(window: readonly [number, number] = WINDOW): Room {
  const [vx, vy] = cupVertex(window);
  return { left: vx, right: window[0] - vx, below: window[1] - vy, above: vy };
}

/** What the screen map reads of a simulation: its room and the trap origin's lift. */
export interface Placed {
  readonly room: Room;
  /** The trap origin's height above the cup wall's lowest point (the first atom's radius). */
  readonly originLift: number;
}

/**
 * Screen position (px, y down) of the trap origin: the room shown as a window of its size, the
 * cup's lowest point at (room.left, room.above); (296, 544 - R) in the original window.
 */
export function screenOrigin(sim: Placed): [number, number] {
  return [sim.room.left, sim.room.above - sim.originLift];
}

/** Trap coordinates [x0, y0, ...] to window pixels, into out if given. */
export function toScreen(sim: Placed, xy: ArrayLike<number>, out?: Float64Array): Float64Array {
  const [ox, oy] = screenOrigin(sim);
  const res = out ?? new Float64Array(xy.length);
  for (let k = 0; k + 1 < xy.length; k += 2) {
    res[k] = ox + xy[k];
    res[k + 1] = oy - xy[k + 1];
  }
  return res;
}
