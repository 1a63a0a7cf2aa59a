/**
 * The game's start (SPEC section 1, docs/model.md "Initial loading"): rows of cells filled
 * from the bottom, centre-out within a row, one atom at a random point of each cell.
 * The same cells and numbers as src/evapcool/physics/loading.py: the shared start generator.
 */
import { ParameterError, pyG } from "../limits";
import { diskPoints, Stream, STREAM_DIRECTION, STREAM_JITTER, STREAM_SPEED } from "./start";

/** Speed at the bottom row and its step per 40 px of height, px / frame. */
export const V0 = 100 / 30;
export const DV = 10 / 30;
/** The original's row spacing (R = 12), px: the speed profile is the original's for any R. */
const ROW_SPACING_ORIGINAL = 40;
/**
 * cos(2 pi k / 64) for k = 0..16 as exact literals (no Math.cos at run time, so every engine
 * builds the same polygon); the other vertices follow by symmetry. As in loading.py.
 */
const QUARTER_COS = [
  1.0, 0.9951847266721969, 0.9807852804032304, 0.9569403357322088, 0.9238795325112867,
  0.881921264348355, 0.8314696123025452, 0.773010453362737, 0.7071067811865476, 0.6343932841636455,
  0.5555702330196023, 0.4713967368259978, 0.38268343236508984, 0.29028467725446233,
  0.19509032201612833, 0.09801714032956077, 0.0,
];
/** A little above 1 / cos(pi / 64): corners this many jitter radii out circumscribe the disk. */
const SECANT = 1.00121;

/** The 64 unit vertices (cos, sin) counter-clockwise from (1, 0). */
function polygon(): [Float64Array, Float64Array] {
  const cos = new Float64Array(64);
  const sin = new Float64Array(64);
  for (let j = 0; j < 16; j++) {
    const c = QUARTER_COS[j];
    const s = QUARTER_COS[16 - j];
    [cos[j], sin[j]] = [c, s];
    [cos[16 + j], sin[16 + j]] = [-s, c];
    [cos[32 + j], sin[32 + j]] = [-c, -s];
    [cos[48 + j], sin[48 + j]] = [s, -c];
  }
  return [cos, sin];
}

const [POLY_COS, POLY_SIN] = polygon();

/** Whether the disk of radius rad around (xc, yc) lies inside y >= a x^2 (its circumscribed 64-gon does). */
export function diskInsideCup(xc: number, yc: number, rad: number, a: number): boolean {
  const rho = rad * SECANT;
  for (let k = 0; k < 64; k++) {
    const px = xc + rho * POLY_COS[k];
    const py = yc + rho * POLY_SIN[k];
    if (!(py > a * px * px)) return false;
  }
  return true;
}

/**
 * Centres of the first n cells, row by row from the bottom, as [x0, y0, x1, y1, ...].
 * Throws RangeError if n cells of jitter disks do not fit below yTop.
 */
export function cellCentres(
  n: number,
  radius: number,
  curvature: number,
  yTop: number,
): Float64Array {
  const jitter = (radius * 8) / 12;
  const cell = radius + jitter;
  const spacing = 2 * cell;
  const y0 = jitter * 1.05; // row 0 lifted a hair so its jitter disk is certified inside
  const out = new Float64Array(2 * n);
  let count = 0;
  for (let k = 0; count < n; k++) {
    const yc = y0 + k * spacing;
    if (yc + cell > yTop) {
      throw new ParameterError(
        "nAtoms",
        `${n} atoms of radius ${pyG(radius)} do not fit in the cup below the window top ` +
          `(at most ${count} fit)`,
        ": ",
      );
    }
    const m = Math.floor(Math.sqrt(yc / curvature) / spacing) + 1;
    // Centre-out: 0, 1, -1, 2, -2, ...
    for (let q = 0; q <= 2 * m && count < n; q++) {
      const j = q === 0 ? 0 : q % 2 === 1 ? (q + 1) / 2 : -q / 2;
      const xc = j * spacing;
      if (diskInsideCup(xc, yc, jitter, curvature)) {
        out[2 * count] = xc;
        out[2 * count + 1] = yc;
        count++;
      }
    }
  }
  return out;
}

/**
 * Positions and velocities ([x0, y0, ...], [vx0, vy0, ...]) of n atoms of equal radius: each at
 * a uniform point of its cell's jitter disk, moving in a uniform direction (a point of the
 * ring 1/16 <= r^2 < 1 normalised by sqrt), as loading.py's load_cup.
 */
export function loadCup(
  n: number,
  radius: number,
  curvature: number,
  yTop: number,
  seed: number,
): { positions: Float64Array; velocities: Float64Array } {
  const centres = cellCentres(n, radius, curvature, yTop);
  const jitter = (radius * 8) / 12;
  const offset = diskPoints(seed, STREAM_JITTER, n);
  const ring = diskPoints(seed, STREAM_DIRECTION, n, 1 / 16);
  const speeds = new Stream(seed, STREAM_SPEED);
  const positions = new Float64Array(2 * n);
  const velocities = new Float64Array(2 * n);
  for (let i = 0; i < n; i++) {
    positions[2 * i] = centres[2 * i] + jitter * offset[2 * i];
    positions[2 * i + 1] = centres[2 * i + 1] + jitter * offset[2 * i + 1];
    const level = (centres[2 * i + 1] - centres[1]) / ROW_SPACING_ORIGINAL;
    const speed = V0 + (level + speeds.uniform(i)) * DV;
    const rx = ring[2 * i];
    const ry = ring[2 * i + 1];
    const norm = Math.sqrt(rx * rx + ry * ry);
    velocities[2 * i] = (speed * rx) / norm;
    velocities[2 * i + 1] = (speed * ry) / norm;
  }
  return { positions, velocities };
}
