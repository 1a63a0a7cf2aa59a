/*
 * The engine core's tables, written once for both editions: compiled to WebAssembly for the
 * page (web/scripts/wasm-plugin.mjs) and natively as the Python package's extension
 * (setup.py, src/evapcool/physics/_coremodule.c). An engine is a `Core`: its scalars and tables,
 * allocated once at the start (no allocation per event); a process may hold several.
 *
 * The entry points the wrappers call, the constants and the log line are the core's API,
 * declared in evapcool_core.h; this header is the core's inside.
 *
 * Row i of the three per-atom tables belongs to the same atom, but not to atom i of the
 * World: rows are renumbered in cell order now and then (driver.c), and `atom` holds the
 * World index. What orders events or is seen outside (tie breaks, the log, the knife's
 * order) uses that index, never the row.
 */
#ifndef EVAPCOOL_TABLES_H
#define EVAPCOOL_TABLES_H

#include "evapcool_core.h"

#define INF __builtin_inf()
#define NAN __builtin_nan("")
/* Native builds ask for memory ahead of the loop (lookahead.c); -DCORE_NO_LOOKAHEAD turns it
 * off. WebAssembly has no prefetch: there the loop touches the next rows instead. */
#if !defined(__wasm__) && !defined(CORE_NO_LOOKAHEAD)
#define CORE_LOOKAHEAD 1
#endif

/* What the pair scan reads of every neighbour, one 64-byte line. */
typedef struct {
  double x, y, vx, vy; /* stored position (trap coordinates, px) and velocity (px/frame) */
  double t;            /* ... at this time (frames): the atom's own clock */
  double radius;
  int64_t count; /* events so far: a partner's pair event is stale once it moved on */
  int32_t atom;  /* World index */
  int32_t next;  /* the next row in the same cell (-1: the last), read by the scan's walk */
} State;

/* What the event calendar reads: the key time and the times it is chosen from. */
typedef struct {
  double key_t;       /* time the atom is filed under: min(real_t, cross_t) */
  double real_t;      /* time of its real event (pair, wall or exit), inf if none */
  double cross_t;     /* time of its next cell crossing, inf if none */
  double arc_cross_t; /* last y crossing taken on the current arc (-inf: none) */
  double mass;
} Queued;

/* Where the calendar keeps a row (calendar.c). A table of its own, four to a line: moving a
 * bin's list into the heap walks `next` from row to row, and that walk stays in the caches. */
typedef struct {
  int32_t heap_pos; /* place in the heap, -1 if in a list */
  int32_t bin;      /* list it is filed in, -1 if in the heap */
  int32_t next;     /* neighbours in that list, -1 at the ends */
  int32_t prev;
} Filing;

/* The atom's pending events (key parts, kinds, partner) and where it is. */
typedef struct {
  int32_t rank, tie_a, tie_b;            /* the filed key: (key_t, rank, tie_a, tie_b) */
  int32_t real_rank, real_a, real_b;     /* the real event's key parts */
  int32_t real_kind;                     /* KIND_PAIR, KIND_WALL, KIND_EXIT or KIND_NONE */
  int32_t partner;                       /* row of the partner of a pair event */
  int32_t partner_count;                 /* the partner's count then (low 32 bits) */
  int32_t cross_axis;                    /* KIND_CROSS_X, KIND_CROSS_Y or KIND_NONE */
  int32_t cross_to;                      /* cell column (x) or row (y) the crossing enters */
  int32_t status;                        /* TRAPPED, ESCAPED or GONE */
  int32_t cell_x, cell_y;                /* the cell it is filed in (trapped atoms only) */
  int32_t cell_prev;                     /* previous atom in that cell, -1 if first */
  int32_t atom;                          /* World index */
} Plan;

/* An entry of the calendar's heap: a row filed under key time t. */
typedef struct {
  double t;
  int32_t row;
  int32_t pad;
} HeapEntry;

