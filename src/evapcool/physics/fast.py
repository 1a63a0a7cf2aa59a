"""The fast engine: Numba, a cell grid and one pending event per atom.

A drop-in for `ReferenceEngine` that reproduces its event sequence exactly:
the scalar formulas of kernels.py are compiled here with Numba, so both
engines do bit-identical arithmetic on the same stored states, and events are
ordered by the same key (time, solo before pair, then atom indices).

Techniques (Smallenburg, Eur. Phys. J. E 45, 22 (2022); Bannerman et al.,
J. Comput. Chem. 32, 3329 (2011)):

- Each atom keeps only its earliest event, filed under that event's time in an
  event calendar (Paul, J. Comput. Phys. 221, 615 (2007)): time bins, the
  current one in a small indexed 4-ary heap ordered by the full key, later
  ones in unordered lists. A pair event remembers the partner's collision
  counter and is dropped (the atom re-predicted) if the partner changed since.
- Trapped atoms live in a uniform grid of cells at least one contact distance
  wide (1.1 of it); pairs are only looked for in the 3 x 3 block around an atom. Crossing
  a cell edge is an event (linear in x, the stable quadratic in y under
  gravity) that changes no stored state. The edge cells are clamped, i.e. they
  reach to infinity, so a trapped atom flying out of the nominal box is still
  in a cell and still meets its neighbours.
- Positions are advanced lazily: an atom's stored state moves only when it
  takes part in a real event. Escaped atoms leave the grid and have only their
  exit-window event.

numba is imported by this module only, and this module only when the fast
engine is used.
"""

from __future__ import annotations

import math
import types

import numpy as np
from llvmlite import ir
from numba import njit
from numba.core import cgutils
from numba.core import types as nt
from numba.extending import intrinsic

from evapcool.physics import kernels as _k
from evapcool.physics.world import (
    ESCAPED,
    EV_ESCAPE,
    EV_GONE,
    EV_KNIFE,
    EV_PAIR,
    EV_WALL,
    GONE,
    TRAPPED,
    WALL_MIN_NORMAL_SPEED,
    WIN_DAMPING,
    WIN_DAMPING_MIN_SPEED,
    WIN_NORMAL_SPEED_FLOOR,
    World,
)

INF = math.inf

# The very kernels the reference engine mirrors; error_model="numpy" gives
# inf/nan instead of raising, like the NumPy scalars of the reference engine.
_jit = njit(cache=True, error_model="numpy")
# The engine never allocates inside compiled code, so Numba's reference
# counting (atomic operations on every array passed around) is switched off.
_fn = njit(cache=True, _nrt=False)
# Small helpers on the hot path are inlined by Numba itself: a call between
# compiled functions passes every array as its full descriptor (7-9 words
# each, dozens of words per call), which LLVM's inliner rarely removes.
_fni = njit(cache=True, _nrt=False, inline="always")
_flight_x = _jit(_k.flight_x)
_flight_y = _jit(_k.flight_y)
_flight_vy = _jit(_k.flight_vy)
_atom_energy = _jit(_k.atom_energy)
_pair_time = _jit(_k.pair_contact_time)
_wall_time = _jit(_k.wall_contact_time)
_exit_time = _jit(_k.exit_time)
_collide = _jit(_k.collide_pair)
_reflect = _jit(_k.reflect_wall)
_bounce = _jit(
    types.FunctionType(
        _k.bounce_wall.__code__, {**vars(_k), "reflect_wall": _reflect}, "bounce_wall"
    )
)
# settle_wall calls reflect_wall: compile it against the compiled one.
_settle = _jit(
    types.FunctionType(
        _k.settle_wall.__code__, {**vars(_k), "reflect_wall": _reflect}, "settle_wall"
    )
)

# The engine keeps its atoms in a few row-per-atom tables (one cache line of
# floats per atom; few arrays also keep Numba's reference counting cheap) and
# copies them from and to the World around every call.
# S, float: stored state, radius, collision counter and the atom's index in the World
# (both exact as floats): the pair scan and the partner check read them with the
# state, on the same cache line.
X, Y, VX, VY, T, R, CNT, SID = range(8)
# A, int32: lifecycle status, cell, previous in cell, and the atom's index in the World
# (see "rows" below): the last columns of V's rows (A and V are one table, so an
# atom's integers fill one cache line), named apart for reading.
# head, int: the first atom of every cell, then the next atom in cell of every
# atom (one array: the pair scan walks it only).
A_ST, A_CX, A_CY, A_PRV, A_ID = range(11, 16)
# E, float: key time, real-event time, crossing time, the time of the arc's last y
# crossing, mass; then the queue's links (Q_POS.. below), read through an int32
# view Q of the same rows, so filing an atom touches the line that holds its key.
E_KEY, E_RT, E_CT, E_TLY, E_M = range(5)
# V, int: the event tables. Each atom has a real event (wall, exit or pair) and a
# cell crossing; its heap key is the earlier of the two.
V_RANK, V_A, V_B = range(3)  # key: rank, then two tie-break indices
V_RR, V_RA, V_RB, V_KIND, V_ARG, V_PC = range(3, 9)  # real: key parts, kind, partner, its counter
V_XK, V_XT = 9, 10  # crossing: axis kind and target cell coordinate

# Internal event kinds.
K_NONE = 0
K_PAIR = 1
K_WALL = 2
K_EXIT = 3
K_CROSS_X = 4
K_CROSS_Y = 5

# Ranks order events of equal time: a cell crossing changes no state and may
# reveal a partner, so it goes first; then solo events (the reference engine
# prefers them to pairs on a tie); then pairs by (lower, higher) index.
R_CROSS = -1
R_SOLO = 0
R_PAIR = 1

# Float parameters fp and integer parameters ip (fixed for the engine's life).
P_G, P_A, P_GX0, P_GY0, P_CS, P_XL, P_XR, P_YB = range(8)
Q_NX, Q_NY, Q_KNIFE, Q_RECORD, Q_RENUMBER, Q_DEEP = range(6)
# Running scalars: floats fs and integers js (copied from/to the World).
S_TIME, S_ESUM, S_XRIM, S_H = range(4)
J_WON, J_NTRAP, J_PAIRS, J_WALLS = range(4)
# Engine-only event counts (stats): cell crossings and stale pair events; and
# events since the rows were last put in cell order.
ST_CROSS, ST_STALE, ST_SINCE = range(3)

LOG_CAPACITY = 1 << 16
_LOG_ROOM = 4  # the most log lines one event can write (pair + two knives)

#: Cell edge in contact distances; > 1 leaves room for round-off in crossing times.
CELL_FACTOR = 1.1
#: The nominal box reaches the height this percentile of trapped atoms can reach.
BOX_PERCENTILE = 99.5
#: At most this many cells per atom (bounds memory for tiny, sparse atoms).
MAX_CELLS_PER_ATOM = 8
#: Rows are put back in cell order every this many events per atom.
RENUMBER_EVENTS_PER_ATOM = 8
#: From this many atoms the tables are far beyond the caches the core has to itself,
#: and the event loop asks two events ahead for the rows the scans will read (with
#: fewer atoms they are found in cache anyway, and the asking only costs time).
DEEP_MIN_ATOMS = 20_000

