/**
 * Scalar event kernels: free flight, contact times and collision rules.
 *
 * Each function performs the floating-point operations of its namesake in
 * src/evapcool/physics/kernels.py in the same order (JavaScript never fuses a
 * multiply and an add, and Math.sqrt is correctly rounded), so both editions
 * compute the same bits. Trap coordinates: x right, y up, the centre-wall y = a x^2.
 * Kernels with many inputs take an in/out buffer (see IO_X below).
 */

// Kernels with many inputs read them from, and write their results to, a scratch
// Float64Array `io` at these places: V8 boxes every double passed to (or returned from) a
// call it does not inline, and the event loop is too big for it to inline them all.
/** An atom's stored state and the cup: the wall and exit kernels. */
export const IO_X = 0;
export const IO_Y = 1;
export const IO_VX = 2;
export const IO_VY = 3;
export const IO_T0 = 4;
export const IO_A = 5;
export const IO_G = 6;
/** 1 - damping (reflectWall, settleWall); v_min (bounceWall) or v_floor (settleWall). */
export const IO_KEEP = 7;
export const IO_VMIN = 8;
/** The window edges pushed out by the radius (exitTime). */
export const IO_XL = 9;
export const IO_XR = 10;
export const IO_YB = 11;
/** collidePair's inputs: r2 - r1 at contact, both velocities and masses. */
export const IO_RX = 0;
export const IO_RY = 1;
export const IO_VX1 = 2;
export const IO_VY1 = 3;
export const IO_VX2 = 4;
export const IO_VY2 = 5;
export const IO_M1 = 6;
export const IO_M2 = 7;
/** Results: a time, or new velocities (vx', vy' or vx1', vy1', vx2', vy2'). */
export const IO_OUT = 12;
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
 * in: io[IO_X], io[IO_Y], io[IO_VX], io[IO_VY], io[IO_T0], io[IO_A], io[IO_G];
 * out: io[IO_OUT].
 */
export function wallContactTime(io: Float64Array): void {
  const x = io[IO_X];
  const vx = io[IO_VX];
  const a = io[IO_A];
  const A = -(0.5 * io[IO_G] + a * vx * vx);
  const B = io[IO_VY] - 2.0 * a * x * vx;
  let C = io[IO_Y] - a * x * x;
  if (C < 0.0) C = 0.0;
  const s = Math.sqrt(B * B - 4.0 * A * C);
  const t0 = io[IO_T0];
  io[IO_OUT] = B >= 0.0 ? t0 + (-0.5 * (B + s)) / A : t0 + C / (0.5 * (s - B));
}

/**
 * Absolute time when a falling centre crosses the window bounds (which include its radius).
 * in: io[IO_X], io[IO_Y], io[IO_VX], io[IO_VY], io[IO_T0], io[IO_G], io[IO_XL], io[IO_XR],
 * io[IO_YB]; out: io[IO_OUT].
 */
export function exitTime(io: Float64Array): void {
  const x = io[IO_X];
  const y = io[IO_Y];
  const vx = io[IO_VX];
  const vy = io[IO_VY];
  const t0 = io[IO_T0];
  const g = io[IO_G];
  const xLeft = io[IO_XL];
  const xRight = io[IO_XR];
  const yBottom = io[IO_YB];
  if (x <= xLeft || x >= xRight || y <= yBottom) {
    io[IO_OUT] = t0;
    return;
  }
  let dt = Infinity;
  if (vx < 0.0) dt = (xLeft - x) / vx;
  else if (vx > 0.0) dt = (xRight - x) / vx;
  const h = y - yBottom;
  const s = Math.sqrt(vy * vy + 2.0 * g * h);
  const dy = vy > 0.0 ? (vy + s) / g : (2.0 * h) / (s - vy);
  if (dy < dt) dt = dy;
  io[IO_OUT] = t0 + dt;
}

