/**
 * Scalar event kernels: free flight, contact times and collision rules.
 *
 * Each function performs the floating-point operations of its namesake in
 * src/evapcool/physics/kernels.py in the same order (JavaScript never fuses a
 * multiply and an add, and Math.sqrt is correctly rounded), so both editions
 * compute the same bits. Trap coordinates: x right, y up, the centre-wall y = a x^2.
 * Kernels with many inputs take an in/out buffer with named fields (ATOM_IN_X, ... below).
 */

// Kernels with many inputs read them from, and write their results to, a scratch
// Float64Array `io` at these places: V8 boxes every double passed to (or returned from) a
// call it does not inline, and the event loop is too big for it to inline them all.
// An atom's stored state and the cup: the wall, exit and bounce kernels.
export const ATOM_IN_X = 0;
export const ATOM_IN_Y = 1;
export const ATOM_IN_VX = 2;
export const ATOM_IN_VY = 3;
export const ATOM_IN_T0 = 4;
export const ATOM_IN_CURVATURE = 5;
export const ATOM_IN_GRAVITY = 6;
// The bounce rules: keep = 1 - damping; vMin, the least normal speed (or the floor).
export const WALL_IN_KEEP = 7;
export const WALL_IN_V_MIN = 8;
// The window edges pushed out by the radius (exitTime).
export const EXIT_IN_X_LEFT = 9;
export const EXIT_IN_X_RIGHT = 10;
export const EXIT_IN_Y_BOTTOM = 11;
// collidePair's inputs: r2 - r1 at contact, both velocities and masses.
export const PAIR_IN_RX = 0;
export const PAIR_IN_RY = 1;
export const PAIR_IN_VX1 = 2;
export const PAIR_IN_VY1 = 3;
export const PAIR_IN_VX2 = 4;
export const PAIR_IN_VY2 = 5;
export const PAIR_IN_M1 = 6;
export const PAIR_IN_M2 = 7;
// Results: a time, or new velocities (vx', vy', or both atoms' after a collision).
export const OUT_TIME = 12;
export const OUT_VX = 12;
export const OUT_VY = 13;
export const OUT_VX1 = 12;
export const OUT_VY1 = 13;
export const OUT_VX2 = 14;
export const OUT_VY2 = 15;
export const IO_SIZE = 16;

/** Horizontal free flight, seed Eq. (3). */
export function flightX(x: number, vx: number, dt: number): number {
  return x + vx * dt;
}

/** Vertical free flight under gravity -g (y up), seed Eq. (3). */
export function flightY(y: number, vy: number, halfG: number, dt: number): number {
  return y + vy * dt - halfG * dt * dt;
}

/** Vertical velocity after free flight, seed Eq. (4). */
export function flightVy(vy: number, g: number, dt: number): number {
  return vy - g * dt;
}

/** 1/2 m v^2 + m g y, the summand of seed Eq. (1). */
export function atomEnergy(m: number, y: number, vx: number, vy: number, g: number): number {
  return 0.5 * m * (vx * vx + vy * vy) + m * g * y;
}

/**
 * Absolute time when two centres reach distance sigma = R1 + R2 (seed Eqs. 15-19).
 * Both states are carried to the later of their times; only approaching pairs
 * collide; an overlapping approaching pair collides at that time.
 */
export function pairContactTime(
  x1: number,
  y1: number,
  vx1: number,
  vy1: number,
  t1: number,
  x2: number,
  y2: number,
  vx2: number,
  vy2: number,
  t2: number,
  sigma: number,
  g: number,
): number {
  const halfG = 0.5 * g;
  const tr = t1 >= t2 ? t1 : t2;
  const d1 = tr - t1;
  const d2 = tr - t2;
  const rx = x1 + vx1 * d1 - (x2 + vx2 * d2);
  const ry = y1 + vy1 * d1 - halfG * d1 * d1 - (y2 + vy2 * d2 - halfG * d2 * d2);
  const vx = vx1 - vx2;
  const vy = vy1 - g * d1 - (vy2 - g * d2);
  const b = rx * vx + ry * vy;
  if (b >= 0.0) return Infinity;
  const c = rx * rx + ry * ry - sigma * sigma;
  if (c <= 0.0) return tr;
  const vv = vx * vx + vy * vy;
  const disc = b * b - vv * c;
  if (disc <= 0.0) return Infinity;
  return tr + c / (Math.sqrt(disc) - b);
}

/**
 * Absolute time when a trapped centre meets the wall y = a x^2 (SPEC 2.1): the one
 * non-negative root of A s^2 + B s + C, cancellation-free; C < 0 is round-off, read as 0.
 * in: ATOM_IN_*; out: OUT_TIME.
 */
export function wallContactTime(io: Float64Array): void {
  const x = io[ATOM_IN_X];
  const vx = io[ATOM_IN_VX];
  const a = io[ATOM_IN_CURVATURE];
  const A = -(0.5 * io[ATOM_IN_GRAVITY] + a * vx * vx);
  const B = io[ATOM_IN_VY] - 2.0 * a * x * vx;
  let C = io[ATOM_IN_Y] - a * x * x;
  if (C < 0.0) C = 0.0;
  const s = Math.sqrt(B * B - 4.0 * A * C);
  const t0 = io[ATOM_IN_T0];
  io[OUT_TIME] = B >= 0.0 ? t0 + (-0.5 * (B + s)) / A : t0 + C / (0.5 * (s - B));
}

/**
 * Absolute time when a falling centre crosses the window bounds (which include its radius).
 * in: ATOM_IN_* but _CURVATURE, EXIT_IN_*; out: OUT_TIME.
 */