# Rows: the engine's tables hold atom i of the World in row rows[i], not row i.
# Every so often the rows are renumbered in cell order (row-major), so that the
# atoms of neighbouring cells sit next to each other in memory: the pair scans
# of big systems then hit the cache instead of main memory. Everything that
# orders events or is seen outside (tie-break indices, the log, the knife's
# ascending order, pull and push) uses the World index A_ID, never the row.


# -- prefetch -------------------------------------------------------------------------
@intrinsic
def _prefetch(typingctx, arr, i):
    """Hint the CPU to start loading row i of arr (a cache-line read, no fault).

    Why: at 10^5 atoms the tables outgrow the caches and each event starts with
    misses on its atom's rows; fetching the likely next atom's rows during the
    current event overlaps those misses with useful work. No effect on results.
    """

    def codegen(context, builder, sig, args):
        aryty = sig.args[0]
        ary = context.make_array(aryty)(context, builder, args[0])
        row = context.cast(builder, args[1], sig.args[1], nt.intp)
        idx = [row] + [ir.Constant(ir.IntType(64), 0)] * (aryty.ndim - 1)
        ptr = cgutils.get_item_pointer2(
            context, builder, ary.data,
            cgutils.unpack_tuple(builder, ary.shape),
            cgutils.unpack_tuple(builder, ary.strides),
            aryty.layout, idx, wraparound=False,
        )  # fmt: skip
        i8p = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        fnty = ir.FunctionType(ir.VoidType(), [i8p, i32, i32, i32])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "llvm.prefetch.p0")
        # read, high temporal locality, data cache
        builder.call(fn, [builder.bitcast(ptr, i8p), i32(0), i32(3), i32(1)])
        return context.get_dummy_value()

    return nt.void(arr, i), codegen


@_fni
def _prefetch_atom(j, S, E, V):
    """Start loading every table row of row j (queue links share E's row, A is in V's)."""
    _prefetch(S, j)
    _prefetch(E, j)
    _prefetch(V, j)


@_fni
def _coming_cells(j, A, V, nx, ny):
    """The block of cells atom j's next event will scan: (x0, x1, y0, y1), empty if x0 > x1.

    A crossing scans the row or column beyond its new cell; other events the 3 x 3
    block around it (a pair's partner scans around its own cell, not included).
    """
    ci = A[j, A_CX]
    cj = A[j, A_CY]
    x0 = ci - 1 if ci > 0 else 0
    x1 = ci + 1 if ci < nx - 1 else nx - 1
    y0 = cj - 1 if cj > 0 else 0
    y1 = cj + 1 if cj < ny - 1 else ny - 1
    if V[j, V_RANK] == R_CROSS:
        c = 2 * V[j, V_XT] - (ci if V[j, V_XK] == K_CROSS_X else cj)
        if V[j, V_XK] == K_CROSS_X:
            x0 = c
            x1 = c if 0 <= c < nx else c - 1
        else:
            y0 = c
            y1 = c if 0 <= c < ny else c - 1
    if A[j, A_ST] != TRAPPED:
        x1 = x0 - 1
    return x0, x1, y0, y1


@_fni
def _ask_heads(j, A, V, head, nx, ny):
    """Ask for the lines of cell heads atom j's next event will read."""
    x0, x1, y0, y1 = _coming_cells(j, A, V, nx, ny)
    if x0 <= x1:
        for yy in range(y0, y1 + 1):
            _prefetch(head, yy * nx + x0)


@_fni
def _ask_firsts(j, S, A, V, head, nx, ny):
    """Read those heads (asked for an event earlier) and ask for their atoms' rows.

    Most cells hold one atom or none, so the first is most of a scan's misses.
    No branch on empty cells: row 0 is asked for instead, harmlessly.
    """
    x0, x1, y0, y1 = _coming_cells(j, A, V, nx, ny)
    if x0 <= x1:
        for yy in range(y0, y1 + 1):
            for xx in range(x0, x1 + 1):
                _prefetch(S, max(head[yy * nx + xx], 0))


# -- event queue: a calendar of time bins in front of a small 4-ary heap ------------
# (Paul, J. Comput. Phys. 221, 615 (2007); Smallenburg 2022.) Time is cut into
# bins of width dt from a base time. Atoms whose key lies in the current bin or
# earlier sit in the heap, ordered by the full key; later ones sit, unordered,
# in the list of their bin (a ring of NB lists covering NB bins), beyond the
# ring in an overflow list, or with no event at all in a list of their own. The
# bin of a time is floor((t - base) / dt), monotone in t, so every heap key comes
# before every listed key: the heap's root is the earliest event, the order is
# the plain heap's. The heap stays small (about EVENTS_PER_BIN atoms), so its
# sifts stay in cache; filing an atom in a list touches two rows instead of a
# sift path through a heap of all atoms (which, at 10^5 atoms, misses the cache
# at every level). The bin width is set from the pending events whenever the
# queue is rebuilt (with the rows' renumbering).
# heap[p] (p < heap size) is a row and heap_t[p] its key time; Q[i] holds row i's
# heap place (-1 if listed), list (-1 if in the heap), and list neighbours.
Q_POS, Q_LST, Q_NXT, Q_PRV = range(12, 16)  # int32 columns: bytes 48-63 of E's row
# cal, int: heap size, current bin, bin of the last overflow scan, ring size, atoms
# in the ring, atoms in the overflow list, cursors walking the next two bins' lists
# ahead of time (prefetch); then the list heads: NB ring bins, the overflow list,
# the no-event list.
C_HN, C_CB, C_SCAN, C_NB, C_NRING, C_NOVER, C_CUR, C_CUR2 = range(8)
C_HEADS = 8
# calf, float: base time, bin width.
F_BASE, F_DT = range(2)
#: The bin width aims at this many events per bin (the heap's typical size).
EVENTS_PER_BIN = 8
#: The ring spans about this many events per atom into the future.
RING_EVENTS_PER_ATOM = 2


@_fni
def _less(x, tx, y, ty, V):
    """True if atom x's key comes before atom y's: (t, rank, a, b)."""
    if tx != ty:
        return tx < ty
    if V[x, V_RANK] != V[y, V_RANK]:
        return V[x, V_RANK] < V[y, V_RANK]
    if V[x, V_A] != V[y, V_A]:
        return V[x, V_A] < V[y, V_A]
    return V[x, V_B] < V[y, V_B]


@_fni
def _sift(p, heap, heap_t, Q, cal, V):
    """Move the entry at heap place p up or down to its place (children 4p+1..4p+4)."""
    n = cal[C_HN]
    i = heap[p]
    ti = heap_t[p]
    while p > 0:
        q = (p - 1) >> 2
        j = heap[q]
        tj = heap_t[q]
        if not _less(i, ti, j, tj, V):
            break
        heap[p] = j
        heap_t[p] = tj
        Q[j, Q_POS] = p
        p = q
    while True:
        c = 4 * p + 1
        if c >= n:
            break
        end = c + 4 if c + 4 <= n else n
        for d in range(c + 1, end):
            if _less(heap[d], heap_t[d], heap[c], heap_t[c], V):
                c = d
        if not _less(heap[c], heap_t[c], i, ti, V):
            break
        heap[p] = heap[c]
        heap_t[p] = heap_t[c]
        Q[heap[c], Q_POS] = p
        p = c
    heap[p] = i
    heap_t[p] = ti
    Q[i, Q_POS] = p


