"""Compiling the engine ahead of use (`prepare`), with progress.

The engine's compiled code comes from Numba's cache after the first start on a
machine (about half a second), but the first start compiles it. `prepare` does that
in steps, each compiling (or loading) the entry points a part of the engine needs
by running them on a two-atom World, and reports progress after every compiled
function: to a callback (the applet draws a bar from a worker thread) or, by
default, on the terminal.
"""

from __future__ import annotations

import sys
import threading
import time
import types
from collections.abc import Callable, Iterable
from typing import Any, TextIO

import numpy as np

from evapcool.physics.world import World

Progress = Callable[[int, int, str], Any]
#: Makes an engine on a World (FastEngine; passed in by the engine itself).
EngineMaker = Callable[[World], Any]

#: Steps: name -> (what the progress line says, the entry points the step compiles).
STEPS = {
    "start": ("setting up the tables", ("start",)),
    "advance": ("the event loop", ("run_until", "maintain")),
    "knife": ("the knife rule", ("knife_now",)),
}
#: What the first frame of a World needs (plus "knife" with the knife rule).
FIRST_FRAME = ("start", "advance")
#: The long passes of Numba's compiler: each end of one of them for an entry point
#: (the biggest functions) is a unit of progress.
LONG_PASSES = ("inline_inlinables", "nopython_type_inference", "native_lowering")
PASS_UNITS = len(LONG_PASSES)

_lock = threading.RLock()
_done: set[str] = set()
_busy = False


def _tiny_world(knife: bool) -> World:
    """Two atoms in the cup: enough to run every entry point once."""
    return World(
        pos=np.array([[-10.0, 5.0], [10.0, 5.0]]),
        vel=np.array([[1.0, 0.0], [-1.0, 0.0]]),
        radius=np.array([2.0, 2.0]),
        mass=np.array([1.0, 1.0]),
        curvature=0.01,
        gravity=10.0 / 30.0,
        trap_height=400.0,
        x_left=-300.0,
        x_right=300.0,
        y_bottom=-100.0,
        escape_rule="knife" if knife else "rim",
    )


def _run_step(name: str, make_engine: EngineMaker) -> None:
    world = _tiny_world(knife=name == "knife")
    engine = make_engine(world)
    if name == "advance":
        engine.advance_to(1.0)
    elif name == "knife":
        engine.set_trap_height(300.0)


def _reachable(entries: Iterable[str]) -> set[Any]:
    """The engine's compiled functions an entry point is built from (itself included).

    Follows the global names (and K.<kernel>) each function's code refers to, through
    the pieces Numba splices in (jit.part).
    """
    from evapcool.physics.fast import driver, jit

    compiled = set(jit.REGISTRY)
    seen: set[Any] = set()
    todo = [getattr(driver, e) for e in entries]
    while todo:
        disp = todo.pop()
        if disp in seen:
            continue
        seen.add(disp)
        fn = disp.py_func
        names = _names(fn.__code__)
        spaces = [fn.__globals__, *(vars(v) for v in fn.__globals__.values() if v is jit.K)]
        for space in spaces:
            todo.extend(v for n, v in space.items() if n in names and hasattr(v, "py_func"))
    return seen & compiled


def _names(code: types.CodeType) -> set[str]:
    names = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            names |= _names(const)
    return names


class _Counter:
    """Counts compiled functions (and the passes of the entry points) into progress calls."""

    def __init__(self, progress: Progress, total: int) -> None:
        self.progress = progress
        self.total = total
        self.done = 0
        self.limit = 0  # progress never passes the end of the current step
        self.functions: set[Any] = set()
        self.entries: set[str] = set()
        self.what = ""

    def tick(self, what: str) -> None:
        if self.done < self.limit:
            self.done += 1
            self.progress(self.done, self.total, what)

    def reach(self, done: int, what: str) -> None:
        self.done = max(self.done, done)
        self.limit = self.done
        self.progress(self.done, self.total, what)


