/*
 * The game's clock above the physics, written once for both editions (game/rules.py and
 * web/src/game/rules.ts call it; physics/reference.py's `play_to` is its readable oracle).
 * Play goes on in pieces that stop at each whole frame; there the height held during the
 * frame is recorded (the game's moves, up to the win), the frame's end sees the win, and the
 * next frame's height is applied: the script's (a recording watched) or the one asked for.
 * A game is therefore its heights per whole frame, whatever the display's rate.
 */
#include "tables.h"

static int32_t holding(const Play *p) { return p->n_script > 0 && p->n_script == p->script_runs; }

/* The script's height for the frame starting now, as the one asked; past its end: none. */
static void scripted(Play *p) {
  if (!holding(p)) return;
  while (p->script_run < p->n_script && p->script_used >= p->script[2 * p->script_run + 1]) {
    p->script_used -= p->script[2 * p->script_run + 1];
    p->script_run++;
  }
  if (p->script_run >= p->n_script) {
    p->n_script = p->script_runs = 0;
    return;
  }
  p->asked = p->script[2 * p->script_run];
}

/* The height asked for takes effect (one asked in the win's frame too: the score was fixed
 * at its end). */
static void apply_asked(Core *core) {
  double h = core->play.asked;
  if (h != h) return;
  core->play.asked = NAN;
  if (h != core->run.trap_height) core_set_trap_height(core, h);
}

/* Add one frame held at h to the moves: 0 if a new run finds them full. */
static int32_t record(Play *p, double h) {
  if (p->n_moves > 0 && p->moves[2 * p->n_moves - 2] == h) {
    p->moves[2 * p->n_moves - 1] += 1.0;
    return 1;
  }
  if (p->n_moves == CORE_MOVES_CAPACITY) return 0;
  p->moves[2 * p->n_moves] = h;
  p->moves[2 * p->n_moves + 1] = 1.0;
  p->n_moves++;
  return 1;
}

/* The work owed at the whole frame reached: its move, its end, then the next height. */
static int32_t settle(Core *core, int32_t each_frame) {
  Play *p = &core->play;
  Run *r = &core->run;
  if (p->owed == OWED_END) {
    int32_t recorded = r->score < 0; /* the moves end with the frame of the win */
    if (recorded && !record(p, r->trap_height)) return CORE_MOVES_FULL;
    frame_end(core);
    p->frames += 1.0;
    p->script_used += 1.0;
    p->owed = OWED_NEXT;
    if (each_frame && recorded) return CORE_FRAME_END;
  }
  if (p->owed == OWED_NEXT) {
    if (r->record && r->knife && r->n_log > 0) return CORE_LOG_FULL; /* the knife may log all */
    scripted(p);
    apply_asked(core);
    p->owed = OWED_NONE;
  }
  return CORE_DONE;
}

int32_t core_play_to(Core *core, double end, int32_t each_frame) {
  Run *r = &core->run;
  for (;;) {
    int32_t code = settle(core, each_frame);
    if (code != CORE_DONE || !(r->time < end)) return code;
    double next = whole_frame(r->time) + 1.0;
    if (core_advance_to(core, next < end ? next : end) == CORE_LOG_FULL) return CORE_LOG_FULL;
    if (r->time >= next) core->play.owed = OWED_END;
  }
}

int32_t core_ask_height(Core *core, double height, int32_t now) {
  Play *p = &core->play;
  if (core->run.won || holding(p) || height == core_asked_height(core)) return 0;
  p->asked = height;
  /* nothing in flight: paused, or on a whole frame */
  if ((now || core->run.time == whole_frame(core->run.time)) && p->owed == OWED_NONE)
    apply_asked(core);
  return 1;
}

double core_asked_height(const Core *core) {
  double h = core->play.asked;
  return h == h ? h : core->run.trap_height;
}

int32_t core_hold(Core *core, int32_t n_runs) {
  Play *p = &core->play;
  p->n_script = p->script_runs = 0;
  if (n_runs > p->script_capacity) {
    p->script = core_take(core, sizeof(double) * 2 * (uintptr_t)n_runs);
    if (!p->script) return 0;
    p->script_capacity = n_runs;
  }
  p->script_runs = n_runs;
  return 1;
}

void core_hold_run(Core *core, double height, double frames) {
  Play *p = &core->play;
  if (p->n_script >= p->script_runs) return;
  p->script[2 * p->n_script] = height;
  p->script[2 * p->n_script + 1] = frames;
  if (++p->n_script < p->script_runs) return;
  p->script_run = 0; /* the script's frames count from the start */
  p->script_used = p->frames;
  scripted(p);
  if (core->run.time == whole_frame(core->run.time) && p->owed == OWED_NONE) apply_asked(core);
}

int32_t core_n_moves(const Core *core) { return core->play.n_moves; }
double core_move_height(const Core *core, int32_t k) { return core->play.moves[2 * k]; }
double core_move_frames(const Core *core, int32_t k) { return core->play.moves[2 * k + 1]; }
void core_moves_taken(Core *core) { core->play.n_moves = 0; }