@_fni
def _heap_push(i, t, heap, heap_t, Q, cal, V):
    p = cal[C_HN]
    cal[C_HN] = p + 1
    heap[p] = i
    heap_t[p] = t
    _sift(p, heap, heap_t, Q, cal, V)


@_fni
def _list_add(i, lst, Q, cal):
    h = cal[C_HEADS + lst]
    Q[i, Q_LST] = lst
    Q[i, Q_NXT] = h
    Q[i, Q_PRV] = -1
    if h >= 0:
        Q[h, Q_PRV] = i
    cal[C_HEADS + lst] = i
    nb = cal[C_NB]
    if lst < nb:
        cal[C_NRING] += 1
    elif lst == nb:
        cal[C_NOVER] += 1


@_fni
def _list_del(i, Q, cal):
    lst = Q[i, Q_LST]
    p = Q[i, Q_PRV]
    q = Q[i, Q_NXT]
    if p >= 0:
        Q[p, Q_NXT] = q
    else:
        cal[C_HEADS + lst] = q
    if q >= 0:
        Q[q, Q_PRV] = p
    Q[i, Q_LST] = -1
    nb = cal[C_NB]
    if lst < nb:
        cal[C_NRING] -= 1
    elif lst == nb:
        cal[C_NOVER] -= 1


@_fni
def _place(i, t, heap, heap_t, Q, cal, calf, V):
    """File atom i under key time t: in the heap if its bin has come, else in a list."""
    q = (t - calf[F_BASE]) / calf[F_DT]
    cb = cal[C_CB]
    nb = cal[C_NB]
    p = Q[i, Q_POS]
    if q < cb + 1:  # bin <= current bin: into the heap, or moved within it
        if p < 0:
            if Q[i, Q_LST] >= 0:
                _list_del(i, Q, cal)
            p = cal[C_HN]
            cal[C_HN] = p + 1
            heap[p] = i
        heap_t[p] = t
    else:
        if t == INF:
            lst = nb + 1
        elif q < cb + nb:
            lst = int(q) % nb
        else:
            lst = nb
        if p < 0:
            if Q[i, Q_LST] == lst:  # lists are unordered: nothing to do
                return
            if Q[i, Q_LST] >= 0:
                _list_del(i, Q, cal)
        _list_add(i, lst, Q, cal)
        if p < 0:
            return
        # Out of the heap: its last entry fills the hole.
        Q[i, Q_POS] = -1
        last = cal[C_HN] - 1
        cal[C_HN] = last
        if p == last:
            return
        heap[p] = heap[last]
        heap_t[p] = heap_t[last]
    _sift(p, heap, heap_t, Q, cal, V)  # one call site: every inlined copy costs compile time


@_fn
def _rebuild(base, dt, E, V, heap, heap_t, Q, cal, calf):
    """Empty the queue and file every atom again, with a new base time and bin width."""
    nb = cal[C_NB]
    for k in range(C_HEADS + nb + 2):
        cal[k] = -1 if k >= C_HEADS else 0
    cal[C_NB] = nb
    cal[C_CUR] = -1
    cal[C_CUR2] = -1
    calf[F_BASE] = base
    calf[F_DT] = dt
    for i in range(Q.shape[0]):
        Q[i, Q_POS] = -1
        Q[i, Q_LST] = -1
    for i in range(Q.shape[0]):
        _place(i, E[i, E_KEY], heap, heap_t, Q, cal, calf, V)


@_fn
def _bin_width(now, E):
    """Bin width for EVENTS_PER_BIN events per bin, from the event rate of the bulk.

    Residual times of the pending events: their mean, trimmed twice to the bulk
    (a few atoms high above the cup or escaping would otherwise dominate it),
    over their count is the time between events.
    """
    m = INF
    for _ in range(3):
        s = 0.0
        c = 0
        for i in range(E.shape[0]):
            g = E[i, E_KEY] - now
            if g < m * 3.0:
                s += g if g > 0.0 else 0.0
                c += 1
        if c == 0 or s <= 0.0:
            return 1.0
        m = s / c
    return EVENTS_PER_BIN * m / c


@_fn  # once per bin: an ordinary call
def _next_bin(E, V, heap, heap_t, Q, cal, calf):
    """Fill the empty heap from the next non-empty bin; False if no atom has an event."""
    nb = cal[C_NB]
    while cal[C_HN] == 0:
        if cal[C_NRING] == 0:
            if cal[C_NOVER] == 0:
                return False
            # Nothing in the ring: jump to the overflow's earliest bin.
            m = INF
            j = cal[C_HEADS + nb]
            while j >= 0:
                if E[j, E_KEY] < m:
                    m = E[j, E_KEY]
                j = Q[j, Q_NXT]
            if not m < INF:  # no time at all (only a NaN could do this): nothing to pop
                return False
            q = (m - calf[F_BASE]) / calf[F_DT]
            if q > 1e15:  # far beyond: start the bins there
                _rebuild(m, calf[F_DT], E, V, heap, heap_t, Q, cal, calf)
                continue
            cal[C_CB] = int(q) - 1  # q > 0 beyond the ring: int() is floor
            cal[C_SCAN] = cal[C_CB] - nb
        cb = cal[C_CB] + 1
        cal[C_CB] = cb
        if cb >= cal[C_SCAN] + nb:  # the ring moved on by its length: refile the overflow
            cal[C_SCAN] = cb
            j = cal[C_HEADS + nb]
            while j >= 0:
                k = Q[j, Q_NXT]
                _place(j, E[j, E_KEY], heap, heap_t, Q, cal, calf, V)
                j = k
        s = C_HEADS + cb % nb
        j = cal[s]
        cal[s] = -1
        while j >= 0:
            k = Q[j, Q_NXT]
            Q[j, Q_LST] = -1
            cal[C_NRING] -= 1
            _heap_push(j, E[j, E_KEY], heap, heap_t, Q, cal, V)
            j = k
    # The cursor of the bin after the next goes on along the same list.
    cal[C_CUR] = cal[C_CUR2] if cal[C_CUR2] >= 0 else cal[C_HEADS + (cal[C_CB] + 1) % nb]
    j = cal[C_HEADS + (cal[C_CB] + 2) % nb]
    cal[C_CUR2] = j
    if j >= 0:
        _prefetch(E, j)
    return True


@_fni
def _walk_step(j, lst, E, V, Q, deep):
    """One step of a cursor along list lst: the next row, asked for; -1 at the end.

    deep: its V row too (its cells are read two events before its own).
    """
    if j < 0 or Q[j, Q_LST] != lst:  # the atom left the list: its links moved on
        return -1
    j = Q[j, Q_NXT]
    if j >= 0:
        _prefetch(E, j)
        if deep:
            _prefetch(V, j)
    return j


