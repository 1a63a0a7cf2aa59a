/*
 * The overlap check of a start or a state, written once for both editions (issue 47): the
 * first pair of included atoms closer than (r_i + r_j)(1 - tol), least i then least j, with
 * the comparison of physics/validation.py's first_overlap, its readable oracle. Atoms are
 * grouped into levels by radius (a factor 2 a level) and each level's atoms filed in a hash
 * grid of cells 2.5 of its largest radii wide, so a pair is found from its smaller atom in a
 * 3 x 3 block, which holds a bounded number of atoms that do not overlap. A cell's chain is
 * in index order, so the pairs it gives grow: a scan stops at the first that cannot beat the
 * best so far, and a heap of atoms on one spot costs no more than a few.
 */
#include "evapcool_core.h"

/* Levels of radius: a factor 2 each; wider mixtures share the last (slower, still exact). */
#define LEVELS 48

/* The column (or row) of coordinate u in cells of `size` (-0 as +0: one cell, one hash). */
static double cell(double u, double size) { return __builtin_floor(u / size) + 0.0; }

/* MurmurHash3's finalizer: every bit of a cell's number (a double's high bits) counts. */
static uint64_t mix(uint64_t h) {
  h = (h ^ (h >> 33)) * 0xFF51AFD7ED558CCDu;
  h = (h ^ (h >> 33)) * 0xC4CEB9FE1A85EC53u;
  return h ^ (h >> 33);
}

/* The table's slot of cell (cx, cy): the one holding its chain's first atom, or an empty
 * one (-1) where it would go. The table has more slots than atoms: a probe ends. */
static int32_t *slot(int32_t *table, uint32_t mask, double cx, double cy, const double *x,
                     const double *y, double size) {
  uint64_t a, b;
  __builtin_memcpy(&a, &cx, 8);
  __builtin_memcpy(&b, &cy, 8);
  uint64_t h = mix(a ^ mix(b));
  for (uint32_t k = (uint32_t)h & mask;; k = (k + 1) & mask) {
    int32_t j = table[k];
    if (j < 0 || (cell(x[j], size) == cx && cell(y[j], size) == cy)) return &table[k];
  }
}

/* Each included atom's level (0 for the smallest radius); the highest level. */
static int32_t levels(const double *radius, const int8_t *include, int32_t n, int32_t *level) {
  double rmin = __builtin_inf();
  for (int32_t i = 0; i < n; i++)
    if (include[i] && radius[i] < rmin) rmin = radius[i];
  int32_t top = 0;
  for (int32_t i = 0; i < n; i++) {
    int32_t l = 0;
    for (double edge = 2.0 * rmin; l < LEVELS - 1 && radius[i] >= edge; edge *= 2.0) l++;
    level[i] = include[i] ? l : -1;
    top = l > top && include[i] ? l : top;
  }
  return top;
}

int32_t core_first_overlap(const double *x, const double *y, const double *radius,
                           const int8_t *include, int32_t n, double tol, int32_t *work,
                           int32_t *pair) {
  uint32_t slots = 2;
  while (slots < 2u * (uint32_t)n) slots *= 2;
  int32_t *table = work, *next = work + slots, *level = next + n;
  int32_t top = levels(radius, include, n, level);
  int32_t bi = n, bj = n; /* the best pair so far (none: n, n) */
  for (int32_t lev = 0; lev <= top; lev++) {
    double rmax = 0.0;
    for (int32_t i = 0; i < n; i++)
      if (level[i] == lev && radius[i] > rmax) rmax = radius[i];
    if (!(rmax > 0.0)) continue;
    double size = 2.5 * rmax; /* a contact 2 rmax (1 - tol) away is one cell over, at most */
    for (uint32_t k = 0; k < slots; k++) table[k] = -1;
    for (int32_t j = n - 1; j >= 0; j--) { /* filed from the last: chains in index order */
      if (level[j] != lev) continue;
      int32_t *s = slot(table, slots - 1, cell(x[j], size), cell(y[j], size), x, y, size);
      next[j] = *s;
      *s = j;
    }
    for (int32_t i = 0; i < n; i++) {
      if (level[i] < 0 || level[i] > lev) continue;
      double cx = cell(x[i], size), cy = cell(y[i], size);
      for (int32_t d = 0; d < 9; d++) {
        int32_t j = *slot(table, slots - 1, cx + (d % 3 - 1), cy + (d / 3 - 1), x, y, size);
        for (; j >= 0; j = next[j]) {
          if (j == i) continue;
          int32_t a = j < i ? j : i, b = j < i ? i : j;
          if (a > bi || (a == bi && b >= bj)) break;
          double dx = x[i] - x[j], dy = y[i] - y[j], lim = (radius[i] + radius[j]) * (1.0 - tol);
          if (dx * dx + dy * dy < lim * lim) {
            bi = a, bj = b;
            break;
          }
        }
      }
    }
  }
  pair[0] = bi;
  pair[1] = bj;
  return bi < n;
}
