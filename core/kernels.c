/*
 * Scalar event kernels: free flight, contact times and collision rules.
 *
 * Each performs the floating-point operations of its namesake in
 * src/evapcool/physics/kernels.py in the same order (pair_contact_time also tells, before
 * solving, the pairs that cannot come first: a time it returns is the same). Compiled with
 * -ffp-contract=off (no fused multiply-add; wasm32 has none anyway) and __builtin_sqrt
 * (correctly rounded), so the reference engine and both builds of the core compute the same
 * bits.
 */
#include "tables.h"

/* Horizontal free flight, seed Eq. (3). */
double flight_x(double x, double vx, double dt) { return x + vx * dt; }

/* Vertical free flight under gravity -g (y up), seed Eq. (3). */
double flight_y(double y, double vy, double half_g, double dt) {
  return y + vy * dt - half_g * dt * dt;
}

/* Vertical velocity after free flight, seed Eq. (4). */
double flight_vy(double vy, double g, double dt) { return vy - g * dt; }

/* 1/2 m v^2 + m g y, the summand of seed Eq. (1). */
double atom_energy_of(double m, double y, double vx, double vy, double g) {
  return 0.5 * m * (vx * vx + vy * vy) + m * g * y;
}

/*
 * Absolute time when two centres reach distance sigma = R1 + R2 (seed Eqs. 15-19), or inf
 * if they never do, or surely not by time `beat` (inf: any time). Both states are carried to
 * the later of their times; only approaching pairs collide; an overlapping approaching pair
 * collides at that time. A time it returns is the reference engine's, bit for bit.
 */
double pair_contact_time(const State *p, const State *q, double sigma, double g, double beat) {
  double half_g = 0.5 * g;
  double t1 = p->t, t2 = q->t;
  double tr = t1 >= t2 ? t1 : t2;
  double d1 = tr - t1;
  double d2 = tr - t2;
  double rx = p->x + p->vx * d1 - (q->x + q->vx * d2);
  double ry = p->y + p->vy * d1 - half_g * d1 * d1 - (q->y + q->vy * d2 - half_g * d2 * d2);
  double vx = p->vx - q->vx;
  double vy = p->vy - g * d1 - (q->vy - g * d2);
  double b = rx * vx + ry * vy;
  double c = rx * rx + ry * ry - sigma * sigma;
  double vv = vx * vx + vy * vy;
  double disc = b * b - vv * c;
  /* The root is tr + c / (sqrt(disc) - b) > tr + c / (-2 b + 1e-161), as sqrt(disc) <=
   * |b| (b * b below 1e-308 keeps few digits: 1e-161 > sqrt(2^-1074) covers them): a pair
   * for which that bound is past `beat` (with room for round-off many times over) cannot
   * be the earlier. An overlapping pair (c <= 0) meets now if it approaches, whatever disc
   * (b * b may underflow): it passes the two tests below. */
  double room = (beat - tr) * (1.0 + 1e-9) + __builtin_fabs(beat) * 1e-12 + 1e-290;
  const int apart = c > 0.0;
  double meets = apart ? disc : 1.0, in_time = apart ? (1e-161 - 2.0 * b) * room - c : 1.0;
  /* One test for the three ways to miss (receding, passing by, too late), as most pairs
   * do: a branch taken either way at random costs more than the arithmetic it skips. */
  double nb = -b, least = nb < meets ? nb : meets;
  least = least < in_time ? least : in_time; /* > 0 iff b < 0, it meets, and in time */
  if (!(least > 0.0)) return INF;
  if (!apart) return tr; /* overlapping and approaching */
  return tr + c / (__builtin_sqrt(disc) - b);
}

#ifdef CORE_LANES
/* The least of a and b lane by lane, as `a < b ? a : b` (minpd is defined so). */
static inline v2d least2(v2d a, v2d b) {
#ifdef __SSE2__
  return __builtin_ia32_minpd(a, b);
#else
  return lane_pick(a < b, a, b);
#endif
}

