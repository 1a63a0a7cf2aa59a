"""The fast engine's event queue: a calendar of time bins in front of a small heap.

Whatever the bin width, ring size, ties and infinite keys, the queue must hand out
the atom with the least key (t, rank, a, b), exactly as one heap would: the event
order of the whole engine rests on it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

pytest.importorskip("numba")

from evapcool.physics.fast import calendar
from evapcool.physics.fast.jit import entry
from evapcool.physics.fast.tables import (
    HEAP_ENTRY,
    LOG_LINE,
    PLAN,
    QUEUED,
    RUN,
    STATE,
    Tables,
    aligned,
)


# The calendar's functions are inlined into the engine and have no Python entry of
# their own: these wrappers give them one.
@entry
def _file(i, t, tb):
    calendar.file_atom(i, t, tb)


@entry
def _pop(tb):
    """The root's row (left in place, as in the engine), or -1 if no atom has an event."""
    if tb.run[0].heap_size == 0 and not calendar.next_bin(tb):
        return -1
    calendar.walk_ahead(True, tb)  # a prefetch: must not disturb anything
    return tb.heap[0].row


class Queue:
    """The engine's queue tables for n atoms, driven through the compiled functions."""

    def __init__(self, n: int, ring: int) -> None:
        self.tb = Tables(
            state=aligned(n, STATE),
            queued=aligned(n, QUEUED),
            plan=aligned(n, PLAN),
            heap=np.zeros(n, dtype=HEAP_ENTRY),
            bins=np.full(ring + 2, -1, dtype=np.int64),
            cells=np.full(n + 1, -1, dtype=np.int32),
            run=np.zeros(1, dtype=RUN),
            tc_table=np.zeros(n + 1),
            log=np.zeros(1, dtype=LOG_LINE),
        )
        self.tb.run["n_bins"] = ring
        self.tb.queued["key_t"] = math.inf

    def key(self, i: int) -> tuple[float, int, int, int]:
        p = self.tb.plan[i]
        return (float(self.tb.queued[i]["key_t"]), int(p["rank"]), int(p["tie_a"]), int(p["tie_b"]))

    def set(self, i: int, t: float, rank: int, a: int, b: int) -> None:
        self.tb.queued["key_t"][i] = t
        self.tb.plan["rank"][i], self.tb.plan["tie_a"][i], self.tb.plan["tie_b"][i] = rank, a, b
        _file(i, t, self.tb)

    def refile(self, base: float, width: float) -> None:
        calendar.refile_all(base, width, self.tb)

    def pop(self) -> int:
        return int(_pop(self.tb))


# Times on a coarse grid, so equal times (ties broken by rank, a, b) are common.
_times = st.one_of(st.integers(0, 400).map(lambda k: k * 0.125), st.just(math.inf))
_keys = st.tuples(_times, st.integers(-1, 1), st.integers(0, 3), st.integers(0, 3))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    n=st.integers(1, 30),
    ring=st.sampled_from([1, 2, 3, 16]),
    width=st.sampled_from([0.01, 0.3, 2.0, 1e3, math.inf]),
    data=st.data(),
)
def test_queue_hands_out_the_least_key(
    n: int, ring: int, width: float, data: st.DataObject
) -> None:
    q = Queue(n, ring)
    for i in range(n):
        q.tb.queued["key_t"][i] = data.draw(_times)
        q.tb.plan["rank"][i] = data.draw(st.integers(-1, 1))
    q.refile(0.0, width)
    for _ in range(4 * n + 10):
        i = q.pop()
        keys = [q.key(j) for j in range(n)]
        if i < 0:
            assert all(k[0] == math.inf for k in keys)
            break
        assert q.key(i) == min(keys)
        now = q.key(i)[0]
        # The event's atom gets a new key (at or after now, or none); now and then
        # so does another atom (a partner), and the queue is refiled (upkeep).
        t, rank, a, b = data.draw(_keys)
        q.set(i, now + t, rank, a, b)
        if n > 1 and data.draw(st.booleans()):
            j = data.draw(st.integers(0, n - 1))
            t, rank, a, b = data.draw(_keys)
            q.set(j, now + t, rank, a, b)
        if data.draw(st.integers(0, 9)) == 0:
            q.refile(now, data.draw(st.sampled_from([0.05, 1.0, 50.0])))


def test_queue_far_future_key_restarts_the_bins() -> None:
    """A lone key far beyond the ring (1e20 bins away) still comes out, and in order."""
    q = Queue(3, 16)
    q.tb.queued["key_t"] = [math.inf, 5.0, 1e20]
    q.refile(0.0, 1e-3)
    assert q.pop() == 1
    q.set(1, math.inf, 0, 1, 0)
    assert q.pop() == 2
    q.set(2, math.inf, 0, 2, 0)
    assert q.pop() == -1


def test_bin_width_follows_the_bulk_not_the_stragglers() -> None:
    """Bins sized by the many short waits, not by a few atoms waiting ~1e6 times longer."""
    q = Queue(1000, 16)
    q.tb.queued["key_t"][:990] = np.linspace(0.001, 0.002, 990)
    q.tb.queued["key_t"][990:] = 1e3
    width = calendar.bin_width(0.0, q.tb)
    # 990 events in ~0.0015: EVENTS_PER_BIN of them per bin.
    assert width == pytest.approx(calendar.EVENTS_PER_BIN * 0.0015 / 990, rel=0.05)


def test_queue_with_no_time_at_all_stops() -> None:
    """A NaN key (a bug elsewhere) ends the events instead of spinning over empty bins."""
    q = Queue(2, 16)
    q.tb.queued["key_t"] = [math.nan, math.inf]
    q.refile(0.0, 1.0)
    assert q.pop() == -1
