/*
 * Asking for memory ahead of the event loop (native builds; speed only, no effect on
 * results). From 10^4 atoms on the tables outgrow the caches a core has to itself, and an
 * event would start by waiting for its row's records, its partner's and the heads of the
 * cells it scans. While one event is processed the loop asks for what the next will read:
 * the next event is most likely the earliest of the heap root's children. From
 * DEEP_MIN_ATOMS on it also asks for the rows of the event after that, for the heads of the
 * cells their scans will read, and an event later for the first atoms of those cells.
 */
#include "tables.h"

#ifdef CORE_LOOKAHEAD

/* From this many atoms the loop asks two events ahead (fewer: in cache anyway). */
#define DEEP_MIN_ATOMS 20000

static inline void ask_row(const Core *core, int32_t r) {
  __builtin_prefetch(&core->state[r]);
  __builtin_prefetch(&core->queued[r]);
  __builtin_prefetch(&core->plan[r]);
}

/* The block of cells row j's next event will scan (x0..x1, y0..y1); 0 if none. A crossing
 * scans the column or row beyond its new cell, other events the 3 x 3 block around it. */
static int coming_cells(const Core *core, int32_t j, int32_t b[4]) {
  const Plan *p = &core->plan[j];
  const int32_t nx = core->run.nx, ny = core->run.ny, cx = p->cell_x, cy = p->cell_y;
  if (p->status != TRAPPED) return 0;
  b[0] = cx > 0 ? cx - 1 : 0;
  b[1] = cx < nx - 1 ? cx + 1 : nx - 1;
  b[2] = cy > 0 ? cy - 1 : 0;
  b[3] = cy < ny - 1 ? cy + 1 : ny - 1;
  if (p->rank == RANK_CROSS) {
    if (p->cross_axis == KIND_CROSS_X) {
      b[0] = b[1] = 2 * p->cross_to - cx;
      if (b[0] < 0 || b[0] >= nx) return 0;
    } else {
      b[2] = b[3] = 2 * p->cross_to - cy;
      if (b[2] < 0 || b[2] >= ny) return 0;
    }
  }
  return 1;
}

/* The heads of those cells: one line per row of cells. */
static void ask_heads(const Core *core, int32_t j) {
  int32_t b[4];
  if (!coming_cells(core, j, b)) return;
  for (int32_t cy = b[2]; cy <= b[3]; cy++) __builtin_prefetch(&core->cells[cy * core->run.nx + b[0]]);
}

/* Read those heads (asked for an event ago) and ask for their first atoms' states. */
static void ask_firsts(const Core *core, int32_t j) {
  int32_t b[4];
  if (!coming_cells(core, j, b)) return;
  for (int32_t cy = b[2]; cy <= b[3]; cy++)
    for (int32_t cx = b[0]; cx <= b[1]; cx++) {
      int32_t first = core->cells[cy * core->run.nx + cx];
      if (first >= 0) __builtin_prefetch(&core->state[first]);
    }
}

/* Heap place of the event after the next (the next is at place c), or -1. */
static int32_t after_next(const Core *core, int32_t c) {
  const int32_t n = core->run.heap_size;
  int32_t best = -1;
  double t = INF;
  for (int32_t d = 1; d < 5 && d < n; d++)
    if (d != c && core->heap[d].t < t) best = d, t = core->heap[d].t;
  for (int32_t d = 4 * c + 1; d < 4 * c + 5 && d < n; d++)
    if (core->heap[d].t < t) best = d, t = core->heap[d].t;
  return best;
}

/* One row further along the list of the bin the calendar opens next, asking for the row
 * after it: when the bin moves into the heap, its walk from row to row finds every line in
 * the caches instead of waiting for each in turn (about as many events as rows per bin). */
static void walk_next_bin(Core *core) {
  if (core->run.walk_bin != core->run.bin) {
    core->run.walk_bin = core->run.bin;
    int64_t b = core->run.bin + 1;
    core->run.walk = b >= 0 ? core->bins[(int32_t)(b % core->run.n_bins)] : -1;
  } else if (core->run.walk >= 0) {
    core->run.walk = core->filing[core->run.walk].next;
  }
  if (core->run.walk >= 0) {
    __builtin_prefetch(&core->filing[core->run.walk]);
    __builtin_prefetch(&core->queued[core->run.walk]);
  }
}

/* Before row i's event of this kind: ask for the records of the next two events' rows (the
 * likely next, and from DEEP_MIN_ATOMS on the one after), for i's partner's and for the
 * heads of the cells i's scans read; for the next row, whose heads were asked an event
 * ago, its cells' first atoms. Only lines already asked for are read: a read that misses
 * would stall the loop it is meant to spare. The likely next row (or -1) and, in *after,
 * the one after it (or -1). */
int32_t look_before(Core *core, int32_t i, int32_t kind, int32_t *after) {
  const int32_t n = core->run.heap_size;
  int32_t next = -1;
  *after = -1;
  if (n > 1) {
    int32_t c = 1;
    for (int32_t d = 2; d < 5 && d < n; d++)
      if (core->heap[d].t < core->heap[c].t) c = d;
    next = core->heap[c].row;
    ask_row(core, next);
    if (core->run.n_atoms >= DEEP_MIN_ATOMS && n > 2) {
      int32_t a = after_next(core, c);
      if (a >= 0) {
        *after = core->heap[a].row;
        ask_row(core, *after);
      }
      ask_firsts(core, next);
    }
  }
  if (kind == KIND_PAIR) ask_row(core, core->plan[i].partner);
  ask_heads(core, i);
  walk_next_bin(core);
  return next;
}

/* After the event, before the predictions (the slow part): the rows asked for before it
 * have come, so ask for the next row's partner and the heads of the cells the next two
 * rows' scans read. */
void look_after(Core *core, int32_t next, int32_t after) {
  if (next < 0) return;
  const Plan *p = &core->plan[next];
  if (p->rank != RANK_CROSS && p->real_kind == KIND_PAIR) ask_row(core, p->partner);
  ask_heads(core, next);
  if (after >= 0) ask_heads(core, after);
}

#endif
