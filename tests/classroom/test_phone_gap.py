"""Issue 46: a hall's phones get their class's board at most once a second (their place),
but a new round, its close and the debrief's view at once; the newest board still reaches
them after the last change."""

from __future__ import annotations

import asyncio
import time

from evapcool.classroom.hub import PHONE_GAP, Hub


def _hub() -> Hub:
    hub = Hub.__new__(Hub)  # the state the phones' schedule uses; no store
    hub.phones_at, hub.phone_phase, hub.phones_late, hub.pending = {}, {}, set(), set()
    hub.wake = asyncio.Event()
    return hub


def _board(challenge: int = 1, is_open: bool = True, pick: str | None = None) -> dict:
    return {"challenge": challenge, "open": is_open, "debrief": {"pick": pick}, "players": 3}


def test_phones_get_a_board_a_second_but_a_round_or_its_close_at_once() -> None:
    async def run() -> list[bool]:
        hub = _hub()
        answers = [hub._phones_due(1, _board()) for _ in range(5)]  # a burst of games
        answers.append(hub._phones_due(2, _board()))  # another room: its own schedule
        answers.append(hub._phones_due(1, _board(is_open=False)))  # the close: at once
        answers.append(hub._phones_due(1, _board(is_open=False, pick="3")))  # the debrief's view
        answers.append(hub._phones_due(1, _board(challenge=2)))  # a new round
        answers.append(hub._phones_due(1, _board(challenge=2)))
        assert hub.phones_late == {1} and not hub.pending
        started = time.monotonic()
        await hub.wake.wait()  # the board held back is sent once the gap is over
        assert time.monotonic() - started >= PHONE_GAP * 0.9
        assert hub.pending == {1} and not hub.phones_late
        answers.append(hub._phones_due(1, _board(challenge=2)))
        return answers

    got = asyncio.run(run())
    assert got == [True, False, False, False, False, True, True, True, True, False, True]


def test_the_class_guide_says_the_gaps() -> None:
    """docs/class.md's API table gives the streams' gaps: 0.25 s for a room's screens, a
    second for its joined students."""
    from pathlib import Path

    from evapcool.classroom.hub import BOARD_GAP

    text = (Path(__file__).resolve().parents[2] / "docs" / "class.md").read_text("utf-8")
    assert BOARD_GAP == 0.25 and "at most one every 0.25 s" in text
    assert PHONE_GAP == 1.0 and "at most one a second" in text
