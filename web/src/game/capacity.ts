/**
 * How many atoms of a radius the initial loading fits (SPEC 1 rows of cells) with every
 * disk below the starting rim, computed like the desktop's `loading.capacity` (whole rows
 * of cells, the loader's own 64-gon test), so the settings screen offers the same "1 to N".
 */
import { CURVATURE } from "./constants";
import { CLASSIC_ROOM, diskInsideCup, roomTop } from "./engine";

/** The rim at the start, px: no atom of the start may sit above it (or under the border). */
const START_HEIGHT = 400;
/** Atoms this far below the room's top are in view: under the play area's top border, px. */
const SHOWN_BELOW_TOP = 48;

const cache = new Map<number, number>();

/** Atoms of this radius that start wholly inside the cup, below its rim, in view. */
export function cupCapacity(radius: number, curvature = CURVATURE): number {
  const key = radius * 1e6 + curvature;
  const hit = cache.get(key);
  if (hit !== undefined) return hit;
  // The border's edge in trap coordinates, or the rim if that is lower.
  const yTop = Math.min(START_HEIGHT, roomTop(CLASSIC_ROOM, radius) - SHOWN_BELOW_TOP);
  const jitter = (radius * 8) / 12;
  const cell = radius + jitter;
  const spacing = 2 * cell;
  const y0 = jitter * 1.05;
  let count = 0;
  for (let k = 0; ; k++) {
    const yc = y0 + k * spacing;
    if (yc + cell > yTop) break;
    const m = Math.trunc(Math.sqrt(yc / curvature) / spacing) + 1;
    for (let j = -m; j <= m; j++) {
      if (diskInsideCup(j * spacing, yc, jitter, curvature)) count++;
    }
  }
  cache.set(key, count);
  return count;
}
