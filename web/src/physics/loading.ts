/**
 * The game's start (SPEC section 1, docs/model.md "Initial loading"): rows of cells filled
 * from the bottom, centre-out within a row, one atom at a random point of each cell.
 * The same cells as src/evapcool/physics/loading.py; random numbers from Xoshiro128.
 */
import { ParameterError, pyG } from "../limits";
import { Xoshiro128 } from "./rng";

/** Speed at the bottom row and its step per 40 px of height, px / frame. */
export const V0 = 100 / 30;
export const DV = 10 / 30;
/** The original's row spacing (R = 12), px: the speed profile is the original's for any R. */
const ROW_SPACING_ORIGINAL = 40;
/** Vertices of the circumscribed polygon that certifies a jitter disk inside the cup. */
const POLYGON = 64;

function diskInsideCup(xc: number, yc: number, rad: number, a: number): boolean {
  const rho = rad / Math.cos(Math.PI / POLYGON);
  for (let k = 0; k < POLYGON; k++) {
    const ang = (2 * Math.PI * k) / POLYGON;
    const px = xc + rho * Math.cos(ang);
    const py = yc + rho * Math.sin(ang);
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

/** Positions and velocities ([x0, y0, ...], [vx0, vy0, ...]) of n atoms of equal radius. */
export function loadCup(
  n: number,
  radius: number,
  curvature: number,
  yTop: number,
  rng: Xoshiro128,
): { positions: Float64Array; velocities: Float64Array } {
  const centres = cellCentres(n, radius, curvature, yTop);
  const jitter = (radius * 8) / 12;
  const positions = new Float64Array(2 * n);
  const velocities = new Float64Array(2 * n);
  for (let i = 0; i < n; i++) {
    const u0 = rng.random();
    const u1 = rng.random();
    const u2 = rng.random();
    const u3 = rng.random();
    const r = jitter * Math.sqrt(u0);
    const phi = 2 * Math.PI * u1;
    positions[2 * i] = centres[2 * i] + r * Math.cos(phi);
    positions[2 * i + 1] = centres[2 * i + 1] + r * Math.sin(phi);
    const level = (centres[2 * i + 1] - centres[1]) / ROW_SPACING_ORIGINAL;
    const speed = V0 + (level + u2) * DV;
    const theta = 2 * Math.PI * u3;
    velocities[2 * i] = speed * Math.cos(theta);
    velocities[2 * i + 1] = speed * Math.sin(theta);
  }
  return { positions, velocities };
}