/*
 * pair_contact_time of row p with q0 and with q1 at once, into t[0] and t[1]: each
 * lane does the scalar function's operations in its order, so each time is the same bits.
 * `slack` is |beat| 1e-12, as the scalar function computes it. (The one `beat` serves both;
 * a later one only lets more pairs through to be solved exactly.) Returns which lanes did
 * not miss (bits 1 and 2); if none, t[] is not written (both inf).
 */
int32_t pair_contact_times(const State *p, const State *q0, const State *q1, double g, double beat,
                           double slack, double t[2]) {
  const v2d one = {1.0, 1.0}, zero = {0.0, 0.0};
  const PairSide me_ = {{p->t, p->t}, {p->x, p->x}, {p->y, p->y}, {p->vx, p->vx}, {p->vy, p->vy},
                        {p->radius, p->radius}, {0.5 * g, 0.5 * g}, {g, g}};
  const PairSide *me = &me_;
  v2d t1 = me->t, t2 = {q0->t, q1->t};
  v2d tr = lane_pick(t1 >= t2, t1, t2);
  v2d d1 = tr - t1, d2 = tr - t2;
  v2d qx = {q0->x, q1->x}, qy = {q0->y, q1->y}, qvx = {q0->vx, q1->vx}, qvy = {q0->vy, q1->vy};
  v2d rx = me->x + me->vx * d1 - (qx + qvx * d2);
  v2d ry = me->y + me->vy * d1 - me->half_g * d1 * d1 - (qy + qvy * d2 - me->half_g * d2 * d2);
  v2d vx = me->vx - qvx;
  v2d vy = me->vy - me->g * d1 - (qvy - me->g * d2);
  v2d sigma = me->r + (v2d){q0->radius, q1->radius};
  v2d b = rx * vx + ry * vy;
  v2d c = rx * rx + ry * ry - sigma * sigma;
  v2d vv = vx * vx + vy * vy;
  v2d disc = b * b - vv * c;
  v2d room = ((v2d){beat, beat} - tr) * (1.0 + 1e-9) + slack + 1e-290;
  v2m apart = c > zero;
  v2d meets = lane_pick(apart, disc, one);
  v2d in_time = lane_pick(apart, (1e-161 - 2.0 * b) * room - c, one);
  v2m pass = least2(least2(-b, meets), in_time) > zero;
  int32_t lanes = (int32_t)(pass[0] & 1) | (int32_t)(pass[1] & 2);
  if (lanes == 0) return 0; /* as most pairs do: t[] not written */
  for (int k = 0; k < 2; k++)
    t[k] = !pass[k] ? INF : apart[k] ? tr[k] + c[k] / (__builtin_sqrt(disc[k]) - b[k]) : tr[k];
  return lanes;
}
#endif

/*
 * Absolute time when a trapped centre meets the wall y = a x^2 (SPEC 2.1): the one
 * non-negative root of A s^2 + B s + C, cancellation-free; C < 0 is round-off, read as 0.
 */
double wall_contact_time(const State *s, double a, double g) {
  double x = s->x, vx = s->vx;
  double A = -(0.5 * g + a * vx * vx);
  double B = s->vy - 2.0 * a * x * vx;
  double C = s->y - a * x * x;
  if (C < 0.0) C = 0.0;
  double sq = __builtin_sqrt(B * B - 4.0 * A * C);
  return B >= 0.0 ? s->t + (-0.5 * (B + sq)) / A : s->t + C / (0.5 * (sq - B));
}

/* Absolute time when a falling centre crosses the window bounds (with its radius). */
double exit_time(const State *s, double x_left, double x_right, double y_bottom, double g) {
  double x = s->x, y = s->y, vx = s->vx, vy = s->vy;
  if (x <= x_left || x >= x_right || y <= y_bottom) return s->t;
  double dt = INF;
  if (vx < 0.0)
    dt = (x_left - x) / vx;
  else if (vx > 0.0)
    dt = (x_right - x) / vx;
  double h = y - y_bottom;
  double sq = __builtin_sqrt(vy * vy + 2.0 * g * h);
  double dy = vy > 0.0 ? (vy + sq) / g : (2.0 * h) / (sq - vy);
  if (dy < dt) dt = dy;
  return s->t + dt;
}

