/*
 * The event calendar: one key per row, (key_t, rank, tie_a, tie_b), the least handed out
 * first (Paul, J. Comput. Phys. 221, 615 (2007); Smallenburg 2022).
 *
 * Time is cut into bins of width bin_width from bin_base. Rows whose key lies in the current
 * bin or earlier sit in a small indexed 4-ary heap ordered by the full key; later ones sit,
 * unordered, in the doubly linked list of their bin (a ring of n_bins lists), beyond the
 * ring in an overflow list, and with no event (time infinity) in a list of their own. The
 * bin of a time is monotone in the time, so the heap's root is the least key of all.
 */
#include "tables.h"

/* The bin width aims at this many events per bin (the heap's typical size). */
#define EVENTS_PER_BIN 8
/* The ring spans about this many events per row into the future. */
#define RING_EVENTS_PER_ATOM 2

/* The ring's size: a power of two >= 16 near 2 n / 8. */
void calendar_init(Core *core, int32_t n) {
  double want = __builtin_floor((double)(RING_EVENTS_PER_ATOM * n) / EVENTS_PER_BIN);
  if (want < 1) want = 1;
  int32_t nb = 1;
  while (nb < want) nb <<= 1;
  core->run.n_bins = nb < 16 ? 16 : nb;
  for (int32_t r = 0; r < n; r++) {
    core->queued[r].key_t = INF;
    core->filing[r].heap_pos = -1;
    core->filing[r].bin = -1;
  }
}

/* True if the key (t, plan x) comes before the key (u, plan y). */
static inline int comes_before(Core *core, double t, int32_t x, double u, int32_t y) {
  if (t != u) return t < u;
  const Plan *p = &core->plan[x], *q = &core->plan[y];
  if (p->rank != q->rank) return p->rank < q->rank;
  if (p->tie_a != q->tie_a) return p->tie_a < q->tie_a;
  return p->tie_b < q->tie_b;
}

/* Entry e's place at or above place p (whose entry is e, or free): the entries above that
 * come after it moved down. */
static inline int32_t sift_up(Core *core, int32_t p, HeapEntry e) {
  while (p > 0) {
    int32_t q = (p - 1) >> 2;
    if (!comes_before(core, e.t, e.row, core->heap[q].t, core->heap[q].row)) break;
    core->heap[p] = core->heap[q];
    core->filing[core->heap[p].row].heap_pos = p;
    p = q;
  }
  return p;
}

/* Entry e at place p (children 4p+1..4p+4). */
static inline void put(Core *core, int32_t p, HeapEntry e) {
  core->heap[p] = e;
  core->filing[e.row].heap_pos = p;
}

/* The place of the lesser key of places c and d (c on a tie). */
static inline int32_t lesser(Core *core, int32_t c, int32_t d) {
  double td = core->heap[d].t, tc = core->heap[c].t;
  if (td == tc) /* rare: the rest of the keys decide */
    return comes_before(core, td, core->heap[d].row, tc, core->heap[c].row) ? d : c;
  return td < tc ? d : c; /* without a branch */
}

/* Move the heap entry at place p up or down to its place. (Once it moved up, it comes
 * before every entry below its new place: the way down would move nothing.) */
static void sift(Core *core, int32_t p) {
  HeapEntry e = core->heap[p];
  int32_t n = core->run.heap_size, up = sift_up(core, p, e);
  if (up != p) {
    put(core, up, e);
    return;
  }
  for (;;) {
    int32_t c = 4 * p + 1;
    if (c >= n) break;
    if (c + 4 <= n) { /* four children, as at most places */
      int32_t first = c;
      c = lesser(core, c, first + 1);
      c = lesser(core, c, first + 2);
      c = lesser(core, c, first + 3);
    } else {
      for (int32_t d = c + 1; d < n; d++) c = lesser(core, c, d);
    }
    if (!comes_before(core, core->heap[c].t, core->heap[c].row, e.t, e.row)) break;
    core->heap[p] = core->heap[c];
    core->filing[core->heap[p].row].heap_pos = p;
    p = c;
  }
  put(core, p, e);
}

/* Row r's entry, new at the heap's end (place p), to its place: only ever up. */
static inline void push(Core *core, int32_t p, int32_t r, double t) {
  HeapEntry e = {t, r, 0};
  put(core, sift_up(core, p, e), e);
}

static void list_add(Core *core, int32_t r, int32_t l) {
  int32_t h = core->bins[l];
  core->filing[r].bin = l;
  core->filing[r].next = h;
  core->filing[r].prev = -1;
  if (h >= 0) core->filing[h].prev = r;
  core->bins[l] = r;
  if (l < core->run.n_bins)
    core->run.n_ring++;
  else if (l == core->run.n_bins)
    core->run.n_over++;
}

static void list_remove(Core *core, int32_t r) {
  Filing *u = &core->filing[r];
  int32_t l = u->bin, p = u->prev, q = u->next;
  if (p >= 0)
    core->filing[p].next = q;
  else
    core->bins[l] = q;
  if (q >= 0) core->filing[q].prev = p;
  u->bin = -1;
  if (l < core->run.n_bins)
    core->run.n_ring--;
  else if (l == core->run.n_bins)
    core->run.n_over--;
}