export function exitTime(io: Float64Array): void {
  const x = io[ATOM_IN_X];
  const y = io[ATOM_IN_Y];
  const vx = io[ATOM_IN_VX];
  const vy = io[ATOM_IN_VY];
  const t0 = io[ATOM_IN_T0];
  const g = io[ATOM_IN_GRAVITY];
  const xLeft = io[EXIT_IN_X_LEFT];
  const xRight = io[EXIT_IN_X_RIGHT];
  const yBottom = io[EXIT_IN_Y_BOTTOM];
  if (x <= xLeft || x >= xRight || y <= yBottom) {
    io[OUT_TIME] = t0;
    return;
  }
  let dt = Infinity;
  if (vx < 0.0) dt = (xLeft - x) / vx;
  else if (vx > 0.0) dt = (xRight - x) / vx;
  const h = y - yBottom;
  const s = Math.sqrt(vy * vy + 2.0 * g * h);
  const dy = vy > 0.0 ? (vy + s) / g : (2.0 * h) / (s - vy);
  if (dy < dt) dt = dy;
  io[OUT_TIME] = t0 + dt;
}

/**
 * Elastic hard-disk collision along the line of centres, seed Eqs. (10)-(12).
 * in: PAIR_IN_*; out: OUT_VX1, OUT_VY1, OUT_VX2, OUT_VY2.
 */
export function collidePair(io: Float64Array): void {
  const rx = io[PAIR_IN_RX];
  const ry = io[PAIR_IN_RY];
  const vx1 = io[PAIR_IN_VX1];
  const vy1 = io[PAIR_IN_VY1];
  const vx2 = io[PAIR_IN_VX2];
  const vy2 = io[PAIR_IN_VY2];
  const m1 = io[PAIR_IN_M1];
  const m2 = io[PAIR_IN_M2];
  const d = Math.sqrt(rx * rx + ry * ry);
  const nx = rx / d;
  const ny = ry / d;
  const dv = nx * (vx1 - vx2) + ny * (vy1 - vy2);
  const k1 = ((2.0 * m2) / (m1 + m2)) * dv;
  const k2 = ((2.0 * m1) / (m1 + m2)) * dv;
  io[OUT_VX1] = vx1 - k1 * nx;
  io[OUT_VY1] = vy1 - k1 * ny;
  io[OUT_VX2] = vx2 + k2 * nx;
  io[OUT_VY2] = vy2 + k2 * ny;
}

/**
 * Reflect v about the tangent of y = a x^2 at x, scaled by keep = 1 - damping.
 * in: ATOM_IN_X, _VX, _VY, _CURVATURE, WALL_IN_KEEP; out: OUT_VX, OUT_VY.
 */
export function reflectWall(io: Float64Array): void {
  const x = io[ATOM_IN_X];
  const vx = io[ATOM_IN_VX];
  const vy = io[ATOM_IN_VY];
  const a = io[ATOM_IN_CURVATURE];
  const keep = io[WALL_IN_KEEP];
  const sx = -2.0 * a * x;
  const nn = sx * sx + 1.0;
  const vn = vx * sx + vy;
  const f = (2.0 * vn) / nn;
  io[OUT_VX] = keep * (vx - f * sx);
  io[OUT_VY] = keep * (vy - f);
}

/**
 * Elastic bounce that leaves the wall at least v_min along the normal (docs/model.md,
 * "Grazing and resting atoms"): a slower bounce is turned, energy kept; an atom slower
 * than v_min leaves at exactly v_min along the normal.
 * in: ATOM_IN_X, _VX, _VY, _CURVATURE, WALL_IN_V_MIN; out: OUT_VX, OUT_VY.
 */
export function bounceWall(io: Float64Array): void {
  io[WALL_IN_KEEP] = 1.0;
  reflectWall(io);
  const x = io[ATOM_IN_X];
  const a = io[ATOM_IN_CURVATURE];
  const vMin = io[WALL_IN_V_MIN];
  const ux = io[OUT_VX];
  const uy = io[OUT_VY];
  const sx = -2.0 * a * x;
  const nn = Math.sqrt(sx * sx + 1.0);
  const nx = sx / nn; // inward unit normal (nx, ny); unit tangent (ny, -nx)
  const ny = 1.0 / nn;
  const un = ux * nx + uy * ny;
  if (un >= vMin) return;
  const ut = ux * ny - uy * nx;
  const rest = ux * ux + uy * uy - vMin * vMin;
  let wt = 0.0;
  if (rest > 0.0) {
    wt = Math.sqrt(rest);
    if (ut < 0.0) wt = -wt;
  }
  io[OUT_VX] = vMin * nx + wt * ny;
  io[OUT_VY] = vMin * ny - wt * nx;
}

/**
 * Damped bounce after the win (seed Eq. 34) with a floor v_floor on the inward normal
 * speed, so a damped atom cannot collapse onto the wall.
 * in: ATOM_IN_X, _VX, _VY, _CURVATURE, WALL_IN_KEEP, WALL_IN_V_MIN = v_floor; out: OUT_VX, OUT_VY.
 */
export function settleWall(io: Float64Array): void {
  reflectWall(io);
  const x = io[ATOM_IN_X];
  const a = io[ATOM_IN_CURVATURE];
  const vFloor = io[WALL_IN_V_MIN];
  let ux = io[OUT_VX];
  let uy = io[OUT_VY];
  const sx = -2.0 * a * x;
  const nn = Math.sqrt(sx * sx + 1.0);
  const vn = (ux * sx + uy) / nn;
  if (vn < vFloor) {
    const d = (vFloor - vn) / nn;
    ux = ux + d * sx;
    uy = uy + d;
  }
  io[OUT_VX] = ux;
  io[OUT_VY] = uy;
}
