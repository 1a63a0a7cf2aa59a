"""The game's clock above the physics, readable: the oracle of core/play.c.

Play goes on in pieces that stop at each whole frame; there the height held during the frame
is recorded (the game's moves, up to the win), the frame's end sees the win and fixes the
score, and the next frame's height is applied: the script's (a recording watched) or the one
asked for. A game is therefore its heights per whole frame, whatever the display's rate.
The reference engine (physics/reference.py) plays by these functions.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

from evapcool.physics.world import World


class Engine(Protocol):
    w: World
    score: int | None
    play: Play

    def advance_to(self, t_end: float) -> None: ...
    def set_trap_height(self, height: float) -> None: ...
    def frame_end(self) -> None: ...


@dataclass
class Play:
    """What the clock keeps: core/tables.h's Play."""

    asked: float | None = None  # applied at the next whole frame
    frames: int = 0  # whole frames played since the start
    moves: list[list[float]] = field(default_factory=list)  # [height, frames] runs
    script: list[float] | None = None  # the height of every frame from the start


def play_to(engine: Engine, end: float, on_frame: Callable[[float], None] | None) -> None:
    """Play to `end` frames; on_frame(height held) after each whole frame recorded."""
    w = engine.w
    while w.time < end:
        boundary = math.floor(w.time) + 1.0
        engine.advance_to(min(boundary, end))
        if w.time >= boundary:
            _frame_reached(engine, on_frame)


def _frame_reached(engine: Engine, on_frame: Callable[[float], None] | None) -> None:
    w, p = engine.w, engine.play
    recorded = engine.score is None  # the moves end with the frame of the win
    if recorded:
        if p.moves and p.moves[-1][0] == w.trap_height:
            p.moves[-1][1] += 1
        else:
            p.moves.append([w.trap_height, 1])
    engine.frame_end()
    p.frames += 1
    if recorded and on_frame is not None:
        on_frame(w.trap_height)
    _scripted(p)
    _apply_asked(engine)


def _scripted(p: Play) -> None:
    """The script's height for the frame starting now, as the one asked; past its end: none."""
    if p.script is None:
        return
    if p.frames >= len(p.script):
        p.script = None
        return
    p.asked = p.script[p.frames]


def _apply_asked(engine: Engine) -> None:
    """The height asked for takes effect (one asked in the win's frame too: the score was
    fixed at its end)."""
    h = engine.play.asked
    if h is None:
        return
    engine.play.asked = None
    if h != engine.w.trap_height:
        engine.set_trap_height(h)


def ask_height(engine: Engine, height: float, now: bool) -> bool:
    """A rim height from the next whole frame (at once if `now` or on one); refused once won,
    while a script plays, or if it is the height asked already."""
    p = engine.play
    if engine.w.won or p.script is not None or height == asked_height(engine):
        return False
    p.asked = height
    if now or float(engine.w.time).is_integer():
        _apply_asked(engine)
    return True


def asked_height(engine: Engine) -> float:
    """The rim's height now, or the one it takes at the next whole frame."""
    asked = engine.play.asked
    return engine.w.trap_height if asked is None else asked


def hold(engine: Engine, runs: Sequence[tuple[float, float]]) -> None:
    """Hold these (height, frames) runs' heights, frame k of the start holding the k-th
    (none: the player's again)."""
    p = engine.play
    p.script = [h for h, n in runs for _ in range(int(n))] or None
    _scripted(p)
    if float(engine.w.time).is_integer():
        _apply_asked(engine)


def moves(engine: Engine) -> list[tuple[float, int]]:
    """The (height, frames) runs held so far, up to the frame of the win."""
    return [(float(h), int(n)) for h, n in engine.play.moves]
