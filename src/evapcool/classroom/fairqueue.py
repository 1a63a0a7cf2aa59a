"""Verifications shared fairly: a few at a time, the waiting ones served address by address.

One student cannot hold the workers: each student token and each client address may have
only so many verifications in flight or waiting (429 past that), and when a worker frees,
the next game comes from the waiting address served longest ago (round robin), so an
address flooding the queue waits behind itself, not in front of everyone else.
"""

from __future__ import annotations

import asyncio
import itertools
from collections import Counter, deque
from collections.abc import Awaitable, Callable
from typing import TypeVar

from evapcool.classroom.errors import RefusedError

T = TypeVar("T")
#: Seconds a student over their bound is told to wait (a verification takes well under it).
RETRY_AFTER = 2


class FairQueue:
    """Runs at most `slots` jobs at once; the waiting ones by address, least recently
    served first, each address's own in the order they came."""

    def __init__(self, slots: int, per_student: int, per_address: int) -> None:
        self.slots = slots
        self.per_student = per_student
        self.per_address = per_address
        self.running = 0
        self.waiting: dict[str, deque[asyncio.Future[None]]] = {}
        #: When each address last had a job started (a tick of `clock`).
        self.served: dict[str, int] = {}
        self.clock = itertools.count()
        self.of_student: Counter[str] = Counter()
        self.of_address: Counter[str] = Counter()

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
                self._release()
        finally:
            self._drop(self.of_student, student)
            self._drop(self.of_address, address)

    async def _turn(self, address: str) -> None:
        """Wait until a slot is this job's (at once if one is free and nobody waits)."""
        if self.running < self.slots and not self.waiting:
            self.running += 1
            self.served[address] = next(self.clock)
            return
        turn: asyncio.Future[None] = asyncio.get_running_loop().create_future()
        self.waiting.setdefault(address, deque()).append(turn)
        try:
            await turn
        except asyncio.CancelledError:
            if turn.done() and not turn.cancelled():
                self._release()  # given a slot just as it was cancelled: pass it on
            raise

    def _release(self) -> None:
        """Free a slot and give it to the next address's first waiting job."""
        self.running -= 1
        while self.waiting and self.running < self.slots:
            address = min(self.waiting, key=lambda a: self.served.get(a, -1))
            turns = self.waiting[address]
            turn = turns.popleft()
            if not turns:
                del self.waiting[address]
            if not turn.cancelled():
                self.running += 1
                self.served[address] = next(self.clock)
                turn.set_result(None)
        if not self.running and not self.waiting:
            self.served.clear()  # idle: nothing to remember (and no growth)

    @staticmethod
    def _drop(counts: Counter[str], key: str) -> None:
        counts[key] -= 1
        if counts[key] <= 0:
            del counts[key]
