/*
 * Reading the tables by World index, and the scalars, for the TypeScript wrapper
 * (web/src/physics/wasm.ts, src/evapcool/physics/_coremodule.c); the tables themselves are
 * declared in tables.h, the entry points in evapcool_core.h.
 */
#include "tables.h"

int32_t core_status_of(Core *core, int32_t a) { return core->plan[core->row_of[a]].status; }

/* Stored value k of World atom a: 0 x, 1 y, 2 vx, 3 vy, 4 t, 5 radius, 6 mass. */
double core_stored_of(Core *core, int32_t a, int32_t k) {
  int32_t r = core->row_of[a];
  const State *s = &core->state[r];
  switch (k) {
  case 0: return s->x;
  case 1: return s->y;
  case 2: return s->vx;
  case 3: return s->vy;
  case 4: return s->t;
  case 5: return s->radius;
  default: return core->queued[r].mass;
  }
}

/* World atom a's energy 1/2 m v^2 + m g y from its stored state (conserved in flight). */
double core_atom_energy(Core *core, int32_t a) { return energy(core, core->row_of[a]); }

/* The atoms of this status at time t as eight columns (the page's snapshot: one call, not
 * five per atom). */
int32_t core_snapshot(Core *core, int32_t status, double t, double *out) {
  const int32_t n = core->run.n_atoms;
  const double g = core->run.gravity;
  int32_t k = 0;
  for (int32_t a = 0; a < n; a++) {
    const int32_t r = core->row_of[a];
    if (core->plan[r].status != status) continue;
    const State *s = &core->state[r];
    const double dt = t - s->t; /* carried to t in free flight */
    const double row[8] = {a, flight_x(s->x, s->vx, dt), flight_y(s->y, s->vy, 0.5 * g, dt),
                           s->vx, flight_vy(s->vy, g, dt), s->radius, core->queued[r].mass,
                           energy(core, r)};
    for (int32_t c = 0; c < 8; c++) out[c * n + k] = row[c];
    k++;
  }
  return k;
}

/* Sum of trapped energies added in World index order (the engines continue it). */
double core_sequential_energy_sum(Core *core) {
  double total = 0.0;
  for (int32_t a = 0; a < core->run.n_atoms; a++)
    if (core_status_of(core, a) == TRAPPED) total += core_atom_energy(core, a);
  return total;
}

void core_force_win(Core *core) { core->run.won = 1; }
LogLine *core_log_address(Core *core) { return core->event_log; }
/* The log was copied out: start it again. */
void core_log_clear(Core *core) { core->run.n_log = 0; }

/* The scalars, by name. */
#define READ(type, field) \
  type core_##field(const Core *core) { return core->run.field; }
READ(double, time)
READ(double, energy_sum)
READ(double, x_rim)
READ(double, trap_height)
READ(int32_t, won)
READ(int32_t, n_trapped)
READ(double, pairs)
READ(double, walls)
READ(double, crossings)
READ(double, stale)
READ(int32_t, n_log)
READ(int32_t, nx)
READ(int32_t, ny)
READ(double, cell)
READ(double, skin)
READ(int32_t, score)
READ(double, win_frame)

/* Every atom's stored state by World index into the caller's arrays (Python's World). */
void core_export_states(Core *core, double *pos, double *vel, double *t, int8_t *status,
                        int64_t *counter) {
  for (int32_t a = 0; a < core->run.n_atoms; a++) {
    int32_t r = core->row_of[a];
    const State *s = &core->state[r];
    pos[2 * a] = s->x;
    pos[2 * a + 1] = s->y;
    vel[2 * a] = s->vx;
    vel[2 * a + 1] = s->vy;
    t[a] = s->t;
    status[a] = (int8_t)core->plan[r].status;
    counter[a] = s->count;
  }
}