/* The engine's scalars (Python's RUN record). */
typedef struct {
  /* fixed for the engine's life */
  double gravity, curvature;
  double grid_x0, grid_y0, cell; /* cell column 0's left edge, row 0's bottom, cell edge */
  double skin;                   /* an atom is refiled this far past its cell's edge */
  double x_left, x_right, y_bottom; /* window edges (exit bounds before the radius) */
  int32_t nx, ny, n_cells, n_atoms;
  int32_t stride; /* cells from one grid row to the next: nx and a border cell each side */
  int32_t knife, record, win_rule;
  int32_t maintain_every; /* events between two renumberings */
  /* shared with the wrapper */
  double time, energy_sum, x_rim, trap_height;
  int32_t won, n_trapped;
  double pairs, walls;
  /* the game (game.c): atoms trapped at the end of the frame the win was seen (-1 before)
   * and that frame */
  int32_t score;
  double win_frame;
  /* engine-only counts */
  double crossings, stale;
  int32_t since_maintain, n_log, log_capacity;
  /* the event calendar */
  double bin_base, bin_width;
  int64_t bin, scan_bin; /* the current bin (its atoms are in the heap); the last refiling */
  int32_t heap_size, n_bins, n_ring, n_over;
  int64_t walk_bin; /* look-ahead: the bin whose successor's list is being walked ... */
  int32_t walk;     /* ... and the row it has reached (-1: at the end) */
} Run;

/* Event kinds inside the engine. */
enum { KIND_NONE = 0, KIND_PAIR, KIND_WALL, KIND_EXIT, KIND_CROSS_X, KIND_CROSS_Y };
/* Ranks order events of equal time: crossings, then solo events, then pairs. */
enum { RANK_CROSS = -1, RANK_SOLO = 0, RANK_PAIR = 1 };

/* What core_play_to owes at a whole frame it reached (play.c). */
enum { OWED_NONE = 0, OWED_END, OWED_NEXT };

/* The game's clock above the physics (play.c): the height asked for, the moves, a script. */
typedef struct {
  double asked;        /* height asked for, applied at the next whole frame; NaN: none */
  double frames;       /* whole frames played since the start */
  double *moves;       /* (height, frames) runs held up to the win, not yet taken */
  int32_t n_moves;
  int32_t owed;        /* OWED_*: the work of the whole frame reached, not yet done */
  double *script;      /* (height, frames) runs to hold (a recording watched) */
  int32_t script_runs; /* runs of the script; held once all n_script are in (0: none) */
  int32_t n_script, script_capacity;
  int32_t script_run;  /* the run holding the frame starting now, and the frames ... */
  double script_used;  /* ... of it already held */
} Play;

/* One engine: its scalars and tables (no globals, so a process may hold several). */
struct Core {
  Run run;
  Play play;
  State *state;
  Queued *queued;
  Plan *plan;
  HeapEntry *heap;
  Filing *filing;     /* by row, reset whenever the calendar is rebuilt (not renumbered) */
  int32_t *bins;      /* first row of each list: n_bins ring lists, overflow, no event */
  int32_t *cells;     /* first row of each cell, at cy * stride + cx; state[].next goes on. A
                       * border of cells that stay empty rings the grid, so a scan of the
                       * cells around any cell needs no clamping to the grid's edges. */
  int32_t *row_of;    /* row of every World atom */
  double *edge_x;     /* where an atom filed in column c is refiled: edge_x[2c] on the left, */
  double *edge_y;     /* edge_x[2c + 1] on the right, a skin out (rows: edge_y, below, above) */
  double *tc_table;   /* critical temperature for every atom count, seed Eq. (46) */
  LogLine *event_log;
  /* spare tables for renumbering (swapped with the live ones) and its order */
  State *state2;
  Queued *queued2;
  Plan *plan2;
  int32_t *order;
  double *inputs;     /* where the caller writes the atoms before load() */
  double *scratch;    /* n + 1 doubles for the trapped atoms' energies (game.c) */
  int32_t out_of_memory;
  /* every block taken (memory.c frees them with the engine) */
  void *blocks[32];
  int32_t n_blocks;
};

