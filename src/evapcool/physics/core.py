"""`CoreEngine`: the compiled engine core (core/*.c) over a World, a drop-in for ReferenceEngine.

The core is the same C source the page runs as WebAssembly, built natively as the extension
`evapcool.physics._core` (setup.py): cells, an event calendar, one pending event per atom.
It processes the reference engine's events in the reference engine's order, bit for bit
(tests/physics/test_core_engine.py, the golden traces). Where the extension could not be
built (an sdist installed without a C compiler) `available()` is False and the game, the
lab and the server play on the reference engine, saying so once (`missing_note`).
"""

from __future__ import annotations

import functools
import importlib
from collections.abc import Callable, Sequence
from pathlib import Path
from types import ModuleType

import numpy as np

from evapcool.extras import MissingExtraError
from evapcool.physics import coresource
from evapcool.physics.model import (
    CORE_DONE,
    CORE_FRAME_END,
    CORE_LOG_FULL,
    CORE_LOG_LINE_BYTES,
    CORE_MOVES_FULL,
)
from evapcool.physics.world import World

#: Lines of the core's event log buffer (emptied into the World when full).
LOG_CAPACITY = 1 << 16
#: One log line in C: int32 kind, a, b, padding; float64 time (core/evapcool_core.h LogLine).
LOG_LINE = np.dtype([("kind", "<i4"), ("a", "<i4"), ("b", "<i4"), ("pad", "<i4"), ("t", "<f8")])
assert LOG_LINE.itemsize == CORE_LOG_LINE_BYTES


#: How to get the core where it is missing (the wheels carry it; an sdist compiles it).
REINSTALL = "reinstall evapcool where a C compiler is at hand (or from a wheel)"


class StaleCoreError(MissingExtraError):
    """The extension built in place in a source checkout is older than the core's sources."""


def compiled() -> ModuleType | None:
    """The extension evapcool.physics._core, or None where it was not built. StaleCoreError
    (one line naming the command that rebuilds it) if it was built in place from sources
    that have changed since: an edited core is never run stale."""
    try:
        module = importlib.import_module("evapcool.physics._core")
    except ImportError:
        return None
    _refuse_if_stale(module.__file__ or "")
    return module


@functools.cache
def _refuse_if_stale(extension: str) -> None:
    """Compare an in-place build's recorded source hash with its checkout's sources (once)."""
    root = coresource.checkout_of(Path(extension)) if extension else None
    if root is None:
        return
    built = getattr(importlib.import_module("evapcool.physics._core"), "SOURCE_HASH", "unknown")
    if built != coresource.source_hash(root):
        raise StaleCoreError(
            f"the compiled engine core in {root} is older than its sources (core/): "
            f"rebuild it with: {coresource.REBUILD}"
        )


def available() -> bool:
    """True if the compiled core is installed."""
    return compiled() is not None


def missing_message(feature: str) -> str:
    """'FEATURE needs the compiled engine core, ...': one line saying how to get it."""
    return f"{feature} needs the compiled engine core, which this install lacks: {REINSTALL}"


def missing_note() -> str:
    """One line for the start of a program that falls back to the reference engine."""
    return (
        "the compiled engine core is not installed (no C compiler when evapcool was built): "
        f"playing on the reference engine, slower beyond a few hundred atoms; {REINSTALL}"
    )


