/*
 * Reading the tables by World index, and the scalars, for the TypeScript wrapper
 * (web/src/physics/wasm.ts); the tables themselves are declared in tables.h.
 */
#include "tables.h"

/* Where state_at writes: x, y, vx, vy. */
static double state_out[4];

EXPORT(status_of) int32_t status_of(int32_t a) { return plan[row_of[a]].status; }

/* Stored value k of World atom a: 0 x, 1 y, 2 vx, 3 vy, 4 t, 5 radius, 6 mass. */
EXPORT(stored_of) double stored_of(int32_t a, int32_t k) {
  int32_t r = row_of[a];
  const State *s = &state[r];
  switch (k) {
  case 0: return s->x;
  case 1: return s->y;
  case 2: return s->vx;
  case 3: return s->vy;
  case 4: return s->t;
  case 5: return s->radius;
  default: return queued[r].mass;
  }
}

/* World atom a's energy 1/2 m v^2 + m g y from its stored state (conserved in flight). */
EXPORT(atom_energy) double atom_energy(int32_t a) { return energy(row_of[a]); }

/* Position and velocity of World atom a carried to time t, into state_out. */
EXPORT(state_at) double *state_at(int32_t a, double t) {
  const State *s = &state[row_of[a]];
  double dt = t - s->t;
  state_out[0] = flight_x(s->x, s->vx, dt);
  state_out[1] = flight_y(s->y, s->vy, 0.5 * run.gravity, dt);
  state_out[2] = s->vx;
  state_out[3] = flight_vy(s->vy, run.gravity, dt);
  return state_out;
}

/* Sum of trapped energies added in World index order (the engines continue it). */
EXPORT(sequential_energy_sum) double sequential_energy_sum(void) {
  double total = 0.0;
  for (int32_t a = 0; a < run.n_atoms; a++)
    if (status_of(a) == TRAPPED) total += atom_energy(a);
  return total;
}

EXPORT(force_win) void force_win(void) { run.won = 1; }
EXPORT(tc_table_address) double *tc_table_address(void) { return tc_table; }
EXPORT(log_address) LogLine *log_address(void) { return event_log; }
/* The log was copied out: start it again. */
EXPORT(log_clear) void log_clear(void) { run.n_log = 0; }

/* The scalars, by name. */
#define READ(type, field) \
  EXPORT(field) type field(void) { return run.field; }
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
READ(double, renumbered)
READ(int32_t, n_log)
READ(int32_t, nx)
READ(int32_t, ny)
READ(double, cell)
