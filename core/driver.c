/*
 * The entry points: the event loop, setting up, renumbering the rows in cell order.
 *
 * The loop processes events in the reference engine's order (physics/reference.py), event
 * for event. It returns to the caller when the log buffer is nearly full, before the next
 * event, and the caller calls it again after emptying the buffer: the run goes on exactly
 * as if never stopped.
 */
#include "tables.h"

/* Rows are put in cell order, and the calendar's bins fitted, every this many events per atom. */
#define RENUMBER_EVENTS_PER_ATOM 32
/* The most log lines one event writes (a pair and two knives), with room to spare. */
#define LOG_ROOM 4

/* Row i's event kind: its crossing if that is what is filed, else its real event. */
static inline int32_t event_kind(Core *core, int32_t i) {
  const Plan *p = &core->plan[i];
  return p->rank == RANK_CROSS ? p->cross_axis : p->real_kind;
}

/* Predictions after an event: the first row's (full, or only its crossing), then the
 * second row's (a pair's higher atom) after its knife test. */
static void repredict(Core *core, int32_t first, int full, int32_t second) {
  if (first >= 0) {
    if (full) predict_real(core, first);
    predict_crossing(core, first);
    set_key(core, first);
  }
  if (second >= 0 && !knife(core, second)) predict(core, second);
}

#ifndef CORE_LOOKAHEAD
/*
 * Touch the lines of the rows of the next few events (the heap's root's children) while
 * this event is processed (speed only: nothing read changes a result). WebAssembly has no
 * prefetch instruction, but a load nobody waits for lets the CPU fetch the lines in the
 * shadow of the work. Measured faster at every size (docs/benchmarks.md).
 */
static volatile double touch_sink; /* where the touches land: a read the compiler must keep */
static inline int32_t touch_ahead(Core *core) {
  int32_t end = core->run.heap_size < 5 ? core->run.heap_size : 5;
  for (int32_t p = 1; p < end; p++) {
    int32_t r = core->heap[p].row;
    touch_sink = core->state[r].x + core->queued[r].real_t + core->plan[r].cell_x;
  }
  return -1;
}
#define look_before(core, i, kind, after) (*(after) = -1, touch_ahead(core))
#define look_after(core, next, after) ((void)(next), (void)(after))
#define LOOKING(core) 1
#else
/* Below this many atoms the tables sit in the caches and asking ahead only costs time
 * (4 % slower at 1 000 atoms, docs/benchmarks.md). */
#define LOOK_MIN_ATOMS 5000
#define LOOKING(core) ((core)->run.n_atoms >= LOOK_MIN_ATOMS)
#endif

/* Process every event with time <= t_end in key order, then set the clock. */
int32_t core_advance_to(Core *core, double t_end) {
  for (;;) {
    if (core->run.record && core->run.n_log + LOG_ROOM > core->run.log_capacity) return CORE_LOG_FULL;
    if (++core->run.since_maintain > core->run.maintain_every) {
      core->run.since_maintain = 0;
      if (core->run.won)
        calendar_rebuild(core, core->run.time);
      else
        renumber(core);
    }
    int32_t i = calendar_top(core);
    if (i < 0) break;
    double te = core->queued[i].key_t;
    if (!(te <= t_end)) break;
    int32_t kind = event_kind(core, i);
    int32_t after = -1;
    int32_t next = LOOKING(core) ? look_before(core, i, kind, &after) : -1;
    int32_t first = i, second = -1, full = 1;
    if (kind == KIND_PAIR)
      first = pair_event(core, i, te, &second);
    else if (kind == KIND_CROSS_X || kind == KIND_CROSS_Y)
      full = !crossing_event(core, i, te, kind);
    else if (kind == KIND_WALL)
      first = wall_event(core, i, te);
    else if (kind == KIND_EXIT)
      exit_event(core, i, te);
    else
      break;
    if (LOOKING(core)) look_after(core, next, after);
    repredict(core, first, full, second);
  }
  core->run.time = t_end;
  return CORE_DONE;
}

