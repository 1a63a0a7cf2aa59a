"""What a teacher gets on the desktop (issue 48): sound, the run to take home, the scene read
in a sentence (key D), and a link's locks and hidden parts.

`Teaching` listens to the game each frame (who left, how close T is to Tc, the win or the
loss) for the sound, keeps the run's rows for "Save this run", and answers the keys M, D
and W. A link's `lock` names controls shown but not changeable; `hide` what is left out.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from evapcool import i18n
from evapcool.app.notices import Notices
from evapcool.app.replays import ReplayKeeper
from evapcool.app.runlog import FRAMES_PER_SECOND, RUNS_FOLDER, RunLog, replay_code, run_file
from evapcool.app.sound import APPROACH_EVERY, APPROACH_FROM, Sound
from evapcool.app.words import t
from evapcool.fileio import atomic_write_text
from evapcool.game.rules import Game

#: The settings' field of each lockable control (the link names them as the page does).
LOCKED_FIELDS = {"atoms": "n_atoms", "radius": "radius", "escape": "escape", "tc-law": "tc_law"}
#: "close to condensing" once T is within this factor of Tc.
CLOSE_TO_TC = 1.25
#: "atoms leaving" while one left within the last second of play.
LEAVING_FRAMES = 30


class Teaching:
    """Sound cues, the run log, the describe line, and the link's locks and hidden parts."""

    def __init__(
        self,
        sound: Sound,
        notices: Notices,
        replays: ReplayKeeper,
        data_folder: Path,
        lock: tuple[str, ...] = (),
        hide: tuple[str, ...] = (),
    ) -> None:
        self.sound = sound
        self.notices = notices
        self.replays = replays
        self.folder = data_folder / RUNS_FOLDER
        self.lock = frozenset(lock)
        self.hide = frozenset(hide)
        self.log = RunLog()
        #: Atoms trapped at the last look, their indices and energies (who left since).
        self._seen: tuple[int, np.ndarray, np.ndarray] | None = None
        self._generation = -1
        self._frames_heard = 0
        self._ended = False
        #: Play time (frames) when the last atom left, for "atoms leaving".
        self._left_at = -1e9
        #: The last file saved (tests, the notice).
        self.saved: Path | None = None

    def attach(self, game: Game) -> None:
        self.log.attach(game)

    # -- locks --------------------------------------------------------------------------
    def allows(self, control: str) -> bool:
        """Whether a control may change; a locked one says so in a notice."""
        if control not in self.lock:
            return True
        self.notices.news(t("desk.link.locked", control=t(f"desk.control.{control}")))
        return False

    # -- sound ---------------------------------------------------------------------------
    def observe(self, game: Game) -> None:
        """After the frame's physics: tick for each atom gone, the approach tone, the end."""
        sim = game.sim
        if game.generation != self._generation:
            self._generation, self._seen, self._ended = game.generation, None, False
            self._frames_heard, self._left_at = 0, -1e9
        n = sim.n_trapped
        if self._seen is not None and n < self._seen[0]:
            _, before, energies = self._seen
            gone = np.isin(before, sim.trapped_indices, invert=True)
            t0 = sim.initial_temperature or 1.0
            self.sound.ticks(energies[gone] / t0)
            self._left_at = float(sim.time)
        if self._seen is None or n != self._seen[0] or not game.paused:
            self._seen = (n, sim.trapped_indices, sim.energies())
        frames = int(sim.time)
        tc = sim.critical_temperature
        if (
            not sim.won
            and tc > 0
            and sim.temperature < APPROACH_FROM * tc
            and frames >= self._frames_heard + APPROACH_EVERY
        ):
            self._frames_heard = frames
            self.sound.approach(sim.temperature / tc)
        if not self._ended and (sim.won or game.too_few_atoms is not None):
            self._ended = True
            self.sound.condensed() if sim.won else self.sound.lost()

    def toggle_mute(self) -> None:
        """Key M."""
        if not self.sound.available:
            self.notices.news(t("desk.sound.no_device"))
            return
        heard = self.sound.toggle_mute()
        self.notices.news(t("sound.unmuted") if heard else t("sound.muted"))

    # -- the scene in a sentence ----------------------------------------------------------
    def describe(self, game: Game) -> str:
        """The scene in one sentence: atoms, T and Tc, the trap, what is happening."""
        sim = game.sim
        n, temp, tc = sim.n_trapped, sim.temperature, sim.critical_temperature
        leaving = sim.n_escaped > 0 or sim.time - self._left_at < LEAVING_FRAMES
        close = tc > 0 and temp < CLOSE_TO_TC * tc
        if sim.won:
            state = "condensed"
        elif game.too_few_atoms is not None:
            state = "too_few"
        elif game.paused:
            state = "paused"
        elif leaving:
            state = "leaving_close" if close else "leaving"
        else:
            state = "close" if close else "waiting"
        # The page's sentence (i48web's describe.*), word for word: one scene, one sentence.
        return t(
            "describe.scene",
            n=n,
            temp=i18n.number(round(temp, 1)),
            tc=i18n.number(round(tc, 1)),
            h=round(game.trap_height),
            what=t(f"describe.{state}"),
        )

    def say(self, game: Game) -> None:
        """Key D: the sentence as a notice."""
        self.notices.news(self.describe(game))

    # -- the run to take home ----------------------------------------------------------------
    def save_run(self, game: Game, every_frame: bool = False) -> Path | None:
        """Key W (Shift+W: every frame): the run as a lab CSV in the data folder's runs/."""
        if game.generation != self.log.generation:
            self.log.start(game)
        code = replay_code(game, self.replays.code, self.replays.recorder)
        every = 1 if every_frame else FRAMES_PER_SECOND
        path = run_file(self.folder, game)
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
            atomic_write_text(path, self.log.csv_text(game, code, every))
        except OSError as exc:
            self.notices.problem(t("desk.run.not_saved", problem=exc.strerror or str(exc)))
            return None
        self.saved = path
        self.notices.news(t("desk.run.saved", path=str(path)))
        return path