@_fni
def _walk_ahead(E, V, Q, cal, deep):
    """Walk the lists of the next two bins one step each (their dumps then hit the cache).

    A list is a chain of rows: walked only when its bin comes, every step would
    wait for memory. Each step reads a row asked for one event earlier, and a list
    is walked for two bins' time, as fast as bins fill.
    """
    nb = cal[C_NB]
    cb = cal[C_CB]
    cal[C_CUR] = _walk_step(cal[C_CUR], (cb + 1) % nb, E, V, Q, deep)
    cal[C_CUR2] = _walk_step(cal[C_CUR2], (cb + 2) % nb, E, V, Q, deep)


@_fni
def _set_key(i, A, E, V, heap, heap_t, Q, cal, calf):
    """Atom i's key is the earlier of its crossing and its real event; refile it."""
    if E[i, E_CT] <= E[i, E_RT]:  # a crossing goes first on a tie
        E[i, E_KEY] = E[i, E_CT]
        V[i, V_RANK] = R_CROSS
        V[i, V_A] = A[i, A_ID]
        V[i, V_B] = V[i, V_XK]
    else:
        E[i, E_KEY] = E[i, E_RT]
        V[i, V_RANK] = V[i, V_RR]
        V[i, V_A] = V[i, V_RA]
        V[i, V_B] = V[i, V_RB]
    _place(i, E[i, E_KEY], heap, heap_t, Q, cal, calf, V)


# -- grid ---------------------------------------------------------------------------
@_fni
def _clamp_cell(u, u0, cs, n):
    """Cell coordinate of u; the edge cells reach to infinity."""
    c = math.floor((u - u0) / cs)
    if c < 0.0:
        return 0
    if c > n - 1:
        return n - 1
    return int(c)


@_fni
def _unlink(i, A, head, nx):
    nc = head.shape[0] - A.shape[0]
    p = A[i, A_PRV]
    q = head[nc + i]
    if p >= 0:
        head[nc + p] = q
    else:
        head[A[i, A_CY] * nx + A[i, A_CX]] = q
    if q >= 0:
        A[q, A_PRV] = p
    head[nc + i] = -1
    A[i, A_PRV] = -1


@_fni
def _link(i, ci, cj, A, head, nx):
    A[i, A_CX] = ci
    A[i, A_CY] = cj
    c = cj * nx + ci
    q = head[c]
    head[head.shape[0] - A.shape[0] + i] = q
    A[i, A_PRV] = -1
    if q >= 0:
        A[q, A_PRV] = i
    head[c] = i


# -- predictions ----------------------------------------------------------------------
@_fni
def _scan(i, xlo, xhi, ylo, yhi, S, A, E, V, head, fp, ip):
    """Pairs of trapped atom i with the atoms of cells [xlo, xhi] x [ylo, yhi].

    Contact times are seed Eqs. (15)-(19) (kernels.pair_contact_time); an
    earlier pair replaces i's real event. On a tie the solo event stays and
    pairs go in (lower, higher) index order, as in the reference engine.
    """
    nx = ip[Q_NX]
    nc = head.shape[0] - S.shape[0]
    g = fp[P_G]
    x = S[i, X]
    y = S[i, Y]
    vx = S[i, VX]
    vy = S[i, VY]
    t0 = S[i, T]
    ri = S[i, R]
    bt = E[i, E_RT]
    pair = V[i, V_RR] == R_PAIR
    ba = V[i, V_RA]
    bb = V[i, V_RB]
    ii = int(S[i, SID])
    best = -1
    for yy in range(ylo, yhi + 1):
        for xx in range(xlo, xhi + 1):
            j = head[yy * nx + xx]
            while j >= 0:
                if j != i:
                    t = _pair_time(
                        x, y, vx, vy, t0,
                        S[j, X], S[j, Y], S[j, VX], S[j, VY], S[j, T],
                        ri + S[j, R], g,
                    )  # fmt: skip
                    if t <= bt:  # rare: only now read j's World index
                        jj = int(S[j, SID])
                        lo = ii if ii < jj else jj
                        hi = jj if ii < jj else ii
                        if t < bt or (pair and (lo < ba or (lo == ba and hi < bb))):
                            bt = t
                            pair = True
                            ba = lo
                            bb = hi
                            best = j
                j = head[nc + j]
    if best >= 0:
        E[i, E_RT] = bt
        V[i, V_RR] = R_PAIR
        V[i, V_RA] = ba
        V[i, V_RB] = bb
        V[i, V_KIND] = K_PAIR
        V[i, V_ARG] = best
        V[i, V_PC] = int(S[best, CNT])  # low 32 bits


@_fni
def _predict_real(i, S, A, E, V, head, fp, ip, won):
    """Atom i's real event: wall (SPEC 2.1) or pair if trapped, exit if escaped."""
    g = fp[P_G]
    st = A[i, A_ST]
    t = INF
    kind = K_NONE
    if st == TRAPPED:
        t = _wall_time(S[i, X], S[i, Y], S[i, VX], S[i, VY], S[i, T], fp[P_A], g)
        kind = K_WALL
    elif st == ESCAPED:
        r = S[i, R]
        t = _exit_time(
            S[i, X], S[i, Y], S[i, VX], S[i, VY], S[i, T], g,
            fp[P_XL] - r, fp[P_XR] + r, fp[P_YB] - r,
        )  # fmt: skip
        kind = K_EXIT
    E[i, E_RT] = t
    V[i, V_RR] = R_SOLO
    V[i, V_RA] = A[i, A_ID]
    V[i, V_RB] = 0
    V[i, V_KIND] = kind
    if st == TRAPPED and not won:
        nx = ip[Q_NX]
        ny = ip[Q_NY]
        ci = A[i, A_CX]
        cj = A[i, A_CY]
        _scan(
            i,
            ci - 1 if ci > 0 else 0,
            ci + 1 if ci < nx - 1 else nx - 1,
            cj - 1 if cj > 0 else 0,
            cj + 1 if cj < ny - 1 else ny - 1,
            S, A, E, V, head, fp, ip,
        )  # fmt: skip


@_fni
def _predict_cross(i, S, A, E, V, fp, ip, won):
    """Atom i's next cell crossing (none unless trapped and the game is on).

    x: straight line to the next edge in the direction of vx. y: up through
    the top edge (first root, if the arc really passes it: a grazing arc with
    equal roots stays below), else down through the bottom edge; roots at or
    before the arc's last y crossing (TLY) are ones already taken. Roots in
    the cancellation-free form. Clamped edge cells have no outer edge.
    """
    bt = INF
    bk = K_NONE
    barg = 0
    if A[i, A_ST] == TRAPPED and not won:
        g = fp[P_G]
        cs = fp[P_CS]
        nx = ip[Q_NX]
        ny = ip[Q_NY]
        x = S[i, X]
        y = S[i, Y]
        vx = S[i, VX]
        vy = S[i, VY]
        t0 = S[i, T]
        ci = A[i, A_CX]
        cj = A[i, A_CY]
        if vx > 0.0 and ci < nx - 1:
            bt = t0 + ((fp[P_GX0] + (ci + 1) * cs) - x) / vx
            bk = K_CROSS_X
            barg = ci + 1
        elif vx < 0.0 and ci > 0:
            bt = t0 + ((fp[P_GX0] + ci * cs) - x) / vx
            bk = K_CROSS_X
            barg = ci - 1
        tc = INF
        tgt = 0
        tl = E[i, E_TLY]
        if vy > 0.0 and cj < ny - 1:
            d = (fp[P_GY0] + (cj + 1) * cs) - y
            disc = vy * vy - 2.0 * g * d
            if disc > 0.0:
                s = math.sqrt(disc)
                t1 = t0 + 2.0 * d / (vy + s)
                t2 = t0 + (vy + s) / g
                if t2 > t1 and t1 > tl:
                    tc = t1
                    tgt = cj + 1
        if tc == INF and cj > 0:
            h = y - (fp[P_GY0] + cj * cs)
            disc = vy * vy + 2.0 * g * h
            if disc < 0.0:
                disc = 0.0
            s = math.sqrt(disc)
            if vy > 0.0:
                t2 = t0 + (vy + s) / g
            elif s - vy > 0.0:
                t2 = t0 + 2.0 * h / (s - vy)
            else:
                t2 = t0
            if t2 > tl:
                tc = t2
                tgt = cj - 1
        if tc < bt:  # x before y on a tie
            bt = tc
            bk = K_CROSS_Y
            barg = tgt
    E[i, E_CT] = bt
    V[i, V_XK] = bk
    V[i, V_XT] = barg