/* The pair scan tests two neighbours at once, natively (SSE2, NEON) and in WebAssembly (its
 * 128-bit SIMD, -msimd128); a build without either tests one at a time. */
#if defined(__SSE2__) || defined(__ARM_NEON) || defined(__wasm_simd128__)
#define CORE_LANES 1
/* Two lanes of doubles: every lane rounds as the scalar operation does (IEEE;
 * -ffp-contract=off leaves no fused multiply-add). */
typedef double v2d __attribute__((vector_size(16)));
typedef int64_t v2m __attribute__((vector_size(16)));
static inline v2d lane_pick(v2m m, v2d a, v2d b) { return (v2d)((m & (v2m)a) | (~m & (v2m)b)); }

/* A scanning row's state, the same in both lanes (kernels.c: pair_contact_times). */
typedef struct {
  v2d t, x, y, vx, vy, r, half_g, g;
} PairSide;
#endif

/* kernels.c */
double flight_x(double x, double vx, double dt);
double flight_y(double y, double vy, double half_g, double dt);
double flight_vy(double vy, double g, double dt);
double atom_energy_of(double m, double y, double vx, double vy, double g);
double pair_contact_time(const State *p, const State *q, double sigma, double g, double beat);
#ifdef CORE_LANES
int32_t pair_contact_times(const State *p, const State *q0, const State *q1, double g, double beat,
                           double slack, double t[2]);
#endif
double wall_contact_time(const State *s, double a, double g);
double exit_time(const State *s, double x_left, double x_right, double y_bottom, double g);
void collide_pair(double rx, double ry, State *p, double m1, State *q, double m2);
void bounce_wall(State *s, double a, double v_min);
void settle_wall(State *s, double a, double keep, double v_floor);
double energy(Core *core, int32_t i);

/* calendar.c */
void calendar_init(Core *core, int32_t n);
void file_atom(Core *core, int32_t i);
int32_t calendar_top(Core *core);
void calendar_rebuild(Core *core, double now);

/* grid.c */
static inline int32_t cell_index(const Core *core, int32_t cx, int32_t cy) {
  return cy * core->run.stride + cx;
}
int32_t grid_shape(Core *core);
void grid_edges(Core *core, double *edges);
int32_t cell_of(Core *core, double u, double u0, int32_t n);
void cell_link(Core *core, int32_t i, int32_t cx, int32_t cy);
void cell_unlink(Core *core, int32_t i);

/* predict.c */
void scan_line(Core *core, int32_t i, int32_t c, int32_t step);
void predict_real(Core *core, int32_t i);
void predict_crossing(Core *core, int32_t i);
void set_key(Core *core, int32_t i);
void load_key(Core *core, int32_t i);
void predict(Core *core, int32_t i);

/* events.c */
void fly_to_clock(Core *core, int32_t i);
int32_t knife(Core *core, int32_t i);
int32_t pair_event(Core *core, int32_t i, double te, int32_t *second);
int32_t wall_event(Core *core, int32_t i, double te);
void exit_event(Core *core, int32_t i, double te);
int32_t crossing_event(Core *core, int32_t i, double te, int32_t kind);

/* driver.c */
void renumber(Core *core);

/* game.c: one whole frame (a replay's: no log), and a whole frame's end */
void frame(Core *core, double height);
int32_t frame_end(Core *core);
/* The clock's whole frame: floor(t) for t >= 0. */
static inline double whole_frame(double t) { return (double)(int64_t)t; }

/* lookahead.c (native builds) */
int32_t look_before(Core *core, int32_t i, int32_t kind, int32_t *after);
void look_after(Core *core, int32_t next, int32_t after);

/* memory.c: n zeroed bytes on a 64-byte line, 0 if none are left */
void *core_take(Core *core, uintptr_t bytes);


#endif
