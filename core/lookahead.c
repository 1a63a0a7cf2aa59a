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

/* The cells row j's next event will scan: the index of the first, into *rows and *cols how
 * many (one line per row of cells); 0 if none. A crossing scans the column or row beyond
 * its new cell, other events the 3 x 3 block around it (the border's cells are empty). */
static int coming_cells(const Core *core, int32_t j, int32_t *first, int32_t *rows, int32_t *cols) {
  const Plan *p = &core->plan[j];
  if (p->status != TRAPPED) return 0;
  int32_t x0 = p->cell_x - 1, y0 = p->cell_y - 1;
  *rows = *cols = 3;
  if (p->rank == RANK_CROSS) {
    if (p->cross_axis == KIND_CROSS_X)
      x0 = 2 * p->cross_to - p->cell_x, *cols = 1;
    else if (p->cross_axis == KIND_CROSS_Y)
      y0 = 2 * p->cross_to - p->cell_y, *rows = 1;
    else
      return 0; /* (no crossing at all: nothing to read) */
  }
  /* A crossing enters a cell of the grid from a neighbour, so the line beyond lies in the
   * grid or its border: every index here is inside the cells' table. */
  *first = cell_index(core, x0, y0);
  return 1;
}

/* The heads of those cells: one line per row of cells. */
static void ask_heads(const Core *core, int32_t j) {
  int32_t c, rows, cols;
  if (!coming_cells(core, j, &c, &rows, &cols)) return;
  for (int32_t r = 0; r < rows; r++) __builtin_prefetch(&core->cells[c + r * core->run.stride]);
}

/* Read those heads (asked for an event ago) and ask for their first atoms' states. */
static void ask_firsts(const Core *core, int32_t j) {
  int32_t c, rows, cols;
  if (!coming_cells(core, j, &c, &rows, &cols)) return;
  for (int32_t r = 0; r < rows; r++)
    for (int32_t k = 0; k < cols; k++) {
      int32_t first = core->cells[c + r * core->run.stride + k];
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
    if (n >= 5) { /* the root's four children, as mostly */
      const HeapEntry *h = core->heap;
      int32_t a = h[2].t < h[1].t ? 2 : 1, b = h[4].t < h[3].t ? 4 : 3;
      c = h[b].t < h[a].t ? b : a;
    } else {
      for (int32_t d = 2; d < n; d++)
        if (core->heap[d].t < core->heap[c].t) c = d;
    }
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
