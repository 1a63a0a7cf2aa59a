/*
 * What each event does (twin of events.py): one handler per event kind, the clock, the
 * log, the win rule and leaving the trap.
 */
#include "tables.h"

/* An elastic bounce leaves the wall at least this fast along the normal (constants.ts). */
#define WALL_MIN_NORMAL_SPEED 1e-3
/* After the win, wall bounces keep 1 - 0.2 of the speed (seed Eq. 34)... */
#define WIN_DAMPING 0.2
/* ...but only while the speed is at least this... */
#define WIN_DAMPING_MIN_SPEED 1.0
/* ...and leave the wall at least this fast along the normal. */
#define WIN_NORMAL_SPEED_FLOOR 0.25

/* Energy of row i from its stored state (conserved in flight). */
double energy(int32_t i) {
  const State *s = &state[i];
  return atom_energy_of(queued[i].mass, s->y, s->vx, s->vy, run.gravity);
}

/* Carry row i's stored state to the clock (exact free flight, seed Eqs. 3-4). */
void move(int32_t i) {
  State *s = &state[i];
  double t = run.time;
  double dt = t - s->t;
  s->x = flight_x(s->x, s->vx, dt);
  s->y = flight_y(s->y, s->vy, 0.5 * run.gravity, dt);
  s->vy = flight_vy(s->vy, run.gravity, dt);
  s->t = t;
  queued[i].arc_cross_t = -INF; /* a new arc: none of its y crossings taken yet */
}

/* Log an event at the clock's time (World indices; b = -1 for solo events). */
static void log_event(int32_t kind, int32_t a, int32_t b) {
  if (!run.record) return;
  LogLine *l = &event_log[run.n_log++];
  l->kind = kind;
  l->a = a;
  l->b = b;
  l->t = run.time;
}

/* The clock to the event's time (never back: an event due in the past happens now). */
static void clock_to(double te) { run.time = te >= run.time ? te : run.time; }

/* T < Tc(N) with the running energy sum (seed Eqs. 1 and 46), latched. */
static void check_win(void) {
  int32_t n = run.n_trapped;
  if (run.won || n == 0 || !run.win_rule) return;
  if (run.energy_sum / n < tc_table[n]) run.won = 1;
}

/* Row i leaves the trapped set (over the rim or by the knife). */
static void leave_trap(int32_t i, int32_t status) {
  plan[i].status = status;
  run.n_trapped--;
  run.energy_sum -= energy(i);
  state[i].count += 1;
  unlink(i);
  predict(i);
  check_win();
}

/* Remove trapped row i now if its energy exceeds m g H; 1 if removed. */
int32_t knife(int32_t i) {
  if (!run.knife) return 0;
  double m = queued[i].mass;
  if (energy(i) > m * run.gravity * run.trap_height) {
    log_event(EV_KNIFE, plan[i].atom, -1);
    leave_trap(i, GONE);
    return 1;
  }
  return 0;
}

/*
 * Row i's pair event at te, seed Eqs. (10)-(12): the row to predict next (-1 if none) and
 * in *second the other atom, still to pass the knife. A stale event (the partner moved
 * on, or pairs are over) only re-predicts row i.
 */
int32_t pair_event(int32_t i, double te, int32_t *second) {
  int32_t j = plan[i].partner;
  if (run.won || (int32_t)state[j].count != plan[i].partner_count) {
    run.stale++;
    return i;
  }
  int swap = state[j].atom < state[i].atom;
  int32_t lo = swap ? j : i, hi = swap ? i : j;
  clock_to(te);
  move(lo);
  move(hi);
  State *sl = &state[lo], *sh = &state[hi];
  collide_pair(sh->x - sl->x, sh->y - sl->y, sl, queued[lo].mass, sh, queued[hi].mass);
  run.pairs++;
  sl->count += 1;
  sh->count += 1;
  log_event(EV_PAIR, plan[lo].atom, plan[hi].atom);
  *second = hi;
  return knife(lo) ? -1 : lo;
}

/* Row i meets the wall at te: escape over the rim (SPEC 2.3, -1) or bounce (i). */
int32_t wall_event(int32_t i, double te) {
  clock_to(te);
  move(i);
  State *s = &state[i];
  if (__builtin_fabs(s->x) > run.x_rim) {
    log_event(EV_ESCAPE, plan[i].atom, -1);
    leave_trap(i, ESCAPED);
    return -1;
  }
  double vx = s->vx, vy = s->vy;
  double speed = __builtin_sqrt(vx * vx + vy * vy);
  int damped = run.won && speed >= WIN_DAMPING_MIN_SPEED; /* seed Eq. (34) */
  int changes = damped || speed < WALL_MIN_NORMAL_SPEED;
  if (changes) run.energy_sum -= energy(i);
  if (damped)
    settle_wall(s, run.curvature, 1.0 - WIN_DAMPING, WIN_NORMAL_SPEED_FLOOR);
  else
    bounce_wall(s, run.curvature, WALL_MIN_NORMAL_SPEED);
  if (changes) run.energy_sum += energy(i);
  run.walls++;
  s->count += 1;
  log_event(EV_WALL, plan[i].atom, -1);
  return i;
}

/* Escaped row i leaves the window at te: gone. */
void exit_event(int32_t i, double te) {
  clock_to(te);
  move(i);
  plan[i].status = GONE;
  state[i].count += 1;
  log_event(EV_GONE, plan[i].atom, -1);
}

/*
 * Row i crosses into the next cell at te (kind: KIND_CROSS_X or KIND_CROSS_Y). Only the
 * row or column of cells that came within reach needs a scan: pairs with the other
 * neighbours are held already. 1 if the real event stands (only the crossing to predict).
 */
int32_t crossing_event(int32_t i, double te, int32_t kind) {
  run.crossings++;
  if (run.won) return 0; /* the grid is no longer kept once the gas has condensed */
  Plan *p = &plan[i];
  int32_t cx = p->cell_x, cy = p->cell_y, to = p->cross_to;
  unlink(i);
  if (kind == KIND_CROSS_X) {
    link(i, to, cy);
    int32_t c = 2 * to - cx;
    if (c >= 0 && c < run.nx)
      scan(i, c, c, cy > 0 ? cy - 1 : 0, cy < run.ny - 1 ? cy + 1 : run.ny - 1);
  } else {
    link(i, cx, to);
    queued[i].arc_cross_t = te;
    int32_t c = 2 * to - cy;
    if (c >= 0 && c < run.ny)
      scan(i, cx > 0 ? cx - 1 : 0, cx < run.nx - 1 ? cx + 1 : run.nx - 1, c, c);
  }
  return 1;
}