@_fn  # an ordinary call, off the hot loop (which has its own inlined copy of the parts)
def _predict(i, S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, won):
    """Everything about atom i from its stored state; store it and refile it."""
    _predict_real(i, S, A, E, V, head, fp, ip, won)
    _predict_cross(i, S, A, E, V, fp, ip, won)
    _set_key(i, A, E, V, heap, heap_t, Q, cal, calf)


# -- state changes ------------------------------------------------------------------
@_fni
def _move(i, t, S, E, g):
    """Carry atom i's stored state to time t (exact free flight, seed Eqs. 3-4)."""
    dt = t - S[i, T]
    S[i, X] = _flight_x(S[i, X], S[i, VX], dt)
    S[i, Y] = _flight_y(S[i, Y], S[i, VY], 0.5 * g, dt)
    S[i, VY] = _flight_vy(S[i, VY], g, dt)
    S[i, T] = t
    E[i, E_TLY] = -INF  # a new arc: none of its y crossings taken yet


@_fni
def _energy(i, S, E, g):
    return _atom_energy(E[i, E_M], S[i, Y], S[i, VX], S[i, VY], g)


@_fni
def _log(kind, i, j, t, ip, log_i, log_t, nlog):
    if ip[Q_RECORD] != 0:
        log_i[nlog, 0] = kind
        log_i[nlog, 1] = i
        log_i[nlog, 2] = j
        log_t[nlog] = t
        return nlog + 1
    return nlog


@_fn
def _check_win(fs, js, tc_table):
    """T < Tc(N) with the running energy sum (seed Eqs. 1 and 46)."""
    n = js[J_NTRAP]
    if js[J_WON] != 0 or n == 0:
        return
    if fs[S_ESUM] / n < tc_table[n]:
        js[J_WON] = 1


@_fn
def _remove(i, new_status, S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, fs, js, tc_table):
    """Atom i leaves the trapped set: off the grid, solo prediction, win check."""
    A[i, A_ST] = new_status
    js[J_NTRAP] -= 1
    fs[S_ESUM] -= _energy(i, S, E, fp[P_G])
    S[i, CNT] += 1.0
    _unlink(i, A, head, ip[Q_NX])
    _predict(i, S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, js[J_WON] != 0)
    _check_win(fs, js, tc_table)


@_fn
def _knife(
    i, t, S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, fs, js, tc_table, log_i, log_t, nlog
):
    """Remove trapped atom i at once if its energy exceeds m g H; returns (removed, nlog)."""
    if ip[Q_KNIFE] == 0:
        return False, nlog
    if _energy(i, S, E, fp[P_G]) > E[i, E_M] * fp[P_G] * fs[S_H]:
        nlog = _log(EV_KNIFE, A[i, A_ID], -1, t, ip, log_i, log_t, nlog)
        _remove(i, GONE, S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, fs, js, tc_table)
        return True, nlog
    return False, nlog


# -- entry points ---------------------------------------------------------------------
@_fn
def _pull(S, A, rows, pos, vel, t_atom, status, counter):
    """World arrays -> engine tables."""
    for k in range(S.shape[0]):
        i = rows[k]
        S[i, X] = pos[k, 0]
        S[i, Y] = pos[k, 1]
        S[i, VX] = vel[k, 0]
        S[i, VY] = vel[k, 1]
        S[i, T] = t_atom[k]
        A[i, A_ST] = status[k]
        S[i, CNT] = counter[k]


@_fn
def _push(S, A, rows, pos, vel, t_atom, status, counter):
    """Engine tables -> World arrays."""
    for k in range(S.shape[0]):
        i = rows[k]
        pos[k, 0] = S[i, X]
        pos[k, 1] = S[i, Y]
        vel[k, 0] = S[i, VX]
        vel[k, 1] = S[i, VY]
        t_atom[k] = S[i, T]
        status[k] = A[i, A_ST]
        counter[k] = int(S[i, CNT])


@_fn
def _permute_rows(T, dest, scratch, off):
    """Row j of T moves to row dest[j]; scratch[:, off:] holds the copy meanwhile."""
    for j in range(T.shape[0]):
        for q in range(T.shape[1]):
            scratch[j, off + q] = T[j, q]
    for j in range(T.shape[0]):
        r = dest[j]
        for q in range(T.shape[1]):
            T[r, q] = scratch[j, off + q]


@_fn
def _renumber(S, A, E, V, heap, heap_t, Q, cal, calf, head, rows, fsc, isc, nx, now):
    """Renumber the rows in cell order (row-major), the atoms off the grid last.

    Walks the cell lists, so the atoms of one cell get consecutive rows; then
    moves every table row, relabels every row reference (partners, rows),
    rebuilds the cell lists and refiles the queue from the current time. The
    events, their keys and the in-cell order's irrelevance (a scan keeps the
    least (t, rank, lo, hi) whatever the order it meets the pairs in) leave the
    event sequence unchanged.
    """
    n = S.shape[0]
    nc = head.shape[0] - n
    # isc[old row, 0] = new row (plain loops: slicing would need Numba's runtime).
    for j in range(n):
        isc[j, 0] = -1
    k = 0
    for c in range(nc):
        j = head[c]
        while j >= 0:
            isc[j, 0] = k
            k += 1
            j = head[nc + j]
    nlinked = k
    for o in range(n):
        j = rows[o]
        if isc[j, 0] < 0:
            isc[j, 0] = k
            k += 1
    # Move the rows through the scratch tables, then relabel the row references.
    dest = isc[:, 0]
    _permute_rows(S, dest, fsc, 0)
    _permute_rows(E, dest, fsc, 0)
    # A is columns of V (moved with it below).
    for j in range(n):
        for q in range(V.shape[1]):
            isc[j, 1 + q] = V[j, q]
    for j in range(n):
        r = isc[j, 0]
        for q in range(V.shape[1]):
            V[r, q] = isc[j, 1 + q]
    for i in range(n):
        V[i, V_ARG] = isc[V[i, V_ARG], 0]
    for o in range(n):
        rows[o] = isc[rows[o], 0]
    # Cell lists: linking in descending row order leaves each in ascending order.
    for c in range(head.shape[0]):
        head[c] = -1
    for i in range(n):
        A[i, A_PRV] = -1
    for i in range(nlinked - 1, -1, -1):
        _link(i, A[i, A_CX], A[i, A_CY], A, head, nx)
    _rebuild(now, _bin_width(now, E), E, V, heap, heap_t, Q, cal, calf)