/* Put trapped rows in their cells (positions now), predict every row, file the keys. */
static void setup(Core *core) {
  const double half_g = 0.5 * core->run.gravity, now = core->run.time;
  for (int32_t r = 0; r < core->run.n_atoms; r++) {
    if (core->plan[r].status != TRAPPED) continue;
    const State *s = &core->state[r];
    double dt = now - s->t;
    double x = flight_x(s->x, s->vx, dt);
    double y = flight_y(s->y, s->vy, half_g, dt);
    cell_link(core, r, cell_of(core, x, core->run.grid_x0, core->run.nx), cell_of(core, y, core->run.grid_y0, core->run.ny));
  }
  for (int32_t r = 0; r < core->run.n_atoms; r++) {
    predict_real(core, r);
    predict_crossing(core, r);
    load_key(core, r);
  }
  calendar_rebuild(core, now);
  core->run.since_maintain = 0;
}

/* Order of the rows: the cells' rows in cell order (row-major), then the others; sets
 * row_of (World atom -> new row) and returns how many rows are in cells. */
static int32_t cell_order(Core *core) {
  const int32_t n = core->run.n_atoms;
  int32_t k = 0;
  for (int32_t cy = 0; cy < core->run.ny; cy++)
    for (int32_t cx = 0; cx < core->run.nx; cx++)
      for (int32_t j = core->cells[cell_index(core, cx, cy)]; j >= 0; j = core->state[j].next)
        core->order[k++] = j;
  int32_t linked = k;
  for (int32_t r = 0; r < n; r++) core->row_of[core->plan[r].atom] = -1;
  for (int32_t q = 0; q < linked; q++) core->row_of[core->plan[core->order[q]].atom] = q;
  for (int32_t r = 0; r < n; r++)
    if (core->row_of[core->plan[r].atom] < 0) core->order[k++] = r;
  for (int32_t q = linked; q < n; q++) core->row_of[core->plan[core->order[q]].atom] = q;
  return linked;
}

/*
 * Renumber the rows in cell order, the atoms off the grid last: the atoms of neighbouring
 * cells then sit next to each other in memory and the pair scans stay in the caches.
 * Events, their keys (World indices) and so the event order are unchanged.
 */
void renumber(Core *core) {
  const int32_t n = core->run.n_atoms;
  int32_t linked = cell_order(core);
  for (int32_t q = 0; q < n; q++) {
    int32_t o = core->order[q];
    core->state2[q] = core->state[o];
    core->queued2[q] = core->queued[o];
    core->plan2[q] = core->plan[o];
  }
  /* Partners are rows: relabel them (the old row's World index, then its new row). */
  for (int32_t q = 0; q < n; q++)
    if (core->plan2[q].real_kind == KIND_PAIR) core->plan2[q].partner = core->row_of[core->plan[core->plan2[q].partner].atom];
  State *s = core->state;
  Queued *u = core->queued;
  Plan *p = core->plan;
  core->state = core->state2;
  core->queued = core->queued2;
  core->plan = core->plan2;
  core->state2 = s;
  core->queued2 = u;
  core->plan2 = p;
  /* Cell lists: linking in descending row order leaves each list ascending. */
  for (int32_t cy = 0; cy < core->run.ny; cy++)
    for (int32_t cx = 0; cx < core->run.nx; cx++) core->cells[cell_index(core, cx, cy)] = -1;
  for (int32_t q = 0; q < n; q++) core->state[q].next = -1;
  for (int32_t q = linked - 1; q >= 0; q--) cell_link(core, q, core->plan[q].cell_x, core->plan[q].cell_y);
  for (int32_t q = 0; q < n; q++) load_key(core, q);
  calendar_rebuild(core, core->run.time);
}

/* New rim height; with the knife rule, atoms above m g H go at once, in index order. */
void core_set_trap_height(Core *core, double height) {
  core->run.trap_height = height;
  core->run.x_rim = __builtin_sqrt(height / core->run.curvature);
  if (!core->run.knife) return;
  for (int32_t a = 0; a < core->run.n_atoms; a++) {
    int32_t r = core->row_of[a];
    if (core->plan[r].status == TRAPPED) knife(core, r);
  }
}

/* The tables of n atoms; returns the inputs' place: x, y, vx, vy, t, radius, mass (n
 * doubles each), then the status (n int32), or 0 if the memory cannot hold them. The
 * wrapper fills them, then calls load. */
