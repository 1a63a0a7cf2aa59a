"""The event queue: a calendar of time bins in front of a small 4-ary heap.

(Paul, J. Comput. Phys. 221, 615 (2007); Smallenburg, Eur. Phys. J. E 45, 22 (2022).)
Each atom is filed under its key (key_t, rank, tie_a, tie_b). Time is cut into bins
of width bin_width from bin_base. Atoms whose key lies in the current bin or earlier
sit in the heap, ordered by the full key; later ones sit, unordered, in the list of
their bin (a ring of n_bins lists covering n_bins bins), beyond the ring in an
overflow list, or, with no event at all, in a list of their own. The bin of a time,
floor((t - bin_base) / bin_width), is monotone in t, so every heap key comes before
every listed key: the heap's root is the earliest event, the order is one heap's.

Why: the heap stays small (about EVENTS_PER_BIN atoms), so its sifts stay in cache;
filing an atom in a list touches two records instead of a sift path through a heap
of all atoms (which, at 10^5 atoms, misses the cache at every level). The bin width
is set from the pending events whenever the queue is refiled (driver.maintain).

Lists: tb.bins[k] is the first row of list k (-1 if empty): k < n_bins the ring,
n_bins the overflow, n_bins + 1 the atoms with no event. A row's list and neighbours
are in its QUEUED record (bin, next, prev); its heap place in heap_pos.
"""

from __future__ import annotations

import math

from evapcool.physics.fast.jit import entry, hot, part, prefetch

INF = math.inf

#: The bin width aims at this many events per bin (the heap's typical size).
EVENTS_PER_BIN = 8
#: The ring spans about this many events per atom into the future.
RING_EVENTS_PER_ATOM = 2


