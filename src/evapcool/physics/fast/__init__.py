"""The fast engine: Numba, a cell grid and one pending event per atom.

A drop-in for `ReferenceEngine` that reproduces its event sequence exactly: the
scalar formulas of kernels.py are compiled as they are, so both engines do
bit-identical arithmetic on the same stored states, and events are ordered by the
same key (time, solo before pair, then atom indices).

Techniques (Smallenburg, Eur. Phys. J. E 45, 22 (2022); Bannerman et al., J. Comput.
Chem. 32, 3329 (2011)): each atom keeps only its earliest event, filed in an event
calendar (calendar.py); a pair event remembers the partner's event count and is
dropped if the partner changed since (lazy invalidation). Trapped atoms live in a
grid of cells (grid.py) whose edges are crossed as events of their own. Positions
move lazily: an atom's stored state changes only when it takes part in a real event.

Where things are:

    tables.py     the record layouts of the tables (NumPy only)
    jit.py        compiling: options, the source-keyed cache, the kernels, prefetch
    calendar.py   the event queue
    grid.py       the cell grid
    predict.py    predictions: real events, crossings, keys
    events.py     what each event does
    lookahead.py  asking for memory ahead of the loop (speed only)
    driver.py     the event loop and the compiled entry points
    engine.py     FastEngine, the Python class
    warmup.py     prepare(): compiling ahead of use, with progress

Importing this package is cheap: Numba is imported, and code compiled or loaded
from the cache, only when FastEngine or prepare() is first used.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from evapcool.physics.fast.engine import FastEngine

__all__ = ["FastEngine", "prepare"]


def prepare(progress: Callable[[int, int, str], Any] | None = None) -> None:
    """Compile, or load from the cache, every compiled function the engine needs.

    Calls progress(done, total, what) after each step; without a callback, progress
    goes to the terminal (one updating line on stderr, shown only when stderr is a
    terminal or the wait is long). Idempotent and safe to call from a worker thread.
    """
    from evapcool.physics.fast.engine import FastEngine
    from evapcool.physics.fast.warmup import prepare as _prepare

    _prepare(FastEngine, progress)


def __getattr__(name: str) -> Any:
    if name == "FastEngine":
        from evapcool.physics.fast.engine import FastEngine

        return FastEngine
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
