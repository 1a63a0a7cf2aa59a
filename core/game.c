/*
 * The game's rules that decide a score, written once for both editions (game/rules.py and
 * web/src/game/rules.ts call them): a trap height takes effect at a whole frame, the win is
 * seen at the end of a whole frame and the score is the atoms trapped then. A game is
 * therefore its heights per whole frame, whatever the display's rate, and a recording of
 * them (game/replay.py, web/src/game/replay.ts) replays to the same score in every edition.
 */
#include "tables.h"

/*
 * The end of a whole frame: a win latched during the frame is seen now, and the score fixed
 * at the atoms trapped now (one already on its way over the rim may still leave; the score
 * stays). 1 at the frame the win is first seen, else 0.
 */
int32_t frame_end(Core *core) {
  Run *r = &core->run;
  if (!r->won || r->score >= 0) return 0;
  r->score = r->n_trapped;
  r->win_frame = r->time;
  return 1;
}

/*
 * One whole frame from a whole frame, the trap at `height` during it: the height takes effect
 * at the frame's start (not after the win: the score is the atoms left), then the events up to
 * the next whole frame, then the frame's end. Replays and paths keep no log, so it never fills.
 */
void frame(Core *core, double height) {
  Run *r = &core->run;
  if (!r->won && height != r->trap_height) core_set_trap_height(core, height);
  core_advance_to(core, whole_frame(r->time) + 1.0);
  frame_end(core);
}

/* n doubles of the engine's memory for the caller to fill (a recording's runs). */
double *core_buffer(Core *core, int32_t n) { return core_take(core, sizeof(double) * n); }

/* NumPy's sum of n doubles (pairwise: blocks of 128 with eight running sums), so a
 * temperature here has the bits of Python's np.sum. */
static double pairwise_sum(const double *a, int32_t n) {
  if (n < 8) {
    double res = 0.0;
    for (int32_t i = 0; i < n; i++) res += a[i];
    return res;
  }
  if (n <= 128) {
    double r[8];
    for (int32_t j = 0; j < 8; j++) r[j] = a[j];
    int32_t i = 8;
    for (; i < n - (n % 8); i += 8)
      for (int32_t j = 0; j < 8; j++) r[j] += a[i + j];
    double res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
    for (; i < n; i++) res += a[i];
    return res;
  }
  int32_t n2 = n / 2;
  n2 -= n2 % 8;
  return pairwise_sum(a, n2) + pairwise_sum(a + n2, n - n2);
}

/* E of the trapped atoms, in World index order and summed as NumPy sums (total_energy); N: *n. */
static double trapped_energy(Core *core, int32_t *n) {
  *n = 0;
  for (int32_t a = 0; a < core->run.n_atoms; a++)
    if (core_status_of(core, a) == TRAPPED) core->scratch[(*n)++] = core_atom_energy(core, a);
  return pairwise_sum(core->scratch, *n);
}

/* The trapped atoms' energy, summed as NumPy sums (the page's Simulation.totalEnergy). */
double core_total_energy(Core *core) {
  int32_t n;
  return trapped_energy(core, &n);
}

/* Keep frame k's point (k, N, T, h) unless no atom is trapped or T is not finite and > 0. */
static void keep(Core *core, double *points, int32_t *n_points, int32_t k, double h) {
  int32_t n;
  double t = trapped_energy(core, &n) / n; /* T = E / N, seed Eq. 1 */
  if (n <= 0 || !__builtin_isfinite(t) || !(t > 0.0)) return;
  double *p = points + 4 * (*n_points)++;
  p[0] = k;
  p[1] = n;
  p[2] = t;
  p[3] = h;
}

/*
 * A recording's path in the (N, T) plane (game/path.py's sampling, its oracle): the runs
 * played as core_replay plays them, up to the win or `limit` frames; kept are frame 0 (with
 * height h0) and every `stride`-th whole frame, the last one and the win's. points: rows
 * of (k, N, T, h), at least limit / stride + 2 of them, or 0 for none (core_replay); their
 * count into n_points. Returns the frames played.
 */
int32_t core_path(Core *core, const double *runs, int32_t n_runs, int32_t limit, int32_t stride,
                  double h0, double *points, int32_t *n_points) {
  core->run.record = 0;
  core->run.n_log = 0;
  if (points) {
    *n_points = 0;
    keep(core, points, n_points, 0, h0);
    if (core->run.score >= 0) return 0;
  }
  int32_t k = 0;
  for (int32_t r = 0; r < n_runs; r++)
    for (double f = 0.0; f < runs[2 * r + 1]; f += 1.0) {
      if (k >= limit) return k;
      frame(core, runs[2 * r]);
      k++;
      int32_t won = core->run.score >= 0;
      if (points && (k % stride == 0 || k == limit || won)) keep(core, points, n_points, k, runs[2 * r]);
      if (won) return k;
    }
  return k;
}

/*
 * A recording played back from a whole frame: runs (height, frames) pairs, each height held
 * for that many whole frames; it stops at the end of the frame the win is seen, or after
 * `limit` frames. Returns the frames played; the win and the score are the core's (core_won,
 * core_score). A replay keeps no event log, nor a path.
 */
int32_t core_replay(Core *core, const double *runs, int32_t n_runs, int32_t limit) {
  return core_path(core, runs, n_runs, limit, 1, 0.0, 0, 0);
}

/*
 * The reach rule, its why and its oracle physics/reference.py's `out_of_reach`: REACH_WITHIN
 * while T < Tc(N) stays reachable, with m the lightest trapped mass, `lowest` the lowest rim
 * the player can set and `height` the rim now. Never once won, nor without the win rule.
 */
int32_t core_out_of_reach(Core *core, double lowest, double height) {
  const Run *r = &core->run;
  if (r->won || !r->win_rule) return REACH_WITHIN;
  int32_t n;
  double energy = trapped_energy(core, &n), m = INF;
  for (int32_t a = 0; a < r->n_atoms; a++) {
    double mass = core_stored_of(core, a, 6);
    if (core_status_of(core, a) == TRAPPED && mass < m) m = mass;
  }
  if (n <= 0) return REACH_ALL_ESCAPED;
  if (energy / n < core->tc_table[n]) return REACH_WITHIN; /* condensing now */
  if (n == 1) return REACH_ONE_ATOM;
  if (energy <= m * r->gravity * lowest) return REACH_STUCK;
  if (energy <= m * r->gravity * height) return REACH_STUCK_HERE;
  return REACH_WITHIN;
}
