/**
 * How many atoms of a radius the initial loading fits (SPEC 1 rows of cells) with every
 * disk below the starting rim: the core's count (core/start.c), the desktop's
 * `loading.capacity`, so the settings screen offers the same "1 to N".
 */
import { CLASSIC_ROOM, CURVATURE, roomTop, startCapacity } from "./engine";
import { HEIGHT_START } from "./rules";

/** Atoms this far below the room's top are in view: under the play area's top border, px. */
const SHOWN_BELOW_TOP = 48;

const cache = new Map<number, number>();

/** Atoms of this radius that start wholly inside the cup, below its rim, in view. */
export function cupCapacity(radius: number, curvature = CURVATURE): number {
  const key = radius * 1e6 + curvature;
  const hit = cache.get(key);
  if (hit !== undefined) return hit;
  // The border's edge in trap coordinates, or the rim at the start if that is lower.
  const yTop = Math.min(HEIGHT_START, roomTop(CLASSIC_ROOM, radius) - SHOWN_BELOW_TOP);
  const count = startCapacity(radius, curvature, yTop);
  cache.set(key, count);
  return count;
}
