/*
 * The engine core's API, declared once: the model's constants and codes, and every entry
 * point a wrapper may call. scripts/core_api.py generates from this header, and checks
 * fresh (tests/physics/test_core_api.py):
 *   - src/evapcool/physics/model.py and web/src/physics/model.ts (the constants below),
 *   - src/evapcool/physics/_core_glue.h (CPython's method tables and plain wrappers),
 *   - src/evapcool/physics/_core.pyi (their types),
 *   - web/src/physics/core-exports.ts (the WebAssembly exports' TypeScript interface).
 * A line "py: Core.name(...) -> type" under an entry point's comment binds it to Python:
 * plain numbers in and out are wrapped by the generator, the rest by hand in
 * _coremodule.c. [nogil] releases the GIL during the call; [nomem] turns 0 into
 * MemoryError. Every entry point here is exported from the WebAssembly module and no other.
 */
#ifndef EVAPCOOL_CORE_H
#define EVAPCOOL_CORE_H

#include <stdint.h>

/* ---- The model's constants and codes ------------------------------------------------- */
/* Frames per second of the original; physics time is measured in frames (SPEC 1). */
#define FPS 30
/* g, px / frame^2, pointing down the screen. */
#define GRAVITY (10.0 / 30.0)
/* a of the cup y = a x^2, per px. */
#define CURVATURE 0.01
/* The original's atom radius, px. */
#define ATOM_RADIUS 12.0
/* The original's atom count. */
#define N_ATOMS 49
/* The slider's start, px above the lowest centre position. */
#define TRAP_HEIGHT 400.0
/* p in Tc(N) = Tc0 (N / N0)^p: the seed's 3D-box law (seed Eq. 46)... */
#define TC_EXPONENT_SEED (2.0 / 3.0)
/* ...or the ideal Bose gas with this cup's density of states g(E) ~ E^(3/2) (SPEC 4). */
#define TC_EXPONENT_CUP (2.0 / 5.0)
/* An elastic bounce leaves the wall at least this fast along the normal (px/frame), so
 * grazing and resting atoms hop instead of stalling (kernels.bounce_wall, docs/model.md). */
#define WALL_MIN_NORMAL_SPEED 1e-3
/* After the win, wall bounces keep 1 - 0.2 of the speed (seed Eq. 34)... */
#define WIN_DAMPING 0.2
/* ...but only while the speed is at least this (px/frame). */
#define WIN_DAMPING_MIN_SPEED 1.0
/* A damped bounce leaves the wall at least this fast (px/frame), see kernels.settle_wall. */
#define WIN_NORMAL_SPEED_FLOOR 0.25
/* @names STATUS_NAMES: Atom lifecycle (SPEC 2.3): trapped -> escaped -> gone. */
#define TRAPPED 0
#define ESCAPED 1
#define GONE 2
/* @names EVENT_NAMES: Event kinds of the event log. */
#define EV_PAIR 0
#define EV_WALL 1
#define EV_ESCAPE 2
#define EV_GONE 3
#define EV_KNIFE 4
/* @names ESCAPE_RULES: How atoms leave: over the rim, or cut at m g H at once (the knife). */
#define ESCAPE_RIM 0
#define ESCAPE_KNIFE 1
/* @names REACH_NAMES: The reach rule's answers (core_out_of_reach): within reach, or why not. */
#define REACH_WITHIN 0
#define REACH_ALL_ESCAPED 1
#define REACH_ONE_ATOM 2
#define REACH_STUCK 3
#define REACH_STUCK_HERE 4
/* The answers of core_advance_to: every event done, or the log to be emptied first (then
 * call again). */
#define CORE_DONE 0
#define CORE_LOG_FULL 1
/* The further answers of core_play_to: the moves to be taken first (then call again), or
 * (asked for) a whole frame played, recorded and ended: call again to go on. */
#define CORE_MOVES_FULL 2
#define CORE_FRAME_END 3
/* Runs of (height, frames) the core keeps before they must be taken. */
#define CORE_MOVES_CAPACITY 64
/* Bytes of one line of the event log (LogLine). */
#define CORE_LOG_LINE_BYTES 24
/* ---- end of the model's constants ------------------------------------------------------ */

