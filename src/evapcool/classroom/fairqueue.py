"""Verifications shared fairly: a few at a time, the waiting ones served address by address.

An "address" here is whatever the caller keys the turns by: the server passes a class and
its client address (a hall behind one NAT address takes its turns as one, apart from the
other classes behind it).

One student cannot hold the workers: each student token and each client address may have
only so many verifications in flight or waiting (429 past that), and when a worker frees,
the next game comes from the waiting address served longest ago (round robin), so an
address flooding the queue waits behind itself, not in front of everyone else; and while
other addresses are active it runs on all workers but one.
"""

from __future__ import annotations

import asyncio
import itertools
import time
from collections import Counter, deque
from collections.abc import Awaitable, Callable
from typing import TypeVar

from evapcool.classroom.errors import RefusedError

T = TypeVar("T")
#: Seconds a student over their bound is told to wait (a verification takes well under it).
RETRY_AFTER = 2
#: Seconds an address counts as active after it last sent a game.
ACTIVE_SECONDS = 60.0


class FairQueue:
    """Runs at most `slots` jobs at once; the waiting ones by address, least recently
    served first, each address's own in the order they came.

    While other addresses have sent games in the last ACTIVE_SECONDS, one address runs on
    at most all but one of the slots: a flood keeps one worker, not all of them, and the
    others' games start without waiting for a long one to end. Alone (a class behind one
    address), an address has every slot.
    """

    def __init__(
        self,
        slots: int,
        per_student: int,
        per_address: int,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.slots = slots
        self.per_student = per_student
        self.per_address = per_address
        self.clock = clock
        self.running = 0
        self.waiting: dict[str, deque[asyncio.Future[None]]] = {}
        #: Jobs running per address; when each address last had one started (a tick).
        self.busy: Counter[str] = Counter()
        self.served: dict[str, int] = {}
        self.ticks = itertools.count()
        #: When each address last sent a game (clock seconds).
        self.active: dict[str, float] = {}
        self.of_student: Counter[str] = Counter()
        self.of_address: Counter[str] = Counter()
        self._timer: asyncio.TimerHandle | None = None

    async def run(self, address: str, student: str, job: Callable[[], Awaitable[T]]) -> T:
        """The job's result once it has had its turn; RefusedError(429) over a bound."""
        if self.of_student[student] >= self.per_student:
            raise RefusedError(
                429, "token", "class.error.busy", retry_after=RETRY_AFTER, n=self.per_student
            )
        if self.of_address[address] >= self.per_address:
            raise RefusedError(
                429, "client", "class.error.busy", retry_after=RETRY_AFTER, n=self.per_address
            )
        self.of_student[student] += 1
        self.of_address[address] += 1
        try:
            await self._turn(address)
            try:
                return await job()
            finally:
                self._release(address)
        finally:
            self._drop(self.of_student, student)
            self._drop(self.of_address, address)

    async def _turn(self, address: str) -> None:
        """Wait until a slot is this job's."""
        self.active[address] = self.clock()
        turn: asyncio.Future[None] = asyncio.get_running_loop().create_future()
        self.waiting.setdefault(address, deque()).append(turn)
        self._dispatch()
        try:
            await turn
        except asyncio.CancelledError:
            if turn.done() and not turn.cancelled():
                self._release(address)  # given a slot just as it was cancelled: pass it on
            raise

    def _release(self, address: str) -> None:
        """Free a slot and give it to the next waiting job."""
        self.running -= 1
        self._drop(self.busy, address)
        self._dispatch()
        if not self.running and not self.waiting:
            self.served.clear()  # idle: nothing to remember (and no growth)

    def _dispatch(self) -> None:
        """Start waiting jobs while slots are free: the address served longest ago first,
        among those under their share."""
        recent = self._recent()
        while self.running < self.slots:
            fits = [a for a in self.waiting if self.busy[a] < self._share(a, recent)]
            if not fits:
                if self.waiting:
                    self._wake_later(recent)
                return
            address = min(fits, key=lambda a: self.served.get(a, -1))
            turns = self.waiting[address]
            turn = turns.popleft()
            if not turns:
                del self.waiting[address]
            if turn.cancelled():
                continue
            self.running += 1
            self.busy[address] += 1
            self.served[address] = next(self.ticks)
            turn.set_result(None)

    def _recent(self) -> dict[str, float]:
        """The addresses active in the last ACTIVE_SECONDS (older ones forgotten)."""
        since = self.clock() - ACTIVE_SECONDS
        self.active = {a: t for a, t in self.active.items() if t > since}
        return self.active

    def _share(self, address: str, recent: dict[str, float]) -> int:
        """The slots an address may run on: all but one while others are active."""
        others = len(recent) - (address in recent)
        return self.slots - 1 if self.slots > 1 and others > 0 else self.slots

    def _wake_later(self, recent: dict[str, float]) -> None:
        """Look again when the next address stops counting as active (a slot is idle only
        while someone else may want it)."""
        if self._timer is not None or not recent:
            return
        delay = min(recent.values()) + ACTIVE_SECONDS - self.clock() + 0.01

        def wake() -> None:
            self._timer = None
            self._dispatch()

        self._timer = asyncio.get_running_loop().call_later(max(delay, 0.01), wake)

    @staticmethod
    def _drop(counts: Counter[str], key: str) -> None:
        counts[key] -= 1
        if counts[key] <= 0:
            del counts[key]
