/**
 * Scalar event kernels: free flight, contact times and collision rules.
 *
 * Each function performs the floating-point operations of its namesake in
 * src/evapcool/physics/kernels.py in the same order (JavaScript never fuses a
 * multiply and an add, and Math.sqrt is correctly rounded), so both editions
 * compute the same bits. Trap coordinates: x right, y up, the centre-wall y = a x^2.
 * Functions with two or four results write them into `out` (no allocation).
 */

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
 * Absolute time when a trapped centre meets the wall y = a x^2 (SPEC 2.1): the
 * one non-negative root of A s^2 + B s + C, cancellation-free; C < 0 is round-off, read as 0.
 */
export function wallContactTime(
  x: number,
  y: number,
  vx: number,
  vy: number,
  t0: number,
  a: number,
  g: number,
): number {
  const A = -(0.5 * g + a * vx * vx);
  const B = vy - 2.0 * a * x * vx;
  let C = y - a * x * x;
  if (C < 0.0) C = 0.0;
  const s = Math.sqrt(B * B - 4.0 * A * C);
  if (B >= 0.0) return t0 + (-0.5 * (B + s)) / A;
  return t0 + C / (0.5 * (s - B));
}

/** Absolute time when a falling centre crosses the window bounds (which include its radius). */
export function exitTime(
  x: number,
  y: number,
  vx: number,
  vy: number,
  t0: number,
  g: number,
  xLeft: number,
  xRight: number,
  yBottom: number,
): number {
  if (x <= xLeft || x >= xRight || y <= yBottom) return t0;
  let dt = Infinity;
  if (vx < 0.0) dt = (xLeft - x) / vx;
  else if (vx > 0.0) dt = (xRight - x) / vx;
  const h = y - yBottom;
  const s = Math.sqrt(vy * vy + 2.0 * g * h);
  const dy = vy > 0.0 ? (vy + s) / g : (2.0 * h) / (s - vy);
  if (dy < dt) dt = dy;
  return t0 + dt;
}

/**
 * Elastic hard-disk collision along the line of centres, seed Eqs. (10)-(12).
 * (rx, ry) = r2 - r1 at contact; out = [vx1', vy1', vx2', vy2'].
 */
export function collidePair(
  rx: number,
  ry: number,
  vx1: number,
  vy1: number,
  vx2: number,
  vy2: number,
  m1: number,
  m2: number,
  out: Float64Array,
): void {
  const d = Math.sqrt(rx * rx + ry * ry);
  const nx = rx / d;
  const ny = ry / d;
  const dv = nx * (vx1 - vx2) + ny * (vy1 - vy2);
  const k1 = ((2.0 * m2) / (m1 + m2)) * dv;
  const k2 = ((2.0 * m1) / (m1 + m2)) * dv;
  out[0] = vx1 - k1 * nx;
  out[1] = vy1 - k1 * ny;
  out[2] = vx2 + k2 * nx;
  out[3] = vy2 + k2 * ny;
}

/** Reflect v about the tangent of y = a x^2 at x, scaled by keep = 1 - damping; out = [vx', vy']. */
export function reflectWall(
  x: number,
  vx: number,
  vy: number,
  a: number,
  keep: number,
  out: Float64Array,
): void {
  const sx = -2.0 * a * x;
  const nn = sx * sx + 1.0;
  const vn = vx * sx + vy;
  const f = (2.0 * vn) / nn;
  out[0] = keep * (vx - f * sx);
  out[1] = keep * (vy - f);
}

/**
 * Elastic bounce that leaves the wall at least vMin along the normal (doc/model.md,
 * "Grazing and resting atoms"): a slower bounce is turned, energy kept; an atom slower
 * than vMin leaves at exactly vMin along the normal. out = [vx', vy'].
 */
export function bounceWall(
  x: number,
  vx: number,
  vy: number,
  a: number,
  vMin: number,
  out: Float64Array,
): void {
  reflectWall(x, vx, vy, a, 1.0, out);
  const ux = out[0];
  const uy = out[1];
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
  out[0] = vMin * nx + wt * ny;
  out[1] = vMin * ny - wt * nx;
}

/**
 * Damped bounce after the win (seed Eq. 34) with a floor vFloor on the inward
 * normal speed, so a damped atom cannot collapse onto the wall. out = [vx', vy'].
 */
export function settleWall(
  x: number,
  vx: number,
  vy: number,
  a: number,
  keep: number,
  vFloor: number,
  out: Float64Array,
): void {
  reflectWall(x, vx, vy, a, keep, out);
  let ux = out[0];
  let uy = out[1];
  const sx = -2.0 * a * x;
  const nn = Math.sqrt(sx * sx + 1.0);
  const vn = (ux * sx + uy) / nn;
  if (vn < vFloor) {
    const d = (vFloor - vn) / nn;
    ux = ux + d * sx;
    uy = uy + d;
  }
  out[0] = ux;
  out[1] = uy;
}
