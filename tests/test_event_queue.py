"""The fast engine's event queue: a calendar of time bins in front of a small heap.

Whatever the bin width, ring size, ties and infinite keys, the queue must hand
out the atom with the least key (t, rank, a, b), exactly as one heap would:
the event order of the whole engine rests on it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

F = pytest.importorskip("evapcool.physics.fast")


class Queue:
    """The engine's queue tables for n atoms, driven through the compiled functions."""

    def __init__(self, n: int, ring: int) -> None:
        self.E = np.full((n, 8), math.inf)
        self.Q = self.E.view(np.int32)
        self.V = np.zeros((n, 11), dtype=np.int32)
        self.heap = np.zeros(n, dtype=np.int32)
        self.heap_t = np.full(n, math.inf)
        self.cal = np.zeros(F.C_HEADS + ring + 2, dtype=np.int64)
        self.cal[F.C_NB] = ring
        self.calf = np.zeros(2)

    def tables(self) -> tuple[np.ndarray, ...]:
        return self.heap, self.heap_t, self.Q, self.cal, self.calf

    def key(self, i: int) -> tuple[float, int, int, int]:
        v = self.V[i]
        return (float(self.E[i, F.E_KEY]), int(v[F.V_RANK]), int(v[F.V_A]), int(v[F.V_B]))

    def set(self, i: int, t: float, rank: int, a: int, b: int) -> None:
        self.E[i, F.E_KEY] = t
        self.V[i, F.V_RANK], self.V[i, F.V_A], self.V[i, F.V_B] = rank, a, b
        F._place(i, t, *self.tables(), self.V)

    def rebuild(self, base: float, dt: float) -> None:
        F._rebuild(base, dt, self.E, self.V, *self.tables())

    def pop(self) -> int:
        """The root's row (left in place, as in the engine), or -1 if no atom has an event."""
        if self.cal[F.C_HN] == 0 and not F._next_bin(self.E, self.V, *self.tables()):
            return -1
        # A prefetch: must not disturb anything.
        F._walk_ahead(self.E, self.V, self.Q, self.cal, True)
        return int(self.heap[0])


# Times on a coarse grid, so equal times (ties broken by rank, a, b) are common.
_times = st.one_of(st.integers(0, 400).map(lambda k: k * 0.125), st.just(math.inf))
_keys = st.tuples(_times, st.integers(-1, 1), st.integers(0, 3), st.integers(0, 3))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    n=st.integers(1, 30),
    ring=st.sampled_from([1, 2, 3, 16]),
    dt=st.sampled_from([0.01, 0.3, 2.0, 1e3, math.inf]),
    data=st.data(),
)
def test_queue_hands_out_the_least_key(n: int, ring: int, dt: float, data: st.DataObject) -> None:
    q = Queue(n, ring)
    for i in range(n):
        q.E[i, F.E_KEY] = data.draw(_times)
        q.V[i, F.V_RANK] = data.draw(st.integers(-1, 1))
    q.rebuild(0.0, dt)
    now = 0.0
    for _ in range(4 * n + 10):
        i = q.pop()
        keys = [q.key(j) for j in range(n)]
        if i < 0:
            assert all(k[0] == math.inf for k in keys)
            break
        assert q.key(i) == min(keys)
        now = q.key(i)[0]
        # The event's atom gets a new key (at or after now, or none); now and then
        # so does another atom (a partner), and the queue is rebuilt (renumbering).
        t, rank, a, b = data.draw(_keys)
        q.set(i, now + t, rank, a, b)
        if n > 1 and data.draw(st.booleans()):
            j = data.draw(st.integers(0, n - 1))
            t, rank, a, b = data.draw(_keys)
            q.set(j, now + t, rank, a, b)
        if data.draw(st.integers(0, 9)) == 0:
            q.rebuild(now, data.draw(st.sampled_from([0.05, 1.0, 50.0])))


def test_queue_far_future_key_restarts_the_bins() -> None:
    """A lone key far beyond the ring (1e20 bins away) still comes out, and in order."""
    q = Queue(3, 16)
    q.E[:, F.E_KEY] = [math.inf, 5.0, 1e20]
    q.rebuild(0.0, 1e-3)
    assert q.pop() == 1
    q.set(1, math.inf, 0, 1, 0)
    assert q.pop() == 2
    q.set(2, math.inf, 0, 2, 0)
    assert q.pop() == -1


def test_bin_width_follows_the_bulk_not_the_stragglers() -> None:
    """Bins sized by the many short waits, not by a few atoms waiting ~1e6 times longer."""
    e = np.full((1000, 8), math.inf)
    e[:990, F.E_KEY] = np.linspace(0.001, 0.002, 990)
    e[990:, F.E_KEY] = 1e3
    dt = F._bin_width(0.0, e)
    # 990 events in ~0.0015: EVENTS_PER_BIN of them per bin.
    assert dt == pytest.approx(F.EVENTS_PER_BIN * 0.0015 / 990, rel=0.05)


def test_queue_with_no_time_at_all_stops() -> None:
    """A NaN key (a bug elsewhere) ends the events instead of spinning over empty bins."""
    q = Queue(2, 16)
    q.E[:, F.E_KEY] = [math.nan, math.inf]
    q.rebuild(0.0, 1.0)
    assert q.pop() == -1