/* One line of the event log: (EV_* kind, atom, other atom or -1, time). */
typedef struct {
  int32_t kind, a, b, pad;
  double t;
} LogLine;
_Static_assert(sizeof(LogLine) == CORE_LOG_LINE_BYTES, "a log line is 24 bytes");

/* One engine: its scalars and tables (core/tables.h); wrappers hold its address only. */
typedef struct Core Core;

#ifdef __wasm__
#define CORE_API(name) __attribute__((export_name(#name)))
#else
#define CORE_API(name)
#endif

/* ---- Entry points ------------------------------------------------------------------------ */
/* memory.c: a new engine, no tables yet (0 if the memory is full). */
CORE_API(core_new) Core *core_new(void);
/* memory.c: the engine and every table it took. */
CORE_API(core_free) void core_free(Core *core);

/* driver.c: the tables of n atoms; returns the inputs' place: x, y, vx, vy, t, radius, mass
 * (n doubles each), then the status (n int32), or 0 if the memory cannot hold them.
 * py: Core.__init__(n_atoms: int, log_capacity: int) -> None */
CORE_API(core_allocate) double *core_allocate(Core *core, int32_t n, int32_t log_capacity);
/* driver.c: copy the inputs into the tables; the fixed parameters and the clock.
 * py: Core.load(inputs: Any, status: Any, gravity: float, curvature: float, x_left: float, x_right: float, y_bottom: float, knife: bool, win_rule: bool, record: bool, time: float, won: bool, pairs: float, walls: float) -> None */
CORE_API(core_load)
void core_load(Core *core, const double *inputs, double gravity, double curvature, double x_left,
               double x_right, double y_bottom, int32_t knife_rule, int32_t win_rule,
               int32_t record, double time, int32_t won, double pairs, double walls);
/* driver.c: the grid, the cells and every prediction; 0 if the memory cannot hold the cells.
 * py: Core.start(energy_sum: float, trap_height: float) -> None [nomem] */
CORE_API(core_start) int32_t core_start(Core *core, double energy_sum, double trap_height);
/* driver.c: every event up to t_end: CORE_DONE, or CORE_LOG_FULL to empty the log first.
 * py: Core.advance_to(t_end: float) -> int [nogil] */
CORE_API(core_advance_to) int32_t core_advance_to(Core *core, double t_end);
/* driver.c: a new rim height, at once (with the knife: atoms above m g H go now).
 * py: Core.set_trap_height(height: float) -> None */
CORE_API(core_set_trap_height) void core_set_trap_height(Core *core, double height);
/* tables.c: declare the gas condensed now.
 * py: Core.force_win() -> None */
CORE_API(core_force_win) void core_force_win(Core *core);

/* tables.c: World atom a's lifecycle status. */
CORE_API(core_status_of) int32_t core_status_of(Core *core, int32_t a);
/* tables.c: stored value k of World atom a: 0 x, 1 y, 2 vx, 3 vy, 4 t, 5 radius, 6 mass. */
CORE_API(core_stored_of) double core_stored_of(Core *core, int32_t a, int32_t k);
/* tables.c: World atom a's energy 1/2 m v^2 + m g y from its stored state. */
CORE_API(core_atom_energy) double core_atom_energy(Core *core, int32_t a);
/* tables.c: the atoms of this status carried to time t, in World index order, as eight
 * columns of n_atoms doubles from out: index, x, y, vx, vy, radius, mass, energy; their count. */
CORE_API(core_snapshot) int32_t core_snapshot(Core *core, int32_t status, double t, double *out);
/* tables.c: the sum of trapped energies added in World index order. */
CORE_API(core_sequential_energy_sum) double core_sequential_energy_sum(Core *core);
/* tables.c: every atom's stored state by World index into (n, 2) pos and vel, n t, n int8
 * status and n int64 counts.
 * py: Core.export(pos: Any, vel: Any, t_atom: Any, status: Any, counter: Any) -> None */
