/*
 * The cell grid: trapped atoms in cells 1.12 contact distances wide, the edge cells
 * reaching to infinity. An atom is refiled into the next cell only once it is a skin past
 * its cell's edge, so one that wanders to and fro over an edge is not refiled each time.
 * `cells` holds the first row of every cell (row-major), state[].next the next row in the
 * same cell; plan.cell_prev links back.
 */
#include "tables.h"

/* The skin on each side of a cell, in contact distances. */
#define SKIN 0.05
/* Cell edge in contact distances: a contact distance, both skins, and 0.01 a side for
 * round-off in crossing times (2e-4 px at the smallest radius: 1.3e4 times a position's
 * round-off at POSITION_MAX, 130 times the way 100 px/frame goes in the clock's round-off
 * at FRAMES_MAX). */
#define CELL_FACTOR (1.02 + 2 * SKIN)
/* At most this many cells per atom (bounds memory for tiny, sparse atoms). */
#define MAX_CELLS_PER_ATOM 8

/* The cell column (or row) of coordinate u, clamped to the grid. */
int32_t cell_of(Core *core, double u, double u0, int32_t n) {
  double c = __builtin_floor((u - u0) / core->run.cell);
  if (c < 0) return 0;
  if (c > n - 1) return n - 1;
  return (int32_t)c;
}

/* File row i first in cell (cx, cy). */
void cell_link(Core *core, int32_t i, int32_t cx, int32_t cy) {
  Plan *p = &core->plan[i];
  p->cell_x = cx;
  p->cell_y = cy;
  int32_t c = cell_index(core, cx, cy);
  int32_t q = core->cells[c];
  core->state[i].next = q;
  p->cell_prev = -1;
  if (q >= 0) core->plan[q].cell_prev = i;
  core->cells[c] = i;
}

/* Take row i out of its cell. */
void cell_unlink(Core *core, int32_t i) {
  Plan *pl = &core->plan[i];
  int32_t p = pl->cell_prev;
  int32_t q = core->state[i].next;
  int32_t c = cell_index(core, pl->cell_x, pl->cell_y);
  if (p >= 0)
    core->state[p].next = q;
  else if (core->cells[c] == i)
    core->cells[c] = q;
  if (q >= 0) core->plan[q].cell_prev = p;
  core->state[i].next = -1;
  pl->cell_prev = -1;
}

/*
 * Cells: CELL_FACTOR of the largest contact distance, over the region the trapped atoms can reach
 * (below the height of the most energetic one, y <= E / (m g)), as long as that takes at
 * most 8 cells per atom (plus 64); beyond it atoms sit in the edge cells, which reach to
 * infinity.
 * Sets run.cell, nx, ny, grid_x0, grid_y0, n_cells, stride; returns the cells to allocate,
 * the border included.
 */
int32_t grid_shape(Core *core) {
  int32_t n = core->run.n_atoms;
  double r_max = 0, top = 1;
  for (int32_t r = 0; r < n; r++) {
    if (core->plan[r].status != TRAPPED) continue;
    if (core->state[r].radius > r_max) r_max = core->state[r].radius;
    double h = energy(core, r) / (core->queued[r].mass * core->run.gravity);
    if (h > top) top = h;
  }
  double cs = r_max > 0 ? CELL_FACTOR * 2 * r_max : 1;
  double max_cells = (double)MAX_CELLS_PER_ATOM * n + 64;
  /* Box: |x| <= sqrt(y_top / a) + cs, 0 <= y <= y_top; shrink y_top until it fits, and
   * once y_top is down to a cell, widen the cells (tiny atoms in a wide cup). */
  double y_top = top + cs;
  double nx, ny;
  for (;;) {
    double half_w = __builtin_sqrt(y_top / core->run.curvature) + cs;
    nx = __builtin_ceil((2 * half_w) / cs);
    ny = __builtin_ceil((y_top + 0.5 * cs) / cs);
    if (nx < 1) nx = 1;
    if (ny < 1) ny = 1;
    if (nx * ny <= max_cells) break;
    if (y_top > cs)
      y_top *= 0.8;
    else
      cs *= 1.25;
  }
  core->run.cell = cs;
  core->run.skin = cs * (SKIN / CELL_FACTOR);
  core->run.nx = (int32_t)nx;
  core->run.ny = (int32_t)ny;
  core->run.grid_x0 = -0.5 * nx * cs;
  core->run.grid_y0 = -0.5 * cs;
  core->run.n_cells = core->run.nx * core->run.ny;
  core->run.stride = core->run.nx + 2;
  return core->run.stride * (core->run.ny + 2);
}

/* The refiling edges of every column, then of every row (2 (nx + ny) doubles), computed
 * once: each edge a skin beyond its cell's (edge_x, edge_y in tables.h). */
void grid_edges(Core *core, double *edges) {
  const double cs = core->run.cell, skin = core->run.skin;
  core->edge_x = edges;
  core->edge_y = edges + 2 * core->run.nx;
  for (int32_t c = 0; c < core->run.nx; c++) {
    core->edge_x[2 * c] = core->run.grid_x0 + c * cs - skin;
    core->edge_x[2 * c + 1] = core->run.grid_x0 + (c + 1) * cs + skin;
  }
  for (int32_t c = 0; c < core->run.ny; c++) {
    core->edge_y[2 * c] = core->run.grid_y0 + c * cs - skin;
    core->edge_y[2 * c + 1] = core->run.grid_y0 + (c + 1) * cs + skin;
  }
  /* The edge cells reach to infinity: their outer edges, read only by y_edge_within's
   * bound (the crossings test for an edge cell first), are infinitely far. */
  core->edge_y[0] = -INF;
  core->edge_y[2 * core->run.ny - 1] = INF;
}

/* 1 if u lies beyond cell c's edges (of n from u0) widened by `room` (edge cells: one edge). */
static int beyond(double u, double u0, int32_t c, int32_t n, double cs, double room) {
  return (c > 0 && u < u0 + c * cs - room) || (c < n - 1 && u > u0 + (c + 1) * cs + room);
}

/* Trapped atoms now beyond their cell, its skin and its round-off room (0 if sound:
 * every pair within reach is then in neighbouring cells). */
int32_t core_grid_errors(Core *core) {
  if (core->run.won) return 0;
  const double cs = core->run.cell, room = core->run.skin + cs * (0.01 / CELL_FACTOR);
  int32_t bad = 0;
  for (int32_t r = 0; r < core->run.n_atoms; r++) {
    if (core->plan[r].status != TRAPPED) continue;
    const State *s = &core->state[r];
    double dt = core->run.time - s->t;
    double x = flight_x(s->x, s->vx, dt), y = flight_y(s->y, s->vy, 0.5 * core->run.gravity, dt);
    const Plan *p = &core->plan[r];
    bad += beyond(x, core->run.grid_x0, p->cell_x, core->run.nx, cs, room) ||
           beyond(y, core->run.grid_y0, p->cell_y, core->run.ny, cs, room);
  }
  return bad;
}
