/*
 * The entry points (twin of driver.py): the event loop, setting up, renumbering the rows
 * in cell order, and what the TypeScript wrapper (web/src/physics/wasm.ts) reads.
 *
 * The loop mirrors web/src/physics/engine.ts's advanceTo event for event. It returns to
 * the wrapper when the log buffer is nearly full, before the next event, and the wrapper
 * calls it again after emptying the buffer: the run goes on exactly as if never stopped.
 */
#include "tables.h"

/* Rows are put in cell order, and the calendar's bins fitted, every this many events per atom. */
#define RENUMBER_EVENTS_PER_ATOM 8
/* The most log lines one event writes (a pair and two knives), with room to spare. */
#define LOG_ROOM 4

Run run;
State *state;
Queued *queued;
Plan *plan;
HeapEntry *heap;
int32_t *bins;
int32_t *cells;
int32_t *row_of;
double *tc_table;
LogLine *event_log;
/* Spare tables for renumbering (swapped with the live ones) and its order. */
static State *state2;
static Queued *queued2;
static Plan *plan2;
static int32_t *order;

/* The event loop's result: every event up to t_end done, or the log to be emptied first. */
enum { DONE = 0, LOG_FULL = 1 };

/* Row i's event kind: its crossing if that is what is filed, else its real event. */
static inline int32_t event_kind(int32_t i) {
  const Plan *p = &plan[i];
  return p->rank == RANK_CROSS ? p->cross_axis : p->real_kind;
}

/* Predictions after an event: the first row's (full, or only its crossing), then the
 * second row's (a pair's higher atom) after its knife test. */
static void repredict(int32_t first, int full, int32_t second) {
  if (first >= 0) {
    if (full) predict_real(first);
    predict_crossing(first);
    set_key(first);
  }
  if (second >= 0 && !knife(second)) predict(second);
}

/* Where the touches below land: a read the compiler must keep. */
static volatile double touch_sink;

/*
 * Ask for the lines of the rows of the next few events (the heap's root's children) while
 * this event is processed: wasm has no prefetch instruction, but a load nobody waits for
 * lets the CPU fetch them in the shadow of the work (physics/fast/lookahead.py's idea).
 * Measured faster at every size on a shared machine (docs/benchmarks.md), so always on.
 */
static inline void touch_ahead(void) {
  int32_t end = run.heap_size < 5 ? run.heap_size : 5;
  for (int32_t p = 1; p < end; p++) {
    int32_t r = heap[p].row;
    touch_sink = state[r].x + queued[r].real_t + plan[r].cell_x;
  }
}

/* Process every event with time <= t_end in key order, then set the clock. */
EXPORT(advance_to) int32_t advance_to(double t_end) {
  for (;;) {
    if (run.record && run.n_log + LOG_ROOM > run.log_capacity) return LOG_FULL;
    if (++run.since_maintain > run.maintain_every) {
      run.since_maintain = 0;
      if (run.won)
        calendar_rebuild(run.time);
      else
        renumber();
    }
    int32_t i = calendar_top();
    if (i < 0) break;
    double te = queued[i].key_t;
    if (!(te <= t_end)) break;
    touch_ahead();
    int32_t kind = event_kind(i);
    int32_t first = i, second = -1, full = 1;
    if (kind == KIND_PAIR)
      first = pair_event(i, te, &second);
    else if (kind == KIND_CROSS_X || kind == KIND_CROSS_Y)
      full = !crossing_event(i, te, kind);
    else if (kind == KIND_WALL)
      first = wall_event(i, te);
    else if (kind == KIND_EXIT)
      exit_event(i, te);
    else
      break;
    repredict(first, full, second);
  }
  run.time = t_end;
  return DONE;
}

/* Put trapped rows in their cells (positions now), predict every row, file the keys. */
static void setup(void) {
  const double half_g = 0.5 * run.gravity, now = run.time;
  for (int32_t r = 0; r < run.n_atoms; r++) {
    if (plan[r].status != TRAPPED) continue;
    const State *s = &state[r];
    double dt = now - s->t;
    double x = flight_x(s->x, s->vx, dt);
    double y = flight_y(s->y, s->vy, half_g, dt);
    link(r, cell_of(x, run.grid_x0, run.nx), cell_of(y, run.grid_y0, run.ny));
  }
  for (int32_t r = 0; r < run.n_atoms; r++) {
    predict_real(r);
    predict_crossing(r);
    load_key(r);
  }
  calendar_rebuild(now);
  run.since_maintain = 0;
}

/* Order of the rows: the cells' rows in cell order (row-major), then the others; sets
 * row_of (World atom -> new row) and returns how many rows are in cells. */
static int32_t cell_order(void) {
  const int32_t n = run.n_atoms, nc = run.n_cells;
  int32_t k = 0;
  for (int32_t c = 0; c < nc; c++)
    for (int32_t j = cells[c]; j >= 0; j = cells[nc + j]) order[k++] = j;
  int32_t linked = k;
  for (int32_t r = 0; r < n; r++) row_of[plan[r].atom] = -1;
  for (int32_t q = 0; q < linked; q++) row_of[plan[order[q]].atom] = q;
  for (int32_t r = 0; r < n; r++)
    if (row_of[plan[r].atom] < 0) order[k++] = r;
  for (int32_t q = linked; q < n; q++) row_of[plan[order[q]].atom] = q;
  return linked;
}

/*
 * Renumber the rows in cell order, the atoms off the grid last: the atoms of neighbouring
 * cells then sit next to each other in memory and the pair scans stay in the caches.
 * Events, their keys (World indices) and so the event order are unchanged.
 */