CORE_API(core_export_states)
void core_export_states(Core *core, double *pos, double *vel, double *t, int8_t *status,
                        int64_t *counter);
/* grid.c: trapped atoms filed more than one cell away from their cell now (0 if sound).
 * py: Core.grid_errors() -> int */
CORE_API(core_grid_errors) int32_t core_grid_errors(Core *core);

/* tables.c: the event log's lines since it was last cleared.
 * py: Core.take_log() -> bytes */
CORE_API(core_log_address) LogLine *core_log_address(Core *core);
/* tables.c: the log was copied out: start it again. */
CORE_API(core_log_clear) void core_log_clear(Core *core);
/* tables.c: the scalars, by name.
 * py: Core.scalars() -> tuple[float, float, bool, int, int, int, int, int, float] */
CORE_API(core_time) double core_time(const Core *core);
CORE_API(core_energy_sum) double core_energy_sum(const Core *core);
CORE_API(core_x_rim) double core_x_rim(const Core *core);
CORE_API(core_trap_height) double core_trap_height(const Core *core);
CORE_API(core_won) int32_t core_won(const Core *core);
CORE_API(core_n_trapped) int32_t core_n_trapped(const Core *core);
CORE_API(core_pairs) double core_pairs(const Core *core);
CORE_API(core_walls) double core_walls(const Core *core);
CORE_API(core_crossings) double core_crossings(const Core *core);
CORE_API(core_stale) double core_stale(const Core *core);
CORE_API(core_n_log) int32_t core_n_log(const Core *core);
/* tables.c: the cell grid: columns, rows, cell edge and skin (px).
 * py: Core.grid() -> tuple[int, int, float, float] */
CORE_API(core_nx) int32_t core_nx(const Core *core);
CORE_API(core_ny) int32_t core_ny(const Core *core);
CORE_API(core_cell) double core_cell(const Core *core);
CORE_API(core_skin) double core_skin(const Core *core);
/* tables.c: atoms trapped at the end of the frame the win was seen (-1 before), that frame.
 * py: Core.score() -> tuple[int, float] | None */
CORE_API(core_score) int32_t core_score(const Core *core);
CORE_API(core_win_frame) double core_win_frame(const Core *core);

/* kernels.c: a * b + c as the core computes it (two roundings, never fused).
 * py: contraction_probe(a: float, b: float, c: float) -> float */
CORE_API(core_contraction_probe) double core_contraction_probe(double a, double b, double c);

/* start.c: the start from a seed into pos and vel ((n, 2) doubles each): the atoms placed,
 * fewer than n if they do not fit below y_top, -1 for impossible odds.
 * py: load_cup(pos: Any, vel: Any, radius: float, curvature: float, y_top: float, seed: int) -> int */
CORE_API(core_load_cup)
int32_t core_load_cup(double *pos, double *vel, int32_t n, double radius, double curvature,
                      double y_top, uint32_t seed_lo, uint32_t seed_hi);
/* start.c: atoms the loading places below y_top.
 * py: cup_capacity(radius: float, curvature: float, y_top: float) -> int */
CORE_API(core_cup_capacity) int32_t core_cup_capacity(double radius, double curvature, double y_top);
/* start.c: x^p from products and square roots (the same bits everywhere).
 * py: power(x: float, p: float) -> float */
CORE_API(core_power) double core_power(double x, double p);
/* start.c: Tc(N) = Tc0 (N / N0)^p for N = 0..N0, the core's own power.
 * py: Core.fill_tc_table(tc0: float, exponent: float) -> None */
CORE_API(core_fill_tc_table) void core_fill_tc_table(Core *core, double tc0, double exponent);

/* overlap.c: the first pair of included atoms (include[i] != 0) closer than
 * (r_i + r_j)(1 - tol), tol >= 0, least i then least j, into pair: 1 if there is one, else 0
 * (dx dx + dy dy < lim lim, lim = (r_i + r_j)(1 - tol), as physics/validation.py compares);
 * work: 6n + 2 int32 of scratch.
 * py: first_overlap(x: Any, y: Any, radius: Any, include: Any, tol: float) -> tuple[int, int] | None */