@_fn
def _setup(S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, now, won):
    """Put trapped atoms in their cells (positions at now) and predict every atom."""
    n = S.shape[0]
    g = fp[P_G]
    head[:] = -1
    for i in range(n):
        A[i, A_PRV] = -1
        E[i, E_KEY] = INF
        E[i, E_RT] = INF
        E[i, E_CT] = INF
        E[i, E_TLY] = -INF
        for q in range(V_XT + 1):  # V's own columns (A's follow them in the row)
            V[i, q] = 0
        V[i, V_A] = A[i, A_ID]
        if A[i, A_ST] == TRAPPED:
            dt = now - S[i, T]
            xn = _flight_x(S[i, X], S[i, VX], dt)
            yn = _flight_y(S[i, Y], S[i, VY], 0.5 * g, dt)
            ci = _clamp_cell(xn, fp[P_GX0], fp[P_CS], ip[Q_NX])
            cj = _clamp_cell(yn, fp[P_GY0], fp[P_CS], ip[Q_NY])
            _link(i, ci, cj, A, head, ip[Q_NX])
    # Every finite key in the heap for now (bin width inf), the bins set after.
    _rebuild(now, INF, E, V, heap, heap_t, Q, cal, calf)
    for i in range(n):
        _predict(i, S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, won)
    _rebuild(now, _bin_width(now, E), E, V, heap, heap_t, Q, cal, calf)


@_fn
def _advance(
    t_end, S, A, E, V, heap, heap_t, Q, cal, calf, head, rows, fsc, isc, fp, ip, fs, js, tc_table,
    log_i, log_t, stats,
):  # fmt: skip
    """Process every event with time <= t_end in order; returns (done, log lines).

    Mirrors ReferenceEngine.advance_to event for event. Stops early (done
    False) when the log buffer is nearly full.
    """
    g = fp[P_G]
    a = fp[P_A]
    nx = ip[Q_NX]
    ny = ip[Q_NY]
    # Without recording nothing is logged and the buffer is never full.
    cap = log_i.shape[0] - _LOG_ROOM if ip[Q_RECORD] != 0 else 1 << 62
    nlog = 0
    every = ip[Q_RENUMBER]
    deep = ip[Q_DEEP] != 0
    while True:
        if nlog > cap:
            return False, nlog
        stats[ST_SINCE] += 1
        if stats[ST_SINCE] > every:
            _renumber(S, A, E, V, heap, heap_t, Q, cal, calf, head, rows, fsc, isc, nx, fs[S_TIME])
            stats[ST_SINCE] = 0
        if cal[C_HN] == 0:
            if not _next_bin(E, V, heap, heap_t, Q, cal, calf):
                break  # no atom has an event
            for p in range(cal[C_HN]):  # a new bin: its atoms' events are the next few
                _prefetch(V, heap[p])
                _prefetch(S, heap[p])
        i = heap[0]
        te = heap_t[0]
        if not te <= t_end:
            break
        # The next event is most likely the earliest child of the root's: load
        # its rows while this event is processed.
        nh = cal[C_HN]
        nxt = -1
        if nh > 1:
            c = 1
            end = 5 if nh >= 5 else nh
            for d in range(2, end):
                if heap_t[d] < heap_t[c]:
                    c = d
            nxt = heap[c]
            _prefetch_atom(nxt, S, E, V)
            if deep and nh > 2:
                # The event after the next: the earliest of the root's other children
                # and the next one's children (its rows came with its bin).
                p2 = -1
                t2 = INF
                for d in range(1, end):
                    if d != c and heap_t[d] < t2:
                        p2 = d
                        t2 = heap_t[d]
                for d in range(4 * c + 1, 4 * c + 5 if 4 * c + 5 <= nh else nh):
                    if heap_t[d] < t2:
                        p2 = d
                        t2 = heap_t[d]
                if p2 >= 0:
                    _ask_heads(heap[p2], A, V, head, nx, ny)
        won = js[J_WON] != 0
        kind = V[i, V_XK] if V[i, V_RANK] == R_CROSS else V[i, V_KIND]
        if kind == K_PAIR:  # the partner's rows, while the counters are compared
            _prefetch_atom(V[i, V_ARG], S, E, V)
        if A[i, A_ST] == TRAPPED:  # the heads of the cells the scan will walk
            ci = A[i, A_CX]
            cx = ci - 1 if ci > 0 else 0
            cj = A[i, A_CY]
            for yy in range(cj - 1 if cj > 0 else 0, cj + 2 if cj < ny - 1 else ny):
                _prefetch(head, yy * nx + cx)
        # After the event: rp's prediction (full, or only its crossing if the real
        # event stands), then the pair's second atom's knife test and prediction.
        # One site for all: _predict's parts are inlined, every site costs code.
        rp = -1
        full = True
        pend = -1
        t = te
        if kind == K_PAIR:
            j = V[i, V_ARG]
            # V_PC holds the low 32 bits of the partner's counter (V is int32).
            if won or (int(S[j, CNT]) - V[i, V_PC]) & 0xFFFFFFFF != 0:
                stats[ST_STALE] += 1  # the partner moved on (or pairs are over)
                rp = i
            else:
                lo = i  # lo, hi: the rows of the lower and higher World index
                hi = j
                if S[j, SID] < S[i, SID]:  # S rows: in hand already
                    lo = j
                    hi = i
                t = te if te >= fs[S_TIME] else fs[S_TIME]
                fs[S_TIME] = t
                _move(lo, t, S, E, g)
                _move(hi, t, S, E, g)
                v = _collide(
                    S[hi, X] - S[lo, X], S[hi, Y] - S[lo, Y],
                    S[lo, VX], S[lo, VY], S[hi, VX], S[hi, VY], E[lo, E_M], E[hi, E_M],
                )  # fmt: skip
                S[lo, VX] = v[0]
                S[lo, VY] = v[1]
                S[hi, VX] = v[2]
                S[hi, VY] = v[3]
                js[J_PAIRS] += 1
                S[lo, CNT] += 1.0
                S[hi, CNT] += 1.0
                nlog = _log(EV_PAIR, A[lo, A_ID], A[hi, A_ID], t, ip, log_i, log_t, nlog)
                gone, nlog = _knife(
                    lo, t, S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, fs, js,
                    tc_table, log_i, log_t, nlog,
                )  # fmt: skip
                if not gone:
                    rp = lo
                pend = hi
        elif kind in (K_CROSS_X, K_CROSS_Y):
            stats[ST_CROSS] += 1
            if won:  # the grid is no longer kept once the gas has condensed
                rp = i
            else:
                # Into the next cell. Only the row or column of cells that just came
                # within reach needs scanning (Smallenburg 2022): pairs with the
                # other neighbours are already held by i or by the partner.
                ci = A[i, A_CX]
                cj = A[i, A_CY]
                tgt = V[i, V_XT]
                _unlink(i, A, head, nx)
                if kind == K_CROSS_X:
                    _link(i, tgt, cj, A, head, nx)
                    c = tgt + (tgt - ci)
                    inside = 0 <= c < nx
                    x0 = c
                    x1 = c
                    y0 = cj - 1 if cj > 0 else 0
                    y1 = cj + 1 if cj < ny - 1 else ny - 1
                else:
                    _link(i, ci, tgt, A, head, nx)
                    E[i, E_TLY] = te
                    c = tgt + (tgt - cj)
                    inside = 0 <= c < ny
                    x0 = ci - 1 if ci > 0 else 0
                    x1 = ci + 1 if ci < nx - 1 else nx - 1
                    y0 = c
                    y1 = c
                if inside:
                    _scan(i, x0, x1, y0, y1, S, A, E, V, head, fp, ip)
                rp = i
                full = False
        elif kind == K_WALL:
            t = te if te >= fs[S_TIME] else fs[S_TIME]
            fs[S_TIME] = t
            _move(i, t, S, E, g)
            x = S[i, X]
            if abs(x) > fs[S_XRIM]:  # over the rim: escaped (SPEC 2.3)
                nlog = _log(EV_ESCAPE, A[i, A_ID], -1, t, ip, log_i, log_t, nlog)
                _remove(
                    i, ESCAPED, S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, fs, js,
                    tc_table,
                )  # fmt: skip
                continue
            vx = S[i, VX]
            vy = S[i, VY]
            speed = math.sqrt(vx * vx + vy * vy)
            damped = won and speed >= WIN_DAMPING_MIN_SPEED  # seed Eq. (34)
            if damped or speed < WALL_MIN_NORMAL_SPEED:  # the energy changes
                fs[S_ESUM] -= _energy(i, S, E, g)
            if damped:  # with a floor on the normal speed (no collapse)
                w = _settle(x, vx, vy, a, 1.0 - WIN_DAMPING, WIN_NORMAL_SPEED_FLOOR)
            else:  # at least WALL_MIN_NORMAL_SPEED along the normal (no stall)
                w = _bounce(x, vx, vy, a, WALL_MIN_NORMAL_SPEED)
            S[i, VX] = w[0]
            S[i, VY] = w[1]
            if damped or speed < WALL_MIN_NORMAL_SPEED:
                fs[S_ESUM] += _energy(i, S, E, g)
            js[J_WALLS] += 1
            S[i, CNT] += 1.0
            nlog = _log(EV_WALL, A[i, A_ID], -1, t, ip, log_i, log_t, nlog)
            rp = i
        elif kind == K_EXIT:
            t = te if te >= fs[S_TIME] else fs[S_TIME]
            fs[S_TIME] = t
            _move(i, t, S, E, g)
            A[i, A_ST] = GONE
            S[i, CNT] += 1.0
            nlog = _log(EV_GONE, A[i, A_ID], -1, t, ip, log_i, log_t, nlog)
            rp = i
        else:
            break
        # Ahead of the next event: the likely next atom's rows asked for at the top
        # have come, so its partner's rows and its cells' heads can be asked for
        # (before the predictions, the slow part: they arrive meanwhile).
        if nxt >= 0:
            if V[nxt, V_RANK] != R_CROSS and V[nxt, V_KIND] == K_PAIR:
                _prefetch_atom(V[nxt, V_ARG], S, E, V)
            if deep:  # its heads were asked for an event ago: now its neighbours' rows
                _ask_firsts(nxt, S, A, V, head, nx, ny)
            elif A[nxt, A_ST] == TRAPPED:  # its cells' heads
                ci = A[nxt, A_CX]
                cx = ci - 1 if ci > 0 else 0
                cj = A[nxt, A_CY]
                if V[nxt, V_RANK] == R_CROSS and V[nxt, V_XK] == K_CROSS_Y:
                    # Into the next row of cells: the row beyond it is the one scanned.
                    yy = 2 * V[nxt, V_XT] - cj
                    if 0 <= yy < ny:
                        _prefetch(head, yy * nx + cx)
                else:
                    for yy in range(cj - 1 if cj > 0 else 0, cj + 2 if cj < ny - 1 else ny):
                        _prefetch(head, yy * nx + cx)
        while True:
            if rp >= 0:
                w = js[J_WON] != 0
                if full:
                    _predict_real(rp, S, A, E, V, head, fp, ip, w)
                _predict_cross(rp, S, A, E, V, fp, ip, w)
                _set_key(rp, A, E, V, heap, heap_t, Q, cal, calf)
            if pend < 0:
                break
            rp = pend
            pend = -1
            gone, nlog = _knife(
                rp, t, S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, fs, js,
                tc_table, log_i, log_t, nlog,
            )  # fmt: skip
            if gone:
                rp = -1
        _walk_ahead(E, V, Q, cal, deep)
    return True, nlog


