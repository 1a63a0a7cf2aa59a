"""Making a simulation in a worker thread, with progress the window can show.

From AUTO_FAST_MIN_ATOMS atoms the game uses the Numba engine. Its first start on a
machine compiles it (about ten seconds; later starts load Numba's cache). The compile
runs here, off the main thread, through the agreed warm-up
`evapcool.physics.fast.prepare(progress)`, so the window stays alive and shows a bar
while it works. Where the engine has no `prepare` yet, making the simulation compiles
what it needs; the bar then shows that it is busy without a share done.
"""

from __future__ import annotations

import importlib.util
import threading
import time

from evapcool.app.words import t
from evapcool.game.rules import GameConfig, make_simulation
from evapcool.physics.simulation import AUTO_FAST_MIN_ATOMS, Simulation

#: Shown under the bar while the fast engine is readied (docs/benchmarks.md, README).
COMPILE_NOTE = "progress.compile_note"

_fast_ready = False


def uses_fast_engine(config: GameConfig) -> bool:
    """Whether making this game's simulation loads (and maybe compiles) the Numba engine."""
    if config.engine == "fast":
        return True
    return (
        config.engine == "auto"
        and config.n_atoms >= AUTO_FAST_MIN_ATOMS
        and importlib.util.find_spec("numba") is not None
    )


def needs_warmup(config: GameConfig) -> bool:
    """True if the fast engine has not been readied in this process yet and config needs it."""
    return uses_fast_engine(config) and not _fast_ready


class SimulationBuilder:
    """make_simulation(config) in a daemon thread; read `state`, `elapsed`, `done`."""

    def __init__(self, config: GameConfig) -> None:
        self.config = config
        #: (what is happening, steps done / all steps or None if unknown), replaced whole
        #: by the worker so the window reads a consistent pair.
        self.state: tuple[str, float | None] = (t("progress.starting"), None)
        self._sim: Simulation | None = None
        self._error: BaseException | None = None
        self._thread = threading.Thread(target=self._work, name="evapcool-warmup", daemon=True)
        self.started = time.monotonic()

    def start(self) -> SimulationBuilder:
        self.started = time.monotonic()
        self._thread.start()
        return self

    @property
    def elapsed(self) -> float:
        return time.monotonic() - self.started

    @property
    def done(self) -> bool:
        return not self._thread.is_alive()

    def wait(self, seconds: float) -> bool:
        """Wait up to seconds for the work; True if it is done."""
        self._thread.join(seconds)
        return self.done

    def result(self) -> Simulation:
        """The simulation (after `done`); re-raises what went wrong in the thread."""
        self._thread.join()
        if self._error is not None:
            raise self._error
        assert self._sim is not None
        return self._sim

    @property
    def what(self) -> str:
        return self.state[0]

    @property
    def fraction(self) -> float | None:
        return self.state[1]

    def _say(self, what: str) -> None:
        self.state = (what, self.state[1])

    def _progress(self, done: int, total: int, what: str) -> None:
        # One more step follows the warm-up: placing the atoms.
        # The engine's own step names are a programmer's words: the player reads ours.
        what = t("progress.compiling_part", done=done, total=total + 1) if total > 0 else what
        self.state = (what, done / (total + 1) if total > 0 else None)

    def _work(self) -> None:
        global _fast_ready
        try:
            compiles_here = False
            if needs_warmup(self.config):
                self._say(t("app.loading_fast"))
                from evapcool.physics import fast

                prepare = getattr(fast, "prepare", None)
                if prepare is not None:
                    prepare(self._progress)
                else:  # making the simulation compiles what it needs
                    compiles_here = True
                    self._say(t("app.compiling_fast"))
            if not compiles_here:
                self._say(t("progress.placing", n=self.config.n_atoms))
            self._sim = make_simulation(self.config)
            if self._sim.engine == "fast":
                _fast_ready = True
        except BaseException as exc:  # handed to the main thread by result()
            self._error = exc