double *core_allocate(Core *core, int32_t n, int32_t log_capacity) {
  core->run.n_atoms = n;
  core->state = core_take(core, sizeof(State) * n);
  core->queued = core_take(core, sizeof(Queued) * n);
  core->plan = core_take(core, sizeof(Plan) * n);
  core->state2 = core_take(core, sizeof(State) * n);
  core->queued2 = core_take(core, sizeof(Queued) * n);
  core->plan2 = core_take(core, sizeof(Plan) * n);
  core->heap = core_take(core, sizeof(HeapEntry) * n);
  core->filing = core_take(core, sizeof(Filing) * n);
  core->order = core_take(core, sizeof(int32_t) * n);
  core->row_of = core_take(core, sizeof(int32_t) * n);
  core->tc_table = core_take(core, sizeof(double) * (n + 1));
  core->scratch = core_take(core, sizeof(double) * (n + 1));
  core->run.log_capacity = log_capacity;
  core->event_log = core_take(core, sizeof(LogLine) * log_capacity);
  core->play.moves = core_take(core, sizeof(double) * 2 * CORE_MOVES_CAPACITY);
  core->play.asked = NAN;
  calendar_init(core, n);
  core->bins = core_take(core, sizeof(int32_t) * (core->run.n_bins + 2));
  double *inputs = core_take(core, sizeof(double) * 8 * n);
  core->inputs = inputs;
  return core->out_of_memory ? 0 : inputs;
}

/* Copy the inputs into the tables and set the fixed parameters and the clock. */
void core_load(Core *core, const double *inputs, double gravity, double curvature, double x_left,
                       double x_right, double y_bottom, int32_t knife_rule, int32_t win_rule,
                       int32_t record, double time, int32_t won, double pairs, double walls) {
  const int32_t n = core->run.n_atoms;
  const int32_t *status = (const int32_t *)(inputs + 7 * n);
  core->run.gravity = gravity;
  core->run.curvature = curvature;
  core->run.x_left = x_left;
  core->run.x_right = x_right;
  core->run.y_bottom = y_bottom;
  core->run.knife = knife_rule;
  core->run.win_rule = win_rule;
  core->run.record = record;
  core->run.time = time;
  core->run.won = won;
  core->run.score = -1; /* the game fixes it at the end of the frame the win is seen */
  core->run.pairs = pairs;
  core->run.walls = walls;
  core->run.n_trapped = 0;
  for (int32_t i = 0; i < n; i++) {
    State *s = &core->state[i];
    s->x = inputs[i];
    s->y = inputs[n + i];
    s->vx = inputs[2 * n + i];
    s->vy = inputs[3 * n + i];
    s->t = inputs[4 * n + i];
    s->radius = inputs[5 * n + i];
    s->atom = i;
    s->next = -1;
    core->queued[i].mass = inputs[6 * n + i];
    core->queued[i].arc_cross_t = -INF;
    core->plan[i].status = status[i];
    core->plan[i].atom = i;
    core->plan[i].cell_prev = -1;
    core->row_of[i] = i;
    if (status[i] == TRAPPED) core->run.n_trapped++;
  }
}

/* The grid, the cells and every prediction; the energy sum and the Tc table are set. 0 if
 * the memory cannot hold the cells. */
int32_t core_start(Core *core, double energy_sum, double trap_height) {
  core->run.energy_sum = energy_sum;
  core->run.trap_height = trap_height;
  core->run.x_rim = __builtin_sqrt(trap_height / core->run.curvature);
  core->run.maintain_every = RENUMBER_EVENTS_PER_ATOM * core->run.n_atoms;
  int32_t nc = grid_shape(core);
  int32_t *cells = core_take(core, sizeof(int32_t) * nc);
  double *edges = core_take(core, sizeof(double) * 2 * (core->run.nx + core->run.ny));
  if (core->out_of_memory) return 0;
  grid_edges(core, edges);
  for (int32_t c = 0; c < nc; c++) cells[c] = -1;
  core->cells = cells + core->run.stride + 1; /* cell (0, 0), inside the border */
  setup(core);
  return 1;
}
