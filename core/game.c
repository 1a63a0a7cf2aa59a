/*
 * The game's rules that decide a score, written once for both editions (game/rules.py and
 * web/src/game/rules.ts call them): a trap height takes effect at a whole frame, the win is
 * seen at the end of a whole frame and the score is the atoms trapped then. A game is
 * therefore its heights per whole frame, whatever the display's rate, and a recording of
 * them (game/replay.py, web/src/game/replay.ts) replays to the same score in every edition.
 */
#include "tables.h"

/* The clock's whole frame: floor(t) for t >= 0. */
static double whole_frame(double t) { return (double)(int64_t)t; }

/*
 * The end of a whole frame: a win latched during the frame is seen now, and the score fixed
 * at the atoms trapped now (one already on its way over the rim may still leave; the score
 * stays). 1 at the frame the win is first seen, else 0.
 */
int32_t core_frame_end(Core *core) {
  Run *r = &core->run;
  if (!r->won || r->score >= 0) return 0;
  r->score = r->n_trapped;
  r->win_frame = r->time;
  return 1;
}

/*
 * One whole frame from a whole frame, the trap at `height` during it: the height takes effect
 * at the frame's start (not after the win: the score is the atoms left), then the events up to
 * the next whole frame, then the frame's end. CORE_LOG_FULL: empty the log and call again with
 * the same height, which goes on where it stopped.
 */
int32_t core_frame(Core *core, double height) {
  Run *r = &core->run;
  if (r->record && r->n_log > 0) return CORE_LOG_FULL; /* the knife may log every atom */
  if (!r->won && height != r->trap_height) core_set_trap_height(core, height);
  if (core_advance_to(core, whole_frame(r->time) + 1.0) == CORE_LOG_FULL) return CORE_LOG_FULL;
  core_frame_end(core);
  return CORE_DONE;
}

/*
 * A recording played back from a whole frame: runs (height, frames) pairs, each height held
 * for that many whole frames; it stops at the end of the frame the win is seen, or after
 * `limit` frames. Returns the frames played; the win and the score are the core's (core_won,
 * core_score). A replay keeps no event log.
 */
int32_t core_replay(Core *core, const double *runs, int32_t n_runs, int32_t limit) {
  int32_t frames = 0;
  core->run.record = 0;
  core->run.n_log = 0;
  for (int32_t k = 0; k < n_runs; k++)
    for (double f = 0.0; f < runs[2 * k + 1]; f += 1.0) {
      if (frames >= limit) return frames;
      core_frame(core, runs[2 * k]);
      frames++;
      if (core->run.score >= 0) return frames;
    }
  return frames;
}

/* n doubles of the engine's memory for the caller to fill (a recording's runs). */
double *core_buffer(Core *core, int32_t n) { return core_take(core, sizeof(double) * n); }
