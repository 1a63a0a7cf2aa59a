/*
 * What each event does, as the reference engine (physics/reference.py) does it: one handler per event kind, the clock, the
 * log, the win rule and leaving the trap.
 */
#include "tables.h"


/* Carry row i's stored state to the clock (exact free flight, seed Eqs. 3-4). */
void fly_to_clock(Core *core, int32_t i) {
  State *s = &core->state[i];
  double t = core->run.time;
  double dt = t - s->t;
  s->x = flight_x(s->x, s->vx, dt);
  s->y = flight_y(s->y, s->vy, 0.5 * core->run.gravity, dt);
  s->vy = flight_vy(s->vy, core->run.gravity, dt);
  s->t = t;
  core->queued[i].arc_cross_t = -INF; /* a new arc: none of its y crossings taken yet */
}

/* Log an event at the clock's time (World indices; b = -1 for solo events). */
static void log_event(Core *core, int32_t kind, int32_t a, int32_t b) {
  if (!core->run.record) return;
  LogLine *l = &core->event_log[core->run.n_log++];
  l->kind = kind;
  l->a = a;
  l->b = b;
  l->t = core->run.time;
}

/* The clock to the event's time (never back: an event due in the past happens now). */
static void clock_to(Core *core, double te) { core->run.time = te >= core->run.time ? te : core->run.time; }

/* T < Tc(N) with the running energy sum (seed Eqs. 1 and 46), latched. */
static void check_win(Core *core) {
  int32_t n = core->run.n_trapped;
  if (core->run.won || n == 0 || !core->run.win_rule) return;
  if (core->run.energy_sum / n < core->tc_table[n]) core->run.won = 1;
}

/* Row i leaves the trapped set (over the rim or by the knife). */
static void leave_trap(Core *core, int32_t i, int32_t status) {
  core->plan[i].status = status;
  core->run.n_trapped--;
  core->run.energy_sum -= energy(core, i);
  core->state[i].count += 1;
  cell_unlink(core, i);
  predict(core, i);
  check_win(core);
}

/* Remove trapped row i now if its energy exceeds m g H; 1 if removed. */
int32_t knife(Core *core, int32_t i) {
  if (!core->run.knife) return 0;
  double m = core->queued[i].mass;
  if (energy(core, i) > m * core->run.gravity * core->run.trap_height) {
    log_event(core, EV_KNIFE, core->plan[i].atom, -1);
    leave_trap(core, i, GONE);
    return 1;
  }
  return 0;
}

/*
 * Row i's pair event at te, seed Eqs. (10)-(12): the row to predict next (-1 if none) and
 * in *second the other atom, still to pass the knife. A stale event (the partner moved
 * on, or pairs are over) only re-predicts row i.
 */
int32_t pair_event(Core *core, int32_t i, double te, int32_t *second) {
  int32_t j = core->plan[i].partner;
  if (core->run.won || (int32_t)core->state[j].count != core->plan[i].partner_count) {
    core->run.stale++;
    return i;
  }
  int swap = core->state[j].atom < core->state[i].atom;
  int32_t lo = swap ? j : i, hi = swap ? i : j;
  clock_to(core, te);
  fly_to_clock(core, lo);
  fly_to_clock(core, hi);
  State *sl = &core->state[lo], *sh = &core->state[hi];
  collide_pair(sh->x - sl->x, sh->y - sl->y, sl, core->queued[lo].mass, sh, core->queued[hi].mass);
  core->run.pairs++;
  sl->count += 1;
  sh->count += 1;
  log_event(core, EV_PAIR, core->plan[lo].atom, core->plan[hi].atom);
  *second = hi;
  return knife(core, lo) ? -1 : lo;
}

/* Row i meets the wall at te: escape over the rim (SPEC 2.3, -1) or bounce (i). */
int32_t wall_event(Core *core, int32_t i, double te) {
  clock_to(core, te);
  fly_to_clock(core, i);
  State *s = &core->state[i];
  if (__builtin_fabs(s->x) > core->run.x_rim) {
    log_event(core, EV_ESCAPE, core->plan[i].atom, -1);
    leave_trap(core, i, ESCAPED);
    return -1;
  }
  double vx = s->vx, vy = s->vy;
  double speed = __builtin_sqrt(vx * vx + vy * vy);
  int damped = core->run.won && speed >= WIN_DAMPING_MIN_SPEED; /* seed Eq. (34) */
  int changes = damped || speed < WALL_MIN_NORMAL_SPEED;
  if (changes) core->run.energy_sum -= energy(core, i);
  if (damped)
    settle_wall(s, core->run.curvature, 1.0 - WIN_DAMPING, WIN_NORMAL_SPEED_FLOOR);
  else
    bounce_wall(s, core->run.curvature, WALL_MIN_NORMAL_SPEED);
  if (changes) core->run.energy_sum += energy(core, i);
  core->run.walls++;
  s->count += 1;
  log_event(core, EV_WALL, core->plan[i].atom, -1);
  return i;
}

/* Escaped row i leaves the window at te: gone. */
void exit_event(Core *core, int32_t i, double te) {
  clock_to(core, te);
  fly_to_clock(core, i);
  core->plan[i].status = GONE;
  core->state[i].count += 1;
  log_event(core, EV_GONE, core->plan[i].atom, -1);
}

/*
 * Row i crosses into the next cell at te (kind: KIND_CROSS_X or KIND_CROSS_Y). Only the
 * row or column of cells that came within reach needs a scan (beyond the grid's edge: its
 * empty border): pairs with the other neighbours are held already. 1 if the real event
 * stands (only the crossing to predict).
 */
int32_t crossing_event(Core *core, int32_t i, double te, int32_t kind) {
  core->run.crossings++;
  if (core->run.won) return 0; /* the grid is no longer kept once the gas has condensed */
  Plan *p = &core->plan[i];
  int32_t cx = p->cell_x, cy = p->cell_y, to = p->cross_to;
  cell_unlink(core, i);
  if (kind == KIND_CROSS_X) {
    cell_link(core, i, to, cy);
    scan_line(core, i, cell_index(core, 2 * to - cx, cy - 1), core->run.stride);
  } else {
    cell_link(core, i, cx, to);
    core->queued[i].arc_cross_t = te;
    scan_line(core, i, cell_index(core, cx - 1, 2 * to - cy), 1);
  }
  return 1;
}