/* Elastic hard-disk collision along r = r2 - r1 at contact, seed Eqs. (10)-(12). */
void collide_pair(double rx, double ry, State *p, double m1, State *q, double m2) {
  double vx1 = p->vx, vy1 = p->vy, vx2 = q->vx, vy2 = q->vy;
  double d = __builtin_sqrt(rx * rx + ry * ry);
  double nx = rx / d;
  double ny = ry / d;
  double dv = nx * (vx1 - vx2) + ny * (vy1 - vy2);
  double k1 = ((2.0 * m2) / (m1 + m2)) * dv;
  double k2 = ((2.0 * m1) / (m1 + m2)) * dv;
  p->vx = vx1 - k1 * nx;
  p->vy = vy1 - k1 * ny;
  q->vx = vx2 + k2 * nx;
  q->vy = vy2 + k2 * ny;
}

/* Reflect v about the tangent of y = a x^2 at x, scaled by keep = 1 - damping. */
static void reflect_wall(double x, double vx, double vy, double a, double keep, double *ux,
                         double *uy) {
  double sx = -2.0 * a * x;
  double nn = sx * sx + 1.0;
  double vn = vx * sx + vy;
  double f = (2.0 * vn) / nn;
  *ux = keep * (vx - f * sx);
  *uy = keep * (vy - f);
}

/*
 * Elastic bounce that leaves the wall at least v_min along the normal (docs/model.md,
 * "Grazing and resting atoms"): a slower bounce is turned, energy kept.
 */
void bounce_wall(State *s, double a, double v_min) {
  double x = s->x, ux, uy;
  reflect_wall(x, s->vx, s->vy, a, 1.0, &ux, &uy);
  double sx = -2.0 * a * x;
  double nn = __builtin_sqrt(sx * sx + 1.0);
  double nx = sx / nn; /* inward unit normal (nx, ny); unit tangent (ny, -nx) */
  double ny = 1.0 / nn;
  double un = ux * nx + uy * ny;
  if (un >= v_min) {
    s->vx = ux;
    s->vy = uy;
    return;
  }
  double ut = ux * ny - uy * nx;
  double rest = ux * ux + uy * uy - v_min * v_min;
  double wt = 0.0;
  if (rest > 0.0) {
    wt = __builtin_sqrt(rest);
    if (ut < 0.0) wt = -wt;
  }
  s->vx = v_min * nx + wt * ny;
  s->vy = v_min * ny - wt * nx;
}

/* Damped bounce after the win (seed Eq. 34) with a floor v_floor on the normal speed. */
void settle_wall(State *s, double a, double keep, double v_floor) {
  double x = s->x, ux, uy;
  reflect_wall(x, s->vx, s->vy, a, keep, &ux, &uy);
  double sx = -2.0 * a * x;
  double nn = __builtin_sqrt(sx * sx + 1.0);
  double vn = (ux * sx + uy) / nn;
  if (vn < v_floor) {
    double d = (v_floor - vn) / nn;
    ux = ux + d * sx;
    uy = uy + d;
  }
  s->vx = ux;
  s->vy = uy;
}

/*
 * a * b + c as two roundings. A build that fuses it into one (a multiply-add: -ffp-contract
 * on) gives other bits for some inputs, and then other events: the tests call this with
 * such inputs to catch a build that contracts.
 */
double core_contraction_probe(double a, double b, double c) { return a * b + c; }

/* Energy of row i from its stored state (conserved in flight). */
double energy(Core *core, int32_t i) {
  const State *s = &core->state[i];
  return atom_energy_of(core->queued[i].mass, s->y, s->vx, s->vy, core->run.gravity);
}