void renumber(void) {
  const int32_t n = run.n_atoms;
  int32_t linked = cell_order();
  for (int32_t q = 0; q < n; q++) {
    int32_t o = order[q];
    state2[q] = state[o];
    queued2[q] = queued[o];
    plan2[q] = plan[o];
  }
  /* Partners are rows: relabel them (the old row's World index, then its new row). */
  for (int32_t q = 0; q < n; q++)
    if (plan2[q].real_kind == KIND_PAIR) plan2[q].partner = row_of[plan[plan2[q].partner].atom];
  State *s = state;
  Queued *u = queued;
  Plan *p = plan;
  state = state2;
  queued = queued2;
  plan = plan2;
  state2 = s;
  queued2 = u;
  plan2 = p;
  /* Cell lists: linking in descending row order leaves each list ascending. */
  for (int32_t c = 0; c < run.n_cells + n; c++) cells[c] = -1;
  for (int32_t q = linked - 1; q >= 0; q--) link(q, plan[q].cell_x, plan[q].cell_y);
  for (int32_t q = 0; q < n; q++) load_key(q);
  calendar_rebuild(run.time);
  run.renumbered++;
}

/* New rim height; with the knife rule, atoms above m g H go at once, in index order. */
EXPORT(set_trap_height) void set_trap_height(double height) {
  run.trap_height = height;
  run.x_rim = __builtin_sqrt(height / run.curvature);
  if (!run.knife) return;
  for (int32_t a = 0; a < run.n_atoms; a++) {
    int32_t r = row_of[a];
    if (plan[r].status == TRAPPED) knife(r);
  }
}

/* -- memory: a bump allocator over the instance's own memory (one engine per instance) -- */
extern unsigned char __heap_base;
static uintptr_t heap_top = (uintptr_t)&__heap_base;

/* Set when the memory could not grow: the wrapper then reports it (RangeError). */
static int32_t out_of_memory;

/* n bytes on a 64-byte line, zeroed (fresh pages are); scratch page 0 if none are left. */
static void *take(uintptr_t bytes) {
  uintptr_t at = (heap_top + 63) & ~(uintptr_t)63;
  uintptr_t have = __builtin_wasm_memory_size(0) * 65536;
  if (out_of_memory || bytes > 0xffffffffu - at) {
    out_of_memory = 1;
    return 0;
  }
  if (at + bytes > have) {
    uintptr_t pages = (at + bytes - have + 65535) / 65536;
    if (__builtin_wasm_memory_grow(0, pages) == (uintptr_t)-1) {
      out_of_memory = 1;
      return 0;
    }
  }
  heap_top = at + bytes;
  return (void *)at;
}

/* The tables of n atoms; returns the inputs' place: x, y, vx, vy, t, radius, mass (n
 * doubles each), then the status (n int32), or 0 if the memory cannot hold them. The
 * wrapper fills them, then calls load. */
EXPORT(allocate) double *allocate(int32_t n, int32_t log_capacity) {
  run.n_atoms = n;
  state = take(sizeof(State) * n);
  queued = take(sizeof(Queued) * n);
  plan = take(sizeof(Plan) * n);
  state2 = take(sizeof(State) * n);
  queued2 = take(sizeof(Queued) * n);
  plan2 = take(sizeof(Plan) * n);
  heap = take(sizeof(HeapEntry) * n);
  order = take(sizeof(int32_t) * n);
  row_of = take(sizeof(int32_t) * n);
  tc_table = take(sizeof(double) * (n + 1));
  run.log_capacity = log_capacity;
  event_log = take(sizeof(LogLine) * log_capacity);
  calendar_init(n);
  bins = take(sizeof(int32_t) * (run.n_bins + 2));
  double *inputs = take(sizeof(double) * 8 * n);
  return out_of_memory ? 0 : inputs;
}

/* Copy the inputs into the tables and set the fixed parameters and the clock. */
EXPORT(load) void load(const double *in, double gravity, double curvature, double x_left,
                       double x_right, double y_bottom, int32_t knife_rule, int32_t win_rule,
                       int32_t record, double time, int32_t won, double pairs, double walls) {
  const int32_t n = run.n_atoms;
  const int32_t *status = (const int32_t *)(in + 7 * n);
  run.gravity = gravity;
  run.curvature = curvature;
  run.x_left = x_left;
  run.x_right = x_right;
  run.y_bottom = y_bottom;
  run.knife = knife_rule;
  run.win_rule = win_rule;
  run.record = record;
  run.time = time;
  run.won = won;
  run.pairs = pairs;
  run.walls = walls;
  run.n_trapped = 0;
  for (int32_t i = 0; i < n; i++) {
    State *s = &state[i];
    s->x = in[i];
    s->y = in[n + i];
    s->vx = in[2 * n + i];
    s->vy = in[3 * n + i];
    s->t = in[4 * n + i];
    s->radius = in[5 * n + i];
    s->atom = i;
    queued[i].mass = in[6 * n + i];
    queued[i].arc_cross_t = -INF;
    plan[i].status = status[i];
    plan[i].atom = i;
    plan[i].cell_prev = -1;
    row_of[i] = i;
    if (status[i] == TRAPPED) run.n_trapped++;
  }
}

/* The grid, the cells and every prediction; the energy sum and the Tc table are set. 0 if
 * the memory cannot hold the cells. */
EXPORT(start) int32_t start(double energy_sum, double trap_height) {
  run.energy_sum = energy_sum;
  run.trap_height = trap_height;
  run.x_rim = __builtin_sqrt(trap_height / run.curvature);
  run.maintain_every = RENUMBER_EVENTS_PER_ATOM * run.n_atoms;
  int32_t nc = grid_shape();
  cells = take(sizeof(int32_t) * (nc + run.n_atoms));
  if (out_of_memory) return 0;
  for (int32_t c = 0; c < nc + run.n_atoms; c++) cells[c] = -1;
  setup();
  return 1;
}
