/*
 * The start from a seed (SPEC 1, issue 22.1), written once for both editions: rows of cells
 * filled from the bottom, centre-out in a row, one atom at a random point of each cell's
 * jitter disk, moving in a random direction. src/evapcool/physics/start.py and loading.py
 * are the readable twin (NumPy) and the oracle these functions are tested against, bit for
 * bit; the golden starts (web/test/golden/starts.json) hold both.
 *
 * Random numbers come from a counter-based hash: MurmurHash3's 32-bit finalizer over the
 * seed, a stream number and a counter, so the k-th number of a stream needs no state.
 * Turning them into a start takes only + - * / and sqrt, which IEEE 754 rounds exactly.
 */
#include "tables.h"

/* Streams: each use of random numbers has its own (start.py's STREAM_*). */
enum { STREAM_JITTER = 1, STREAM_SPEED = 2, STREAM_DIRECTION = 3 };
/* Candidates per atom for a point of the unit disk, then its own fallback stream. */
enum { CANDIDATES = 8, FALLBACK = 16 };

/* Speed at the bottom row and its step per 40 px of height (px / frame). */
#define V0 (100.0 / 30.0)
#define DV (10.0 / 30.0)
/* The original's row spacing (R = 12), px: the speed profile is the original's for any R. */
#define ROW_SPACING_ORIGINAL 40.0
/* A little above 1 / cos(pi / 64): corners this many jitter radii out circumscribe the disk. */
#define SECANT 1.00121

/* cos(2 pi k / 64) for k = 0..16 as exact literals (no cos at run time); the other
 * vertices of the 64-gon follow by symmetry. */
static const double QUARTER_COS[17] = {
    1.0,                 0.9951847266721969,  0.9807852804032304,  0.9569403357322088,
    0.9238795325112867,  0.881921264348355,   0.8314696123025452,  0.773010453362737,
    0.7071067811865476,  0.6343932841636455,  0.5555702330196023,  0.4713967368259978,
    0.38268343236508984, 0.29028467725446233, 0.19509032201612833, 0.09801714032956077,
    0.0,
};

/* MurmurHash3's finalizer: a bijection of 32-bit words that mixes every bit. */
static uint32_t fmix32(uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  return h ^ (h >> 16);
}

/* One stream of a seed: its two keys (the seed's low and high words, salted by the stream). */
typedef struct {
  uint32_t a, b;
} Stream;

static Stream stream_of(uint32_t seed_lo, uint32_t seed_hi, uint32_t stream) {
  Stream s;
  s.a = fmix32(seed_lo ^ (0x9e3779b9u * stream));
  s.b = fmix32(seed_hi ^ s.a ^ 0x5bd1e995u);
  return s;
}

static uint32_t word(Stream s, uint32_t c) { return fmix32(fmix32(c ^ s.a) ^ s.b); }

/* The k-th double in [0, 1), from words 2k and 2k + 1 (27 + 26 bits). */
static double uniform(Stream s, uint32_t k) {
  double hi = (double)(word(s, 2 * k) >> 5), lo = (double)(word(s, 2 * k + 1) >> 6);
  return (hi * 67108864.0 + lo) / 9007199254740992.0;
}

/* The first of `count` candidates from number `first` of the square [-1, 1)^2 with
 * inner <= x^2 + y^2 < 1, into out; 0 if none is. */
static int pick(Stream s, uint32_t first, uint32_t count, double inner, double *out) {
  for (uint32_t c = first; c < first + count; c++) {
    double x = 2.0 * uniform(s, 2 * c) - 1.0, y = 2.0 * uniform(s, 2 * c + 1) - 1.0;
    double r2 = x * x + y * y;
    if (r2 >= inner && r2 < 1.0) {
      out[0] = x;
      out[1] = y;
      return 1;
    }
  }
  return 0;
}

/* Atom i's point of the disk (inner = 0) or ring: its candidates, then its fallback
 * stream's (chance < 1e-5 an atom); 0 if those miss too (impossible odds). */
static int disk_point(uint32_t lo, uint32_t hi, uint32_t stream, uint32_t i, double inner, double *out) {
  if (pick(stream_of(lo, hi, stream), i * CANDIDATES, CANDIDATES, inner, out)) return 1;
  return pick(stream_of(lo, hi, stream + 16 * FALLBACK), i * FALLBACK, FALLBACK, inner, out);
}

/* Vertex k of the unit 64-gon, counter-clockwise from (1, 0). */
static void vertex(int32_t k, double *c, double *s) {
  int32_t j = k & 15;
  double a = QUARTER_COS[j], b = QUARTER_COS[16 - j];
  switch (k >> 4) {
  case 0: *c = a, *s = b; break;
  case 1: *c = -b, *s = a; break;
  case 2: *c = -a, *s = -b; break;
  default: *c = b, *s = -a; break;
  }
}

/* Whether the disk of radius rad around (xc, yc) lies inside y >= a x^2: the region is
 * convex, so a circumscribing 64-gon with its corners inside proves it. */
static int32_t disk_inside_cup(double xc, double yc, double rad, double a) {
  double rho = rad * SECANT;
  for (int32_t k = 0; k < 64; k++) {
    double c, s;
    vertex(k, &c, &s);
    double px = xc + rho * c, py = yc + rho * s;
    if (!(py > a * px * px)) return 0;
  }
  return 1;
}

