/*
 * Predictions: each row keeps only its earliest real event (wall, exit
 * or pair) and its next cell crossing; the key is the earlier of the two.
 */
#include "tables.h"

/* (lower, higher) World index of rows i and j: a pair's key parts. */
static inline void pair_key(const Core *core, int32_t i, int32_t j, int64_t *lo, int64_t *hi) {
  int64_t a = core->state[i].atom, b = core->state[j].atom;
  *lo = a < b ? a : b;
  *hi = a < b ? b : a;
}

/* The heads of the three cells from c, step apart, appended to heads[0..n) without a branch
 * (about two cells in three are empty, at random); the new count. */
static inline int32_t gather3(const int32_t *c, int32_t step, int32_t *heads, int32_t n) {
  for (int32_t k = 0; k < 3; k++) {
    int32_t h = c[k * step];
    heads[n] = h;
    n += h >= 0;
  }
  return n;
}

/* Row i's pair with row j at time t against the best so far (bt, partner `best`, -1 while
 * the real event stands): the new best partner. A tie is decided by the keys. */
static inline int32_t take_pair(const Core *core, int32_t i, int32_t j, double t, int was_pair,
                                int32_t best, double *bt) {
  if (t == *bt) { /* rare: a tie, decided by the keys */
    const Plan *p = &core->plan[i];
    int64_t lo, hi, ba = p->real_a, bb = p->real_b;
    pair_key(core, i, j, &lo, &hi);
    if (best >= 0) pair_key(core, i, best, &ba, &bb);
    if ((best >= 0 || was_pair) && (lo < ba || (lo == ba && hi < bb))) best = j;
  }
  /* an earlier pair, taken without a branch (which way it goes is a coin toss) */
  const int earlier = t < *bt;
  *bt = earlier ? t : *bt;
  return earlier ? j : best;
}

/*
 * Pairs of trapped row i with the rows of the cells whose heads are given (seed Eqs.
 * 15-19), two neighbours at a time. An earlier pair replaces i's real event; on a tie the
 * solo event stays and pairs go in (lower, higher) World index order, as in the reference
 * engine, so the order the pairs are tested in changes nothing.
 */
static void scan(Core *core, int32_t i, const int32_t *heads, int32_t n_heads) {
  const State *s = &core->state[i];
  const double ri = s->radius, g = core->run.gravity;
  Plan *p = &core->plan[i];
  double bt = core->queued[i].real_t;
  const int was_pair = p->real_rank == RANK_PAIR;
  int32_t best = -1; /* the partner found here, -1 while the real event stands */
  int32_t held = -1; /* a neighbour waiting for a second, to test the two at once */
#ifdef CORE_LANES
  double slack = __builtin_fabs(bt) * 1e-12; /* follows bt */
#endif
  for (int32_t k = 0; k < n_heads; k++)
    for (int32_t j = heads[k]; j >= 0; j = core->state[j].next) {
      if (j == i) continue;
#ifndef CORE_LANES
      const State *q = &core->state[j];
      double t = pair_contact_time(s, q, ri + q->radius, g, bt);
      best = take_pair(core, i, j, t, was_pair, best, &bt);
#else
      if (held < 0) {
        held = j;
        continue;
      }
      int32_t rows[2] = {held, j};
      double ts[2];
      held = -1;
      if (!pair_contact_times(s, &core->state[rows[0]], &core->state[rows[1]], g, bt, slack, ts)) {
        if (bt < INF) continue; /* most pairs: both miss, and an inf neither ties nor wins */
        ts[0] = ts[1] = INF;
      }
      for (int32_t m = 0; m < 2; m++) best = take_pair(core, i, rows[m], ts[m], was_pair, best, &bt);
      slack = __builtin_fabs(bt) * 1e-12;
#endif
    }
  if (held >= 0) {
    const State *q = &core->state[held];
    double t = pair_contact_time(s, q, ri + q->radius, g, bt);
    best = take_pair(core, i, held, t, was_pair, best, &bt);
  }
  if (best >= 0) {
    int64_t lo, hi;
    pair_key(core, i, best, &lo, &hi);
    core->queued[i].real_t = bt;
    p->real_rank = RANK_PAIR;
    p->real_a = (int32_t)lo;
    p->real_b = (int32_t)hi;
    p->real_kind = KIND_PAIR;
    p->partner = best;
    p->partner_count = (int32_t)core->state[best].count;
  }
}

/* Pairs of row i with the three cells from cell index c, step apart (a row of cells: 1, a
 * column: the stride): after a crossing, the line of cells that came within reach. */
void scan_line(Core *core, int32_t i, int32_t c, int32_t step) {
  int32_t heads[3];
  scan(core, i, heads, gather3(&core->cells[c], step, heads, 0));
}

/* Pairs of row i with the 3 x 3 cells around its own (the border's cells are empty). */
static void scan_around(Core *core, int32_t i) {
  const int32_t w = core->run.stride;
  const int32_t *c = &core->cells[cell_index(core, core->plan[i].cell_x - 1, core->plan[i].cell_y - 1)];
  int32_t heads[9];
  scan(core, i, heads, gather3(c + 2 * w, 1, heads, gather3(c + w, 1, heads, gather3(c, 1, heads, 0))));
}

/* Row i's real event: wall (SPEC 2.1) or pair if trapped, exit if escaped. */
void predict_real(Core *core, int32_t i) {
  const State *s = &core->state[i];
  Plan *p = &core->plan[i];
  int32_t st = p->status;
  double t = INF;
  int32_t kind = KIND_NONE;
  if (st == TRAPPED) {
    t = wall_contact_time(s, core->run.curvature, core->run.gravity);
    kind = KIND_WALL;
  } else if (st == ESCAPED) {
    double rad = s->radius;
    t = exit_time(s, core->run.x_left - rad, core->run.x_right + rad, core->run.y_bottom - rad, core->run.gravity);
    kind = KIND_EXIT;
  }
  core->queued[i].real_t = t;
  p->real_rank = RANK_SOLO;
  p->real_a = p->atom;
  p->real_b = 0;
  p->real_kind = kind;
  if (st == TRAPPED && !core->run.won) scan_around(core, i);
}