class CoreEngine:
    """Event-driven hard disks in the cup, in the compiled core."""

    name = "fast"

    def __init__(self, world: World) -> None:
        module = compiled()
        if module is None:
            raise MissingExtraError(missing_message("the fast engine"))
        self.w = world
        n = len(world.radius)
        # A knife may log every atom at once: the buffer holds them all.
        self.core = module.Core(n, max(LOG_CAPACITY, n + 8) if world.record_events else 1)
        inputs = np.concatenate(
            [world.pos[:, 0], world.pos[:, 1], world.vel[:, 0], world.vel[:, 1],
             world.t_atom, world.radius, world.mass]
        )  # fmt: skip
        self.core.load(
            inputs, world.status.astype(np.int32), world.gravity, world.curvature,
            world.x_left, world.x_right, world.y_bottom, world.knife, world.win_rule,
            world.record_events, world.time, world.won, world.pair_count, world.wall_count,
        )  # fmt: skip
        self._tc_key: tuple[float, float, bool] | None = None
        self._update_tc_table()
        self.core.start(world.energy_sum, world.trap_height)
        self._crossings = 0
        self._stale = 0
        self._moves: list[tuple[float, int]] = []  # taken from the core when it was full

    def _update_tc_table(self) -> None:
        """Tc(N) for every N, by the core's power (the World's portable power's twin)."""
        w = self.w
        key = (w.tc0, w.tc_exponent, w.win_rule)
        if key != self._tc_key:
            self.core.fill_tc_table(w.tc0, w.tc_exponent)
            self._tc_key = key

    def _sync(self) -> None:
        """The core's clock, sums and stored states into the World (one pass in C)."""
        w = self.w
        self.core.export(w.pos, w.vel, w.t_atom, w.status, w.counter)
        (
            w.time, w.energy_sum, w.won, w.n_trapped, w.pair_count, w.wall_count,
            self._crossings, self._stale, w.trap_height,
        ) = self.core.scalars()  # fmt: skip

    def _take_log(self) -> None:
        if self.w.record_events:
            lines = np.frombuffer(self.core.take_log(), dtype=LOG_LINE)
            kinds, a, b, t = (lines[f].tolist() for f in ("kind", "a", "b", "t"))
            self.w.log.extend(zip(kinds, a, b, t, strict=True))

    # -- public -------------------------------------------------------------------
    def advance_to(self, t_end: float) -> None:
        """Process every event with time <= t_end in time order, then set the clock."""
        self._update_tc_table()
        while self.core.advance_to(float(t_end)) == CORE_LOG_FULL:
            self._take_log()
        self._take_log()
        self._sync()

    def set_trap_height(self, height: float) -> None:
        """New rim height; with the knife rule, atoms above m g H go at once."""
        self._update_tc_table()
        self.core.set_trap_height(float(height))
        self._take_log()
        self._sync()

    def force_win(self) -> None:
        """Latch the win now (demonstrations and tests)."""
        self.core.force_win()
        self.w.won = True

    # -- the game's clock (core/play.c) ------------------------------------------------
    def play_to(self, end: float, on_frame: Callable[[float], None] | None) -> None:
        """Play to `end` frames; on_frame(height held) after each whole frame recorded."""
        self._update_tc_table()
        while (code := self.core.play_to(float(end), on_frame is not None)) != CORE_DONE:
            self._take_log()
            if code == CORE_MOVES_FULL:
                self._take_moves()
            elif code == CORE_FRAME_END and on_frame is not None:
                self._sync()
                on_frame(self.w.trap_height)
        self._take_log()
        self._sync()

    def ask_height(self, height: float, now: bool) -> bool:
        """A rim height from the next whole frame (at once if now or on one), or refused."""
        asked = bool(self.core.ask_height(float(height), bool(now)))
        self._take_log()
        self._sync()
        return asked

    @property
    def asked_height(self) -> float:
        return float(self.core.asked_height())

    def hold(self, runs: Sequence[tuple[float, float]]) -> None:
        """Hold these (height, frames) runs' heights, counted from the start (none: stop)."""
        self.core.hold(len(runs))
        for height, frames in runs:
            self.core.hold_run(float(height), float(frames))
        self._take_log()
        self._sync()

    def _kept_moves(self) -> list[tuple[float, int]]:
        core = self.core
        return [(core.move_height(k), int(core.move_frames(k))) for k in range(core.n_moves())]

    def _take_moves(self) -> None:
        self._moves += self._kept_moves()
        self.core.moves_taken()

    def moves(self) -> list[tuple[float, int]]:
        """The (height, frames) runs held so far, up to the frame of the win."""
        return self._moves + self._kept_moves()

    # -- the game's frame (core/game.c) -----------------------------------------------
    @property
    def score(self) -> int | None:
        """Atoms trapped at the end of the frame the win was seen in; None before."""
        fixed = self.core.score()
        return None if fixed is None else int(fixed[0])

    @property
    def win_frame(self) -> float | None:
        """The whole frame the win was seen at; None before."""
        fixed = self.core.score()
        return None if fixed is None else float(fixed[1])

    def replay(self, runs: np.ndarray, limit: int) -> int:
        """(height, frames) runs from a whole frame, up to the win or limit frames: the
        frames played (no event log is kept)."""
        self._update_tc_table()
        frames = int(self.core.replay(np.ascontiguousarray(runs, dtype=np.float64), limit))
        self._sync()
        return frames

    def path(self, runs: np.ndarray, limit: int, stride: int, h0: float) -> tuple[int, np.ndarray]:
        """The game's path in the (N, T) plane (core_path): the frames played and the rows
        (k, N, T, h) kept (no event log is kept)."""
        self._update_tc_table()
        runs = np.ascontiguousarray(runs, dtype=np.float64)
        frames, rows = self.core.path(runs, int(limit), int(stride), float(h0))
        self._sync()
        return int(frames), np.frombuffer(rows, dtype=np.float64).reshape(-1, 4)

    def out_of_reach(self, lowest: float, height: float) -> int:
        """Why the gas can no longer condense (core_out_of_reach: REACH_*), or REACH_WITHIN."""
        self._update_tc_table()
        return int(self.core.out_of_reach(float(lowest), float(height)))

    # -- diagnostics --------------------------------------------------------------
    @property
    def crossing_count(self) -> int:
        """Cell-crossing events processed so far."""
        return self._crossings

    @property
    def stale_count(self) -> int:
        """Pair events found stale (partner changed) and re-predicted so far."""
        return self._stale

    @property
    def grid_shape(self) -> tuple[int, int, float, float]:
        """(columns, rows, cell edge in px, skin in px) of the cell grid: an atom is refiled
        into the next cell a skin past its cell's edge."""
        nx, ny, cell, skin = self.core.grid()
        return int(nx), int(ny), float(cell), float(skin)