CORE_API(core_first_overlap)
int32_t core_first_overlap(const double *x, const double *y, const double *radius,
                           const int8_t *include, int32_t n, double tol, int32_t *work,
                           int32_t *pair);

/* game.c: (height, frames) runs played from a whole frame up to the win or `limit` frames:
 * the frames played.
 * py: Core.replay(runs: Any, limit: int) -> int */
CORE_API(core_replay) int32_t core_replay(Core *core, const double *runs, int32_t n_runs, int32_t limit);
/* game.c: a recording's path in the (N, T) plane: the runs played as core_replay plays
 * them, frame 0 (height h0), every stride-th frame, the last and the win's kept as rows of
 * (k, N, T, h) in points (their count into n_points); the frames played.
 * py: Core.path(runs: Any, limit: int, stride: int, h0: float) -> tuple[int, Any] */
CORE_API(core_path)
int32_t core_path(Core *core, const double *runs, int32_t n_runs, int32_t limit, int32_t stride,
                  double h0, double *points, int32_t *n_points);
/* game.c: the trapped atoms' energy 1/2 m v^2 + m g y, summed in World index order as NumPy
 * sums (Python's Simulation.total_energy). */
CORE_API(core_total_energy) double core_total_energy(Core *core);
/* game.c: why the gas can no longer condense (REACH_*), or REACH_WITHIN.
 * py: Core.out_of_reach(lowest: float, height: float) -> int */
CORE_API(core_out_of_reach) int32_t core_out_of_reach(Core *core, double lowest, double height);
/* play.c: the game's clock, to `end` (frames) in pieces that stop at each whole frame: there
 * the height held is recorded (up to the win), the win seen, the script's or the asked height
 * applied. CORE_DONE; CORE_LOG_FULL or CORE_MOVES_FULL to empty first; with each_frame
 * CORE_FRAME_END after each recorded frame. Call again with the same end to go on.
 * py: Core.play_to(end: float, each_frame: bool) -> int [nogil] */
CORE_API(core_play_to) int32_t core_play_to(Core *core, double end, int32_t each_frame);
/* play.c: ask for a rim height from the next whole frame (at once if `now` or on one); refused
 * (0) once won, while a script plays, or if it is the height asked already.
 * py: Core.ask_height(height: float, now: bool) -> bool */
CORE_API(core_ask_height) int32_t core_ask_height(Core *core, double height, int32_t now);
/* play.c: the rim's height now, or the one it takes at the next whole frame.
 * py: Core.asked_height() -> float */
CORE_API(core_asked_height) double core_asked_height(const Core *core);
/* play.c: a script of n_runs (height, frames) runs to hold, added by core_hold_run, each
 * height from the whole frame of its turn counted from the start; 0 runs: none. 0 if the
 * memory cannot hold it.
 * py: Core.hold(n_runs: int) -> None [nomem] */
CORE_API(core_hold) int32_t core_hold(Core *core, int32_t n_runs);
/* play.c: the script's next run; after the last, its height for the frame starting now.
 * py: Core.hold_run(height: float, frames: float) -> None */
CORE_API(core_hold_run) void core_hold_run(Core *core, double height, double frames);
/* play.c: runs of moves kept (the last may still grow).
 * py: Core.n_moves() -> int */
CORE_API(core_n_moves) int32_t core_n_moves(const Core *core);
/* play.c: the height of kept run k.
 * py: Core.move_height(k: int) -> float */
CORE_API(core_move_height) double core_move_height(const Core *core, int32_t k);
/* play.c: the frames of kept run k.
 * py: Core.move_frames(k: int) -> float */
CORE_API(core_move_frames) double core_move_frames(const Core *core, int32_t k);
/* play.c: the moves kept were taken (after CORE_MOVES_FULL): keep none.
 * py: Core.moves_taken() -> None */
CORE_API(core_moves_taken) void core_moves_taken(Core *core);
/* game.c: n doubles of the engine's memory for the caller to fill (a recording's runs). */
CORE_API(core_buffer) double *core_buffer(Core *core, int32_t n);

#endif