/* The rows' geometry for atoms of this radius (loading.py's cell_centres). */
typedef struct {
  double jitter, cell, spacing, y0;
} Rows;

static Rows rows_of(double radius) {
  Rows r;
  r.jitter = radius * 8.0 / 12.0;
  r.cell = radius + r.jitter;
  r.spacing = 2.0 * r.cell;
  r.y0 = r.jitter * 1.05; /* row 0 lifted a hair so its jitter disk is certified inside */
  return r;
}

/* Half-width of row k in cells (the cup's width at the row's height, plus one). */
static int32_t row_half_width(Rows r, double yc, double curvature) {
  return (int32_t)(__builtin_sqrt(yc / curvature) / r.spacing) + 1;
}

/* Cell j of a row centre-out: 0, 1, -1, 2, -2, ... */
static int32_t centre_out(int32_t q) { return q == 0 ? 0 : (q & 1) ? (q + 1) / 2 : -(q / 2); }

/*
 * Centres of the first n cells, row by row from the bottom, into xy (x0, y0, x1, y1, ...;
 * none kept if xy is 0). Returns n, or how many cells fit (whole rows) if n do not fit
 * below y_top.
 */
static int32_t cell_centres(double *xy, int32_t n, double radius, double curvature, double y_top) {
  Rows r = rows_of(radius);
  int32_t count = 0;
  for (int32_t k = 0; count < n; k++) {
    double yc = r.y0 + k * r.spacing;
    if (yc + r.cell > y_top) return count;
    int32_t m = row_half_width(r, yc, curvature);
    for (int32_t q = 0; q <= 2 * m && count < n; q++) {
      double xc = centre_out(q) * r.spacing;
      if (!disk_inside_cup(xc, yc, r.jitter, curvature)) continue;
      if (xy) {
        xy[2 * count] = xc;
        xy[2 * count + 1] = yc;
      }
      count++;
    }
  }
  return count;
}

/*
 * The start of n atoms of equal radius from a seed (its low and high 32-bit words): positions
 * into pos and velocities into vel (x0, y0, x1, y1, ...), trap coordinates. Each atom sits at
 * a uniform point of its cell's jitter disk and moves in a uniform direction (a point of the
 * ring 1/16 <= r^2 < 1 normalised by sqrt) at a speed growing with its row's height.
 * Returns n; if the atoms do not fit below y_top, how many fit; -1 for impossible odds.
 */
int32_t core_load_cup(double *pos, double *vel, int32_t n, double radius,
                                            double curvature, double y_top, uint32_t seed_lo,
                                            uint32_t seed_hi) {
  int32_t fit = cell_centres(pos, n, radius, curvature, y_top);
  if (fit < n) return fit;
  const double jitter = radius * 8.0 / 12.0, y_first = pos[1];
  Stream speeds = stream_of(seed_lo, seed_hi, STREAM_SPEED);
  for (int32_t i = 0; i < n; i++) {
    double off[2], ring[2];
    if (!disk_point(seed_lo, seed_hi, STREAM_JITTER, (uint32_t)i, 0.0, off)) return -1;
    if (!disk_point(seed_lo, seed_hi, STREAM_DIRECTION, (uint32_t)i, 1.0 / 16.0, ring)) return -1;
    double level = (pos[2 * i + 1] - y_first) / ROW_SPACING_ORIGINAL;
    double speed = V0 + (level + uniform(speeds, (uint32_t)i)) * DV;
    double norm = __builtin_sqrt(ring[0] * ring[0] + ring[1] * ring[1]);
    pos[2 * i] = pos[2 * i] + jitter * off[0];
    pos[2 * i + 1] = pos[2 * i + 1] + jitter * off[1];
    vel[2 * i] = (speed * ring[0]) / norm;
    vel[2 * i + 1] = (speed * ring[1]) / norm;
  }
  return n;
}

/* How many atoms of this radius the loading places with every disk below y_top: the whole
 * rows of cells whose disks stay under it, wherever the jitter puts them. */
int32_t core_cup_capacity(double radius, double curvature, double y_top) {
  return cell_centres(0, INT32_MAX, radius, curvature, y_top);
}

/*
 * x^p for x >= 0 and 0 < p <= 10 from products and square roots only (portable.py's power):
 * p = whole + sum of b_k 2^-k, so x^p is x^whole times x^(2^-k) for the digits set, x^(2^-k)
 * by k nested square roots (60 at most: x^(2^-60) is 1.0 in double precision here).
 */
double core_power(double x, double p) {
  if (x == 0.0) return 0.0;
  int32_t whole = (int32_t)p; /* floor: p > 0 */
  double result = 1.0, frac = p - whole, root = x;
  for (int32_t k = 0; k < whole; k++) result *= x;
  for (int32_t k = 0; k < 60 && frac != 0.0; k++) {
    root = __builtin_sqrt(root);
    frac *= 2.0;
    if (frac >= 1.0) {
      result *= root;
      frac -= 1.0;
    }
  }
  return result;
}

/* Tc(N) = Tc0 (N / N0)^p for every N = 0..N0 into the table the win test reads (seed Eq. 46). */
void core_fill_tc_table(Core *core, double tc0, double exponent) {
  const int32_t n0 = core->run.n_atoms;
  for (int32_t m = 0; m <= n0; m++) core->tc_table[m] = tc0 * core_power((double)m / (double)n0, exponent);
}
