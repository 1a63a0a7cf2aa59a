"""The verifiers' queue (issue 33): bounds per student and address, addresses in turn."""

from __future__ import annotations

import asyncio

import pytest

from evapcool.classroom.errors import RefusedError
from evapcool.classroom.fairqueue import FairQueue


def test_a_waiting_address_goes_before_the_flooding_one() -> None:
    async def run() -> tuple[list[str], FairQueue]:
        queue = FairQueue(slots=1, per_student=2, per_address=64)
        hold = asyncio.Event()
        ran: list[str] = []

        async def job(name: str) -> None:
            ran.append(name)
            if name == "flood 0":
                await hold.wait()  # running when the others come

        jobs = [("flood", f"flood {i}") for i in range(6)] + [("honest", "honest")]
        tasks = []
        for address, name in jobs:
            tasks.append(asyncio.create_task(queue.run(address, name, lambda n=name: job(n))))
            await asyncio.sleep(0)
        hold.set()
        await asyncio.gather(*tasks)
        return ran, queue

    ran, queue = asyncio.run(run())
    assert ran[:2] == ["flood 0", "honest"] and len(ran) == 7, ran
    assert queue.running == 0 and not queue.waiting and not queue.of_address


def test_bounds_per_student_and_per_address() -> None:
    async def run() -> list[str]:
        queue = FairQueue(slots=1, per_student=2, per_address=3)
        hold = asyncio.Event()

        async def slow() -> None:
            await hold.wait()

        tasks = []
        for address, student in (("a", "s1"), ("a", "s1"), ("a", "s1"), ("a", "s2"), ("a", "s3")):
            tasks.append(asyncio.create_task(queue.run(address, student, slow)))
            await asyncio.sleep(0)
        tasks.append(asyncio.create_task(queue.run("b", "s4", slow)))
        await asyncio.sleep(0)
        hold.set()
        results = await asyncio.gather(*tasks, return_exceptions=True)
        return [f"{r.status} {r.field}" if isinstance(r, RefusedError) else "ran" for r in results]

    assert asyncio.run(run()) == ["ran", "ran", "429 token", "ran", "429 client", "ran"]


def test_a_cancelled_waiter_passes_its_turn_on() -> None:
    async def run() -> list[str]:
        queue = FairQueue(slots=1, per_student=5, per_address=5)
        hold = asyncio.Event()
        ran: list[str] = []

        async def job(name: str) -> None:
            ran.append(name)
            await hold.wait()

        first = asyncio.create_task(queue.run("a", "s", lambda: job("first")))
        await asyncio.sleep(0)
        gone = asyncio.create_task(queue.run("b", "s2", lambda: job("gone")))
        last = asyncio.create_task(queue.run("c", "s3", lambda: job("last")))
        await asyncio.sleep(0)
        gone.cancel()
        hold.set()
        await asyncio.gather(first, last)
        with pytest.raises(asyncio.CancelledError):
            await gone
        assert queue.running == 0 and not queue.of_student
        return ran

    assert asyncio.run(run()) == ["first", "last"]


def test_an_address_keeps_a_worker_free_while_others_are_active() -> None:
    async def run() -> tuple[int, int, int]:
        now = [0.0]
        queue = FairQueue(slots=2, per_student=9, per_address=9, clock=lambda: now[0])
        hold = asyncio.Event()

        async def slow() -> None:
            await hold.wait()

        alone = [asyncio.create_task(queue.run("flood", f"a{i}", slow)) for i in range(3)]
        await asyncio.sleep(0)
        running_alone = queue.busy["flood"]  # nobody else: every worker
        hold.set()
        await asyncio.gather(*alone)
        hold.clear()
        honest = asyncio.create_task(queue.run("honest", "h", lambda: asyncio.sleep(0)))
        await honest
        flood = [asyncio.create_task(queue.run("flood", f"b{i}", slow)) for i in range(3)]
        await asyncio.sleep(0)
        running_shared = queue.busy["flood"]  # honest sent a game just now: one kept free
        now[0] += 61.0  # honest quiet for a minute: the flood may have both again
        flood.append(asyncio.create_task(queue.run("flood", "b9", slow)))
        await asyncio.sleep(0)
        running_later = queue.busy["flood"]
        hold.set()
        await asyncio.gather(*flood)
        return running_alone, running_shared, running_later

    assert asyncio.run(run()) == (2, 1, 2)