def _listeners(counter: _Counter) -> tuple[Any, Any]:
    from numba.core import event

    class Compiled(event.Listener):
        def on_start(self, ev: Any) -> None:
            pass

        def on_end(self, ev: Any) -> None:
            disp = ev.data["dispatcher"]
            if disp in counter.functions:
                counter.tick(f"{counter.what}: {disp.py_func.__name__}")

    class Passes(event.Listener):
        def on_start(self, ev: Any) -> None:
            pass

        def on_end(self, ev: Any) -> None:
            if ev.data["qualname"] in counter.entries and ev.data["name"].split(" ")[0].endswith(
                LONG_PASSES
            ):
                counter.tick(f"{counter.what}: {ev.data['qualname']}")

    return Compiled(), Passes()


def run(steps: Iterable[str], progress: Progress | None, make_engine: EngineMaker) -> None:
    """Run the steps not yet done in this process, reporting progress.

    Steps run one thread at a time; a FastEngine made while they run (in the same
    thread, by a step) does not start them again. make_engine is the engine's class
    (passed in, so that this module need not import the engine that calls it).
    """
    global _busy
    with _lock:
        todo = [s for s in steps if s not in _done]
        if _busy:
            return
        if not todo:  # all done before: say so (a progress bar can close)
            if progress is not None:
                progress(1, 1, "ready")
            return
        _busy = True
        try:
            _run(todo, progress if progress is not None else TerminalProgress(), make_engine)
        finally:
            _busy = False


def _run(todo: list[str], progress: Progress, make_engine: EngineMaker) -> None:
    from numba.core import event

    sets = []
    covered: set[Any] = set()
    for name in todo:
        funcs = _reachable(STEPS[name][1]) - covered
        covered |= funcs
        sets.append(funcs)
    total = 1 + sum(len(f) + PASS_UNITS * len(STEPS[n][1]) for n, f in zip(todo, sets, strict=True))
    counter = _Counter(progress, total)
    counter.reach(1, "Numba loaded")  # importing it was the first unit
    compiled, passes = _listeners(counter)
    with (
        event.install_listener("numba:compile", compiled),
        event.install_listener("numba:run_pass", passes),
    ):
        for name, funcs in zip(todo, sets, strict=True):
            counter.what = STEPS[name][0]
            counter.functions = funcs
            counter.entries = set(STEPS[name][1])
            end = counter.done + len(funcs) + PASS_UNITS * len(STEPS[name][1])
            counter.limit = end
            _run_step(name, make_engine)
            _done.add(name)
            counter.reach(end, counter.what)
    if isinstance(progress, TerminalProgress):
        progress.finish()


def prepare(make_engine: EngineMaker, progress: Progress | None = None) -> None:
    """Every step (see evapcool.physics.fast.prepare)."""
    run(STEPS, progress, make_engine)


class TerminalProgress:
    """Progress on stderr: one line updated in place on a terminal; otherwise one line
    at the start and one at the end, and only if it takes longer than SLOW_S."""

    #: Say nothing for waits shorter than this (a start from the cache).
    QUIET_S = 0.5
    #: Without a terminal, say something only for waits longer than this.
    SLOW_S = 2.0
    WIDTH = 24

    def __init__(self, stream: TextIO | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.t0 = time.monotonic()
        self.shown = False

    def __call__(self, done: int, total: int, what: str) -> None:
        elapsed = time.monotonic() - self.t0
        if self.tty and elapsed >= self.QUIET_S:
            filled = self.WIDTH * done // total if total else 0
            bar = "#" * filled + "." * (self.WIDTH - filled)
            line = f"evapcool: compiling the fast engine (once) [{bar}] {what}"
            self.stream.write("\r" + line[:100].ljust(100))
            self.stream.flush()
            self.shown = True
        elif not self.tty and not self.shown and elapsed >= self.SLOW_S:
            self.stream.write(
                "evapcool: compiling the fast engine; the first start on a machine takes a "
                "few seconds, once...\n"
            )
            self.stream.flush()
            self.shown = True

    def finish(self) -> None:
        if not self.shown:
            return
        took = time.monotonic() - self.t0
        end = "\r" + " " * 100 + "\r" if self.tty else ""
        self.stream.write(f"{end}evapcool: fast engine ready ({took:.1f} s)\n")
        self.stream.flush()
