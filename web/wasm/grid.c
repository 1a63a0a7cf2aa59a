/*
 * The cell grid (twin of grid.py): trapped atoms in cells 1.1 contact distances wide, the
 * edge cells reaching to infinity. `cells` holds the first row of every cell (row-major),
 * then the next row in the same cell for every row; plan.cell_prev links back.
 */
#include "tables.h"

/* Cell edge in contact distances; > 1 leaves room for round-off in crossing times. */
#define CELL_FACTOR 1.1
/* At most this many cells per atom (bounds memory for tiny, sparse atoms). */
#define MAX_CELLS_PER_ATOM 8

/* The cell column (or row) of coordinate u, clamped to the grid. */
int32_t cell_of(double u, double u0, int32_t n) {
  double c = __builtin_floor((u - u0) / run.cell);
  if (c < 0) return 0;
  if (c > n - 1) return n - 1;
  return (int32_t)c;
}

/* File row i first in cell (cx, cy). */
void link(int32_t i, int32_t cx, int32_t cy) {
  Plan *p = &plan[i];
  p->cell_x = cx;
  p->cell_y = cy;
  int32_t c = cy * run.nx + cx;
  int32_t q = cells[c];
  cells[run.n_cells + i] = q;
  p->cell_prev = -1;
  if (q >= 0) plan[q].cell_prev = i;
  cells[c] = i;
}

/* Take row i out of its cell. */
void unlink(int32_t i) {
  Plan *pl = &plan[i];
  int32_t p = pl->cell_prev;
  int32_t q = cells[run.n_cells + i];
  int32_t c = pl->cell_y * run.nx + pl->cell_x;
  if (p >= 0)
    cells[run.n_cells + p] = q;
  else if (cells[c] == i)
    cells[c] = q;
  if (q >= 0) plan[q].cell_prev = p;
  cells[run.n_cells + i] = -1;
  pl->cell_prev = -1;
}

/*
 * Cells: 1.1 of the largest contact distance, over the region the trapped atoms can reach
 * (below the height of the most energetic one, y <= E / (m g)), as long as that takes at
 * most 8 cells per atom; beyond it atoms sit in the edge cells, which reach to infinity.
 * Sets run.cell, nx, ny, grid_x0, grid_y0, n_cells (engine.ts's gridShape).
 */
EXPORT(grid_shape) int32_t grid_shape(void) {
  int32_t n = run.n_atoms;
  double r_max = 0, top = 1;
  for (int32_t r = 0; r < n; r++) {
    if (plan[r].status != TRAPPED) continue;
    if (state[r].radius > r_max) r_max = state[r].radius;
    double h = energy(r) / (queued[r].mass * run.gravity);
    if (h > top) top = h;
  }
  double cs = r_max > 0 ? CELL_FACTOR * 2 * r_max : 1;
  double max_cells = (double)MAX_CELLS_PER_ATOM * n + 64;
  /* Box: |x| <= sqrt(y_top / a) + cs, 0 <= y <= y_top; shrink y_top until it fits. */
  double y_top = top + cs;
  double nx, ny;
  for (;;) {
    double half_w = __builtin_sqrt(y_top / run.curvature) + cs;
    nx = __builtin_ceil((2 * half_w) / cs);
    ny = __builtin_ceil((y_top + 0.5 * cs) / cs);
    if (nx < 1) nx = 1;
    if (ny < 1) ny = 1;
    if (nx * ny <= max_cells || y_top <= cs) break;
    y_top *= 0.8;
  }
  run.cell = cs;
  run.nx = (int32_t)nx;
  run.ny = (int32_t)ny;
  run.grid_x0 = -0.5 * nx * cs;
  run.grid_y0 = -0.5 * cs;
  run.n_cells = run.nx * run.ny;
  return run.n_cells;
}

/* Trapped atoms filed more than one cell away from their cell now (0 if sound). */
EXPORT(grid_errors) int32_t grid_errors(void) {
  if (run.won) return 0;
  int32_t bad = 0;
  for (int32_t r = 0; r < run.n_atoms; r++) {
    if (plan[r].status != TRAPPED) continue;
    const State *s = &state[r];
    double dt = run.time - s->t;
    int32_t cx = cell_of(flight_x(s->x, s->vx, dt), run.grid_x0, run.nx);
    int32_t cy = cell_of(flight_y(s->y, s->vy, 0.5 * run.gravity, dt), run.grid_y0, run.ny);
    int32_t ex = cx - plan[r].cell_x, ey = cy - plan[r].cell_y;
    if (ex > 1 || ex < -1 || ey > 1 || ey < -1) bad++;
  }
  return bad;
}