@_fn
def _knife_all(
    S, A, E, V, heap, heap_t, Q, cal, calf, head, rows, fp, ip, fs, js, tc_table, log_i, log_t
):
    """The knife at the clock time, in ascending atom order; returns log lines."""
    nlog = 0
    for k in range(S.shape[0]):  # ascending World index
        i = rows[k]
        if A[i, A_ST] == TRAPPED:
            _, nlog = _knife(
                i, fs[S_TIME], S, A, E, V, heap, heap_t, Q, cal, calf, head, fp, ip, fs, js,
                tc_table, log_i, log_t, nlog,
            )  # fmt: skip
    return nlog


@_fn
def _grid_errors(S, A, fp, ip, now):
    """Trapped atoms filed more than one cell away from the cell of their centre now."""
    bad = 0
    g = fp[P_G]
    for i in range(S.shape[0]):
        if A[i, A_ST] != TRAPPED:
            continue
        dt = now - S[i, T]
        xn = _flight_x(S[i, X], S[i, VX], dt)
        yn = _flight_y(S[i, Y], S[i, VY], 0.5 * g, dt)
        ci = _clamp_cell(xn, fp[P_GX0], fp[P_CS], ip[Q_NX])
        cj = _clamp_cell(yn, fp[P_GY0], fp[P_CS], ip[Q_NY])
        if abs(ci - A[i, A_CX]) > 1 or abs(cj - A[i, A_CY]) > 1:
            bad += 1
    return bad


# -- the engine -----------------------------------------------------------------------
def _rows(n: int, width: int, dtype: type, fill: float) -> np.ndarray:
    """An (n, width) table whose rows start on 64-byte cache-line boundaries.

    NumPy aligns to 16 bytes only: a 64-byte row would then straddle two lines,
    and every visit to an atom would cost two cache misses instead of one.
    """
    itemsize = np.dtype(dtype).itemsize
    nbytes = n * width * itemsize
    buf = np.empty(nbytes + 64, dtype=np.uint8)
    start = -buf.ctypes.data % 64
    rows = buf[start : start + nbytes].view(dtype).reshape(n, width)
    rows.fill(fill)
    return rows


