"""Every game the applet plays is recorded; at the win its replay code is kept.

The code is written to the data folder's `replays/` and, on request (key C or the win
screen's button), put on the clipboard; without a clipboard the notice says where the
file is instead.
"""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

from evapcool.app.notices import Notices
from evapcool.app.words import t
from evapcool.fileio import atomic_write_text
from evapcool.game.replay import Recorder, Settings, encode
from evapcool.game.rules import Game, GameConfig

REPLAY_FOLDER = "replays"


def settings_of(config: GameConfig) -> Settings:
    """The replay settings of a game's config (the fields that decide a game)."""
    return Settings(
        n_atoms=config.n_atoms,
        radius=config.radius,
        escape=config.escape,
        tc_exponent=config.tc_exponent,
    )


class ReplayKeeper:
    """Records the heights of the game in play; after its win, keeps and copies its code."""

    def __init__(self, folder: Path, notices: Notices, edition: str = "desktop"):
        self.folder = folder
        self.notices = notices
        self.edition = edition
        self.recorder: Recorder | None = None
        #: The replay code of the game just won (None while playing).
        self.code: str | None = None
        #: Where that code was saved (None if not, or not yet).
        self.path: Path | None = None

    def attach(self, game: Game) -> None:
        """The first recording (`start` begins each new one; the core records the moves)."""
        self.start(game)

    def start(self, game: Game) -> None:
        """A new recording for a (re)started game: its settings and the seed its atoms had."""
        seed = game.sim.seed  # drawn by the simulation when the config gives none
        if seed is None:  # a restored state: no seed to replay from
            self.recorder = None
        else:
            self.recorder = Recorder(settings_of(game.config), seed, self.edition)
        self.code = self.path = None

    def finish(self, game: Game) -> str | None:
        """The won game's replay code, saved to the replays folder; None if not recorded."""
        rec = self.recorder
        if rec is None:
            return None
        # The win is seen at a whole frame's end, after that frame was recorded (core/play.c).
        self.recorder = None  # the atoms settling after the win are not part of the game
        self.code = encode(rec.finish(game))
        self.path = self._save(self.code, game.score or 0, rec.seed)
        return self.code

    def finish_lost(self, game: Game, max_frames: int | None) -> str | None:
        """The code of the game just lost for good (its frames so far, at most max_frames:
        the rest cannot win either); None if not recorded. Not saved: it is no replay to
        keep, and its recording ends here."""
        rec = self.recorder
        if rec is None:
            return None
        self.recorder = None
        lost = rec.finish(game)
        if max_frames is not None and lost.frames > max_frames:
            left, moves = max_frames, []
            for h, n in lost.moves:
                if left > 0:
                    moves.append((h, min(n, left)))
                    left -= min(n, left)
            lost = replace(lost, moves=tuple(moves), frames=max_frames)
        return encode(lost)

    def _save(self, code: str, score: int, seed: int) -> Path | None:
        stamp = time.strftime("%Y%m%d-%H%M%S")
        path = self.folder / f"{stamp}-{score}-atoms-seed-{seed}.txt"
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            atomic_write_text(path, code + "\n")
        except OSError as exc:
            self.notices.problem(t("replay.not_saved", problem=exc.strerror or str(exc)))
            return None
        return path

    def copy(self) -> bool:
        """Put the code on the clipboard (or say where its file is); False if no code."""
        if self.code is None:
            return False
        copied = put_on_clipboard(self.code)
        if self.path is None:  # not saved (the notice at the win said why)
            self.notices.news(t("replay.copied_only") if copied else self.code)
        elif copied:
            self.notices.news(t("replay.copied", path=str(self.path)))
        else:
            self.notices.news(t("replay.no_clipboard", path=str(self.path)))
        return True


def put_on_clipboard(text: str) -> bool:
    """Whether the text went to the system clipboard (never raises: some have none)."""
    try:
        import pygame.scrap as scrap

        scrap.put_text(text)
        return bool(scrap.get_text() == text)
    except Exception:  # any clipboard failure means "no clipboard", never a crash
        return False