/* File row r under its key time: in the heap if its bin has come, else in a list. */
void file_atom(Core *core, int32_t r) {
  Filing *u = &core->filing[r];
  double t = core->queued[r].key_t;
  double q = (t - core->run.bin_base) / core->run.bin_width;
  int32_t p = u->heap_pos;
  if (q < (double)(core->run.bin + 1)) {
    if (p >= 0) {
      core->heap[p].t = t;
      sift(core, p);
      return;
    }
    if (u->bin >= 0) list_remove(core, r);
    push(core, core->run.heap_size++, r, t);
    return;
  }
  int32_t nb = core->run.n_bins; /* a power of two */
  /* (here q >= bin + 1 > 0, so truncation is floor) */
  int32_t l = t == INF                      ? nb + 1
              : q < (double)(core->run.bin + nb) ? (int32_t)((int64_t)q & (nb - 1))
                                           : nb;
  if (p < 0) {
    int32_t was = u->bin;
    if (was == l) return; /* lists are unordered: nothing to do */
    if (was >= 0) list_remove(core, r);
    list_add(core, r, l);
    return;
  }
  list_add(core, r, l);
  u->heap_pos = -1;
  int32_t last = --core->run.heap_size;
  if (p == last) return;
  core->heap[p] = core->heap[last];
  core->filing[core->heap[p].row].heap_pos = p;
  sift(core, p);
}

static void reset(Core *core, double base, double width) {
  int32_t n = core->run.n_atoms;
  for (int32_t l = 0; l < core->run.n_bins + 2; l++) core->bins[l] = -1;
  for (int32_t r = 0; r < n; r++) {
    core->filing[r].heap_pos = -1;
    core->filing[r].bin = -1;
  }
  core->run.heap_size = 0;
  core->run.n_ring = 0;
  core->run.n_over = 0;
  core->run.bin_base = base;
  core->run.bin_width = width;
  core->run.bin = 0;
  core->run.scan_bin = 0;
  for (int32_t r = 0; r < n; r++) file_atom(core, r);
}

/*
 * Bin width from the event rate of the bulk: the mean time to the pending events, trimmed
 * twice to the bulk (a few atoms far above the cup would dominate it), over their count.
 */
static double bin_width(Core *core, double now) {
  double m = INF;
  int32_t c = 0;
  for (int pass = 0; pass < 3; pass++) {
    double s = 0;
    c = 0;
    for (int32_t r = 0; r < core->run.n_atoms; r++) {
      double g = core->queued[r].key_t - now;
      if (g < m * 3) {
        s += g > 0 ? g : 0;
        c++;
      }
    }
    if (c == 0 || !(s > 0)) return 1;
    m = s / c;
  }
  return (EVENTS_PER_BIN * m) / c;
}

/* Empty the calendar and file every row again from `now`, the bin width refitted. */
void calendar_rebuild(Core *core, double now) { reset(core, now, bin_width(core, now)); }

/* Nothing in the ring: jump to the overflow's earliest bin; 0 if no row has an event. */
static int jump_to_overflow(Core *core) {
  double m = INF;
  for (int32_t j = core->bins[core->run.n_bins]; j >= 0; j = core->filing[j].next)
    if (core->queued[j].key_t < m) m = core->queued[j].key_t;
  if (!(m < INF)) return 0; /* only a NaN could do this: nothing to hand out */
  double q = (m - core->run.bin_base) / core->run.bin_width;
  if (q > 1e15) {
    reset(core, m, core->run.bin_width); /* far beyond: start the bins there */
    return 2;
  }
  core->run.bin = (int64_t)__builtin_floor(q) - 1;
  core->run.scan_bin = core->run.bin - core->run.n_bins;
  return 1;
}

/* Fill the empty heap from the next non-empty bin; 0 if no row has an event. */
static int next_bin(Core *core) {
  int32_t nb = core->run.n_bins;
  while (core->run.heap_size == 0) {
    if (core->run.n_ring == 0) {
      if (core->run.n_over == 0) return 0;
      int jumped = jump_to_overflow(core);
      if (jumped == 0) return 0;
      if (jumped == 2) continue;
    }
    int64_t cb = ++core->run.bin;
    if (cb >= core->run.scan_bin + nb) {
      /* The ring moved on by its length: re-file the overflow list. */
      core->run.scan_bin = cb;
      for (int32_t j = core->bins[nb]; j >= 0;) {
        int32_t k = core->filing[j].next;
        file_atom(core, j);
        j = k;
      }
    }
    int32_t s = (int32_t)(cb % nb);
    /* (the overflow's re-filing above may have put rows in the heap already) */
    int32_t first = core->run.heap_size, total = first;
    for (int32_t j = core->bins[s]; j >= 0; j = core->filing[j].next) {
      core->filing[j].bin = -1;
      core->heap[total++].row = j;
      __builtin_prefetch(&core->queued[j]);
    }
    core->bins[s] = -1;
    core->run.n_ring -= total - first;
    /* The keys asked for above, into the heap one by one (what lies beyond is not yet in it). */
    for (int32_t p = first; p < total; p++) {
      core->run.heap_size = p + 1;
      int32_t r = core->heap[p].row;
      push(core, p, r, core->queued[r].key_t);
    }
  }
  return 1;
}

/* The row with the least key, or -1 if no row has a finite key. */
int32_t calendar_top(Core *core) {
  if (core->run.heap_size == 0 && !next_bin(core)) return -1;
  return core->heap[0].row;
}