class FastEngine:
    """Event-driven hard disks in the cup: Numba, cells, one event per atom in a heap."""

    name = "fast"

    def __init__(self, world: World) -> None:
        self.w = world
        n = len(world.radius)
        g = float(world.gravity)
        a = float(world.curvature)
        cs = CELL_FACTOR * 2.0 * float(np.max(world.radius))
        # Nominal box: the cup below the height the most energetic atoms reach
        # (a high percentile: outliers just sit in the clamped edge cells).
        trapped = world.status == TRAPPED
        heights = world.energies()[trapped] / (world.mass[trapped] * g)
        top = float(np.percentile(heights, BOX_PERCENTILE)) if len(heights) else 1.0
        y_top = max(top, 1.0) + cs
        half_w = math.sqrt(y_top / a) + cs
        max_cells = MAX_CELLS_PER_ATOM * n + 64
        if (2.0 * half_w / cs) * (y_top / cs) > max_cells:
            cs = math.sqrt(2.0 * half_w * y_top / max_cells)
        nx = max(1, math.ceil(2.0 * half_w / cs))
        ny = max(1, math.ceil((y_top + 0.5 * cs) / cs))
        self.fp = np.array(
            [g, a, -0.5 * nx * cs, -0.5 * cs, cs, world.x_left, world.x_right, world.y_bottom]
        )
        renumber = RENUMBER_EVENTS_PER_ATOM * n
        self.ip = np.array(
            [nx, ny, int(world.knife), int(world.record_events), renumber, n >= DEEP_MIN_ATOMS],
            dtype=np.int64,
        )
        self.S = _rows(n, 8, np.float64, 0.0)
        self.S[:, R] = world.radius
        self.V = _rows(n, 16, np.int32, 0)  # the event tables, then A: one cache line
        self.A = self.V
        self.A[:, A_ID] = np.arange(n)
        self.S[:, SID] = np.arange(n)
        self.rows = np.arange(n, dtype=np.int64)
        # Scratch tables for renumbering (compiled code never allocates).
        self._fsc = np.zeros((n, 8))
        self._isc = np.zeros((n, 17), dtype=np.int64)
        self.E = _rows(n, 8, np.float64, INF)
        self.E[:, E_TLY] = -INF
        self.E[:, E_M] = world.mass
        self.heap = np.zeros(n, dtype=np.int32)
        self.heap_t = np.full(n, INF)
        self.Q = self.E.view(np.int32)  # the queue columns of E, read as integers
        ring = max(
            16, 1 << math.ceil(math.log2(max(1, RING_EVENTS_PER_ATOM * n // EVENTS_PER_BIN)))
        )
        self.cal = np.zeros(C_HEADS + ring + 2, dtype=np.int64)
        self.cal[C_NB] = ring
        self.calf = np.zeros(2)
        self.head = np.full(nx * ny + n, -1, dtype=np.int32)
        self.fs = np.zeros(4)
        self.js = np.zeros(4, dtype=np.int64)
        self.stats = np.zeros(3, dtype=np.int64)
        self.stats[ST_SINCE] = renumber  # renumber at the first event
        self._log_i = np.zeros((LOG_CAPACITY if world.record_events else 1, 3), dtype=np.int64)
        self._log_t = np.zeros(len(self._log_i))
        self._tc_key: tuple[float, float, bool] | None = None
        self._tc_table = np.zeros(n + 1)
        self._pull()
        _setup(
            self.S, self.A, self.E, self.V, self.heap, self.heap_t, self.Q, self.cal, self.calf,
            self.head, self.fp, self.ip, float(world.time), bool(world.won),
        )  # fmt: skip

    # -- World <-> engine -----------------------------------------------------------
    def _pull(self) -> None:
        w = self.w
        _pull(self.S, self.A, self.rows, w.pos, w.vel, w.t_atom, w.status, w.counter)

    def _load(self) -> None:
        w = self.w
        self._pull()
        self.fs[:] = (w.time, w.energy_sum, w.rim_half_width, w.trap_height)
        self.js[:] = (int(bool(w.won)), w.n_trapped, w.pair_count, w.wall_count)
        key = (w.tc0, w.tc_exponent, w.win_rule)
        if key != self._tc_key:
            # Tc(N) for every N, by the World's own expression (same float pow).
            self._tc_table[:] = [w.win_threshold_of(m) for m in range(w.n_initial + 1)]
            self._tc_key = key

    def _store(self, nlog: int) -> None:
        w = self.w
        _push(self.S, self.A, self.rows, w.pos, w.vel, w.t_atom, w.status, w.counter)
        w.time = float(self.fs[S_TIME])
        w.energy_sum = float(self.fs[S_ESUM])
        w.won = bool(self.js[J_WON])
        w.n_trapped = int(self.js[J_NTRAP])
        w.pair_count = int(self.js[J_PAIRS])
        w.wall_count = int(self.js[J_WALLS])
        if nlog:
            li = self._log_i[:nlog].tolist()
            lt = self._log_t[:nlog].tolist()
            w.log.extend((e[0], e[1], e[2], t) for e, t in zip(li, lt, strict=True))

    # -- public -------------------------------------------------------------------
    def advance_to(self, t_end: float) -> None:
        """Process every event with time <= t_end in time order, then set the clock."""
        self._load()
        while True:
            done, nlog = _advance(
                float(t_end), self.S, self.A, self.E, self.V, self.heap, self.heap_t, self.Q,
                self.cal, self.calf, self.head, self.rows, self._fsc, self._isc, self.fp,
                self.ip, self.fs, self.js, self._tc_table, self._log_i, self._log_t, self.stats,
            )  # fmt: skip
            if done:
                break
            self._store(nlog)  # log buffer full: hand it over and go on
        self.fs[S_TIME] = t_end
        self._store(nlog)

    def set_trap_height(self, height: float) -> None:
        """New rim height; with the knife rule, atoms above m g H go at once."""
        w = self.w
        w.trap_height = height
        if not w.knife:
            return
        self._load()
        if len(self._log_i) < len(w.radius) + 1:
            self._log_i = np.zeros((len(w.radius) + 1, 3), dtype=np.int64)
            self._log_t = np.zeros(len(self._log_i))
        nlog = _knife_all(
            self.S, self.A, self.E, self.V, self.heap, self.heap_t, self.Q, self.cal, self.calf,
            self.head, self.rows, self.fp, self.ip, self.fs, self.js, self._tc_table,
            self._log_i, self._log_t,
        )  # fmt: skip
        self._store(nlog)

    # -- diagnostics --------------------------------------------------------------
    @property
    def crossing_count(self) -> int:
        """Cell-crossing events processed so far."""
        return int(self.stats[ST_CROSS])

    @property
    def stale_count(self) -> int:
        """Pair events found stale (partner changed) and re-predicted so far."""
        return int(self.stats[ST_STALE])

    @property
    def grid_shape(self) -> tuple[int, int, float]:
        """(columns, rows, cell edge in px) of the cell grid."""
        return int(self.ip[Q_NX]), int(self.ip[Q_NY]), float(self.fp[P_CS])

    def grid_errors(self) -> int:
        """Trapped atoms filed more than one cell away from where they are now (0 if sound)."""
        if self.w.won:
            return 0
        return int(_grid_errors(self.S, self.A, self.fp, self.ip, float(self.w.time)))