/* Time of the next y crossing of row i's arc and the row it enters (inf if none). */
static double crossing_y(Core *core, const State *s, int32_t cy, double taken, int32_t *to) {
  const double g = core->run.gravity;
  double y = s->y, vy = s->vy, t0 = s->t;
  double tc = INF;
  if (vy > 0.0 && cy < core->run.ny - 1) {
    double d = core->edge_y[2 * cy + 1] - y;
    double disc = vy * vy - 2.0 * g * d;
    if (disc > 0.0) {
      double sq = __builtin_sqrt(disc);
      double t1 = t0 + (2.0 * d) / (vy + sq);
      double t2 = t0 + (vy + sq) / g;
      if (t2 > t1 && t1 > taken) {
        tc = t1;
        *to = cy + 1;
      }
    }
  }
  if (tc == INF && cy > 0) {
    double h = y - core->edge_y[2 * cy];
    double disc = vy * vy + 2.0 * g * h;
    if (disc < 0.0) disc = 0.0;
    double sq = __builtin_sqrt(disc);
    double t2;
    if (vy > 0.0)
      t2 = t0 + (vy + sq) / g;
    else if (sq - vy > 0.0)
      t2 = t0 + (2.0 * h) / (sq - vy);
    else
      t2 = t0;
    if (t2 > taken) {
      tc = t2;
      *to = cy - 1;
    }
  }
  return tc;
}

/*
 * 0 if the arc of state s surely reaches neither y edge of cell row cy before time `by`: it rises
 * at most vy dt and falls at most -vy dt + g dt^2 / 2 in dt (with room for round-off many
 * times over, so that crossing_y would find no crossing before `by` either).
 */
static int y_edge_within(const Core *core, const State *s, int32_t cy, double by) {
  const double g = core->run.gravity, cs = core->run.cell, vy = s->vy;
  double dt = (by - s->t) * (1.0 + 1e-9) + (__builtin_fabs(by) + __builtin_fabs(s->t)) * 1e-12;
  if (!(dt > 0.0 && dt < INF)) return 1; /* (inf: 0 * inf would read as no reach) */
  double rise = (vy > 0.0 ? vy : 0.0) * dt, fall = (vy < 0.0 ? -vy : 0.0) * dt + 0.5 * g * dt * dt;
  /* (the edge rows' outer edges are at infinity in the table: no reach there) */
  double top = core->edge_y[2 * cy + 1] - s->y, bottom = s->y - core->edge_y[2 * cy];
  return (rise * (1.0 + 1e-9) + 1e-9 * cs >= top) | (fall * (1.0 + 1e-9) + 1e-9 * cs >= bottom);
}

/*
 * Row i's next cell crossing (none unless trapped and the game is on). x: straight to the
 * next edge along vx. y: up through the top edge (first root, if the arc passes it), else
 * down through the bottom edge; roots at or before the arc's last y crossing are ones
 * already taken. Edge cells reach to infinity: no outer edge.
 */
void predict_crossing(Core *core, int32_t i) {
  Plan *p = &core->plan[i];
  double bt = INF;
  int32_t bk = KIND_NONE, barg = 0;
  if (p->status == TRAPPED && !core->run.won) {
    const State *s = &core->state[i];
    double x = s->x, vx = s->vx, t0 = s->t;
    int32_t cx = p->cell_x, cy = p->cell_y;
    if (vx > 0.0 && cx < core->run.nx - 1) {
      bt = t0 + (core->edge_x[2 * cx + 1] - x) / vx;
      bk = KIND_CROSS_X;
      barg = cx + 1;
    } else if (vx < 0.0 && cx > 0) {
      bt = t0 + (core->edge_x[2 * cx] - x) / vx;
      bk = KIND_CROSS_X;
      barg = cx - 1;
    }
    /* A y crossing matters only before the x crossing and the real event (after a real
     * event every prediction is made anew; scans only bring it earlier). */
    double by = bt < core->queued[i].real_t ? bt : core->queued[i].real_t;
    int32_t to = 0;
    double tc = INF;
    if (y_edge_within(core, s, cy, by)) tc = crossing_y(core, s, cy, core->queued[i].arc_cross_t, &to);
    if (tc < bt) {
      bt = tc;
      bk = KIND_CROSS_Y;
      barg = to;
    }
  }
  core->queued[i].cross_t = bt;
  p->cross_axis = bk;
  p->cross_to = barg;
}

/* Row i's key from the earlier of its crossing and its real event, not filed. */
void load_key(Core *core, int32_t i) {
  Queued *u = &core->queued[i];
  Plan *p = &core->plan[i];
  if (u->cross_t <= u->real_t) {
    u->key_t = u->cross_t;
    p->rank = RANK_CROSS;
    p->tie_a = p->atom;
    p->tie_b = p->cross_axis;
  } else {
    u->key_t = u->real_t;
    p->rank = p->real_rank;
    p->tie_a = p->real_a;
    p->tie_b = p->real_b;
  }
}

/* Row i's key, re-filed. */
void set_key(Core *core, int32_t i) {
  load_key(core, i);
  file_atom(core, i);
}

/* Everything about row i from its stored state. */
void predict(Core *core, int32_t i) {
  predict_real(core, i);
  predict_crossing(core, i);
  set_key(core, i);
}