/**
 * Elastic hard-disk collision along the line of centres, seed Eqs. (10)-(12).
 * in: io[IO_RX..IO_M2]; out: io[IO_OUT..IO_OUT + 3] = vx1', vy1', vx2', vy2'.
 */
export function collidePair(io: Float64Array): void {
  const rx = io[IO_RX];
  const ry = io[IO_RY];
  const vx1 = io[IO_VX1];
  const vy1 = io[IO_VY1];
  const vx2 = io[IO_VX2];
  const vy2 = io[IO_VY2];
  const m1 = io[IO_M1];
  const m2 = io[IO_M2];
  const d = Math.sqrt(rx * rx + ry * ry);
  const nx = rx / d;
  const ny = ry / d;
  const dv = nx * (vx1 - vx2) + ny * (vy1 - vy2);
  const k1 = ((2.0 * m2) / (m1 + m2)) * dv;
  const k2 = ((2.0 * m1) / (m1 + m2)) * dv;
  io[IO_OUT] = vx1 - k1 * nx;
  io[IO_OUT + 1] = vy1 - k1 * ny;
  io[IO_OUT + 2] = vx2 + k2 * nx;
  io[IO_OUT + 3] = vy2 + k2 * ny;
}

/**
 * Reflect v about the tangent of y = a x^2 at x, scaled by keep = 1 - damping.
 * in: io[IO_X], io[IO_VX], io[IO_VY], io[IO_A], io[IO_KEEP]; out: io[IO_OUT], io[IO_OUT + 1].
 */
export function reflectWall(io: Float64Array): void {
  const x = io[IO_X];
  const vx = io[IO_VX];
  const vy = io[IO_VY];
  const a = io[IO_A];
  const keep = io[IO_KEEP];
  const sx = -2.0 * a * x;
  const nn = sx * sx + 1.0;
  const vn = vx * sx + vy;
  const f = (2.0 * vn) / nn;
  io[IO_OUT] = keep * (vx - f * sx);
  io[IO_OUT + 1] = keep * (vy - f);
}

/**
 * Elastic bounce that leaves the wall at least v_min along the normal (docs/model.md,
 * "Grazing and resting atoms"): a slower bounce is turned, energy kept; an atom slower
 * than v_min leaves at exactly v_min along the normal.
 * in: io[IO_X], io[IO_VX], io[IO_VY], io[IO_A], io[IO_VMIN]; out: io[IO_OUT], io[IO_OUT + 1].
 */
export function bounceWall(io: Float64Array): void {
  io[IO_KEEP] = 1.0;
  reflectWall(io);
  const x = io[IO_X];
  const a = io[IO_A];
  const vMin = io[IO_VMIN];
  const ux = io[IO_OUT];
  const uy = io[IO_OUT + 1];
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
  io[IO_OUT] = vMin * nx + wt * ny;
  io[IO_OUT + 1] = vMin * ny - wt * nx;
}

/**
 * Damped bounce after the win (seed Eq. 34) with a floor v_floor on the inward normal
 * speed, so a damped atom cannot collapse onto the wall.
 * in: io[IO_X], io[IO_VX], io[IO_VY], io[IO_A], io[IO_KEEP], io[IO_VMIN] = v_floor;
 * out: io[IO_OUT], io[IO_OUT + 1].
 */
export function settleWall(io: Float64Array): void {
  reflectWall(io);
  const x = io[IO_X];
  const a = io[IO_A];
  const vFloor = io[IO_VMIN];
  let ux = io[IO_OUT];
  let uy = io[IO_OUT + 1];
  const sx = -2.0 * a * x;
  const nn = Math.sqrt(sx * sx + 1.0);
  const vn = (ux * sx + uy) / nn;
  if (vn < vFloor) {
    const d = (vFloor - vn) / nn;
    ux = ux + d * sx;
    uy = uy + d;
  }
  io[IO_OUT] = ux;
  io[IO_OUT + 1] = uy;
}