def ring_size(n_atoms: int) -> int:
    """Lists in the ring: a power of two, at least 16."""
    want = max(1, RING_EVENTS_PER_ATOM * n_atoms // EVENTS_PER_BIN)
    return max(16, 1 << math.ceil(math.log2(want)))


# -- the heap -------------------------------------------------------------------------
@hot
def comes_before(a, t_a, b, t_b, tb):
    """True if row a, filed under time t_a, comes before row b filed under t_b."""
    if t_a != t_b:
        return t_a < t_b
    pa = tb.plan[a]
    pb = tb.plan[b]
    if pa.rank != pb.rank:
        return pa.rank < pb.rank
    if pa.tie_a != pb.tie_a:
        return pa.tie_a < pb.tie_a
    return pa.tie_b < pb.tie_b


@hot
def _put(p, i, t, tb):
    """Row i with key time t at heap place p."""
    tb.heap[p].row = i
    tb.heap[p].t = t
    tb.queued[i].heap_pos = p


@part
def _sift_up(p, i, t, tb):
    """The place, at or above p, where row i (key time t) belongs; parents moved down."""
    while p > 0:
        up = (p - 1) >> 2
        j = tb.heap[up].row
        tj = tb.heap[up].t
        if not comes_before(i, t, j, tj, tb):
            break
        _put(p, j, tj, tb)
        p = up
    return p


@part
def _sift_down(p, i, t, tb):
    """The place, at or below p, where row i (key time t) belongs; children moved up."""
    n = tb.run[0].heap_size
    while True:
        c = 4 * p + 1
        if c >= n:
            break
        end = c + 4 if c + 4 <= n else n
        for d in range(c + 1, end):
            if comes_before(tb.heap[d].row, tb.heap[d].t, tb.heap[c].row, tb.heap[c].t, tb):
                c = d
        if not comes_before(tb.heap[c].row, tb.heap[c].t, i, t, tb):
            break
        _put(p, tb.heap[c].row, tb.heap[c].t, tb)
        p = c
    return p


@hot
def sift(p, tb):
    """Move the entry at heap place p up or down to its place (children 4p+1..4p+4)."""
    i = tb.heap[p].row
    t = tb.heap[p].t
    p = _sift_up(p, i, t, tb)
    p = _sift_down(p, i, t, tb)
    _put(p, i, t, tb)


@part
def heap_push(i, t, tb):
    run = tb.run[0]
    p = run.heap_size
    run.heap_size = p + 1
    tb.heap[p].row = i
    tb.heap[p].t = t
    sift(p, tb)


# -- the lists ------------------------------------------------------------------------
@hot
def list_add(i, lst, tb):
    q = tb.queued[i]
    first = tb.bins[lst]
    q.bin = lst
    q.next = first
    q.prev = -1
    if first >= 0:
        tb.queued[first].prev = i
    tb.bins[lst] = i
    run = tb.run[0]
    if lst < run.n_bins:
        run.n_ring += 1
    elif lst == run.n_bins:
        run.n_over += 1


@hot
def list_remove(i, tb):
    q = tb.queued[i]
    lst = q.bin
    if q.prev >= 0:
        tb.queued[q.prev].next = q.next
    else:
        tb.bins[lst] = q.next
    if q.next >= 0:
        tb.queued[q.next].prev = q.prev
    q.bin = -1
    run = tb.run[0]
    if lst < run.n_bins:
        run.n_ring -= 1
    elif lst == run.n_bins:
        run.n_over -= 1


# -- filing ---------------------------------------------------------------------------
@part
def _list_of(t, q, run):
    """The list for key time t, at bin position q = (t - base) / width (beyond the heap)."""
    if t == INF:
        return run.n_bins + 1
    if q < run.bin + run.n_bins:
        return int(q) % run.n_bins
    return run.n_bins


@hot
def file_atom(i, t, tb):
    """File row i under key time t: in the heap if its bin has come, else in a list."""
    run = tb.run[0]
    rec = tb.queued[i]
    q = (t - run.bin_base) / run.bin_width
    p = rec.heap_pos
    if q < run.bin + 1:  # bin <= current bin: into the heap, or moved within it
        if p < 0:
            if rec.bin >= 0:
                list_remove(i, tb)
            p = run.heap_size
            run.heap_size = p + 1
            tb.heap[p].row = i
        tb.heap[p].t = t
    else:
        lst = _list_of(t, q, run)
        if p < 0 and rec.bin == lst:  # lists are unordered: nothing to do
            return
        if p < 0 and rec.bin >= 0:
            list_remove(i, tb)
        list_add(i, lst, tb)
        if p < 0:
            return
        # Out of the heap: its last entry fills the hole.
        rec.heap_pos = -1
        last = run.heap_size - 1
        run.heap_size = last
        if p == last:
            return
        tb.heap[p].row = tb.heap[last].row
        tb.heap[p].t = tb.heap[last].t
    sift(p, tb)  # one call site: every inlined copy costs compile time


@entry
def refile_all(base, width, tb):
    """Empty the queue and file every row again, with a new base time and bin width."""
    run = tb.run[0]
    run.heap_size = 0
    run.bin = 0
    run.scan_bin = 0
    run.n_ring = 0
    run.n_over = 0
    run.cursor1 = -1
    run.cursor2 = -1
    run.bin_base = base
    run.bin_width = width
    tb.bins[:] = -1
    for i in range(tb.queued.shape[0]):
        tb.queued[i].heap_pos = -1
        tb.queued[i].bin = -1
    for i in range(tb.queued.shape[0]):
        file_atom(i, tb.queued[i].key_t, tb)


@entry
def bin_width(now, tb):
    """Bin width for EVENTS_PER_BIN events per bin, from the event rate of the bulk.

    Residual times of the pending events: their mean, trimmed twice to the bulk (a few
    atoms high above the cup or escaping would otherwise dominate it), over their
    count is the time between events.
    """
    mean = INF
    for _ in range(3):
        total = 0.0
        count = 0
        for i in range(tb.queued.shape[0]):
            wait = tb.queued[i].key_t - now
            if wait < mean * 3.0:
                total += wait if wait > 0.0 else 0.0
                count += 1
        if count == 0 or total <= 0.0:
            return 1.0
        mean = total / count
    return EVENTS_PER_BIN * mean / count


# -- taking the next bin --------------------------------------------------------------
@part
def _jump_to_overflow(tb):
    """The ring is empty: make the overflow's earliest bin the next one.

    False if no atom has a time at all (only a NaN could do this).
    """
    run = tb.run[0]
    earliest = INF
    j = tb.bins[run.n_bins]
    while j >= 0:
        if tb.queued[j].key_t < earliest:
            earliest = tb.queued[j].key_t
        j = tb.queued[j].next
    if not earliest < INF:
        return False
    q = (earliest - run.bin_base) / run.bin_width
    if q > 1e15:  # far beyond: start the bins there
        refile_all(earliest, run.bin_width, tb)
        return True
    run.bin = int(q) - 1  # q > 0 beyond the ring: int() is floor
    run.scan_bin = run.bin - run.n_bins
    return True


@part
def _refile_overflow(tb):
    """The ring moved on by its length: overflow atoms may now belong in the ring."""
    run = tb.run[0]
    run.scan_bin = run.bin
    j = tb.bins[run.n_bins]
    while j >= 0:
        after = tb.queued[j].next
        file_atom(j, tb.queued[j].key_t, tb)
        j = after


@part
def _dump_bin(tb):
    """Move the current bin's list into the heap."""
    run = tb.run[0]
    slot = run.bin % run.n_bins
    j = tb.bins[slot]
    tb.bins[slot] = -1
    while j >= 0:
        after = tb.queued[j].next
        tb.queued[j].bin = -1
        run.n_ring -= 1
        heap_push(j, tb.queued[j].key_t, tb)
        j = after


@hot
def next_bin(tb):
    """Fill the empty heap from the next non-empty bin; False if no atom has an event."""
    run = tb.run[0]
    while run.heap_size == 0:
        if run.n_ring == 0:
            if run.n_over == 0 or not _jump_to_overflow(tb):
                return False
            if run.heap_size > 0:  # refiled from a new base
                continue
        run.bin += 1
        if run.bin >= run.scan_bin + run.n_bins:
            _refile_overflow(tb)
        _dump_bin(tb)
    # The cursor of the bin after the next goes on along the same list.
    nb = run.n_bins
    run.cursor1 = run.cursor2 if run.cursor2 >= 0 else tb.bins[(run.bin + 1) % nb]
    j = tb.bins[(run.bin + 2) % nb]
    run.cursor2 = j
    if j >= 0:
        prefetch(tb.queued, j)
    return True


@hot
def _walk_step(j, lst, deep, tb):
    """One step of a cursor along list lst: the next row, asked for; -1 at the end.

    deep: its PLAN record too (its cells are read two events before its own).
    """
    if j < 0 or tb.queued[j].bin != lst:  # the atom left the list: its links moved on
        return -1
    j = tb.queued[j].next
    if j >= 0:
        prefetch(tb.queued, j)
        if deep:
            prefetch(tb.plan, j)
    return j


@part
def walk_ahead(deep, tb):
    """Walk the lists of the next two bins one step each (their dumps then hit the cache).

    A list is a chain of rows: walked only when its bin comes, every step would wait
    for memory. Each step reads a row asked for one event earlier, and a list is
    walked for two bins' time, as fast as bins fill. No effect on results.
    """
    run = tb.run[0]
    nb = run.n_bins
    run.cursor1 = _walk_step(run.cursor1, (run.bin + 1) % nb, deep, tb)
    run.cursor2 = _walk_step(run.cursor2, (run.bin + 2) % nb, deep, tb)
