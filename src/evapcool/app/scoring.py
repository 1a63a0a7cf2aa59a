"""The win's name entry and the high-score table, for one applet session."""

from __future__ import annotations

from pathlib import Path

import pygame

from evapcool.app.notices import Notices
from evapcool.app.storage import folder_problem
from evapcool.app.words import t
from evapcool.game.highscores import NAME_MAX, HighScoreTable, format_seconds
from evapcool.view.text_input import CANCEL, SUBMIT, TextInput

AUTOPILOT_FILE = "autopilot-scores.json"


class Scoreboard:
    """Asks a winner's name, stores it, and says what the table overlay shows.

    notices: where messages for the player go.
    """

    def __init__(self, path: Path, notices: Notices) -> None:
        self.notices = notices
        self.table = HighScoreTable(path)
        problem = folder_problem(self.table.path)
        if problem:
            notices.problem(t("scores.unsaved", problem=problem))
        self._pass_on_notices()
        self.name_box: TextInput | None = None
        #: Rank (1-based) of the score stored this round, highlighted in the table.
        self.stored_rank: int | None = None
        #: The round is over (stored or skipped): Enter starts the next player's.
        self.ready_for_next = False
        #: The win being entered: (atoms, seconds).
        self._win = (0, 0.0)
        #: The autopilot's scores: a table of their own beside the players' (never mixed).
        self.autopilot_path = Path(self.table.path).with_name(AUTOPILOT_FILE)
        self._pilots: HighScoreTable | None = None

    def _pass_on_notices(self) -> None:
        for text in self.table.take_notices():
            self.notices.problem(text)

    def new_round(self) -> None:
        self.close_name_box()
        self.stored_rank = None
        self.ready_for_next = False

    def win(self, score: int, seconds: float, name: str | None = None) -> bool:
        """The gas condensed: True if the score makes the table and the name box opens.
        name: the player's name known already (a class's --name): stored under it, unasked."""
        self._win = (score, seconds)
        if self.table.qualifies(score, seconds) and name is not None:
            self.stored_rank = self.table.add(name, score, seconds)
            self._pass_on_notices()
            self.ready_for_next = True
            return False
        if self.table.qualifies(score, seconds):
            self.name_box = TextInput(max_length=NAME_MAX)
            pygame.key.start_text_input()  # the IME / on-screen keyboard, if any
            return True
        self.notices.news(t("notice.not_top10", n=score))
        self.ready_for_next = True
        return False

    @property
    def pilots(self) -> HighScoreTable:
        """The autopilot's table (read when first needed)."""
        if self._pilots is None:
            self._pilots = HighScoreTable(self.autopilot_path)
        return self._pilots

    def autopilot_win(self, label: str, score: int, seconds: float) -> None:
        """An autopilot game's win: kept in the autopilot's table, no name asked."""
        self.pilots.add(label, score, seconds)
        for text in self.pilots.take_notices():
            self.notices.problem(text)
        self.notices.news(t("notice.autopilot_score", name=label, n=score))
        self.ready_for_next = True

    def autopilot_lines(self) -> list[str]:
        """The autopilot's best, marked, for under the players' table (none if it never won)."""
        if self._pilots is None and not self.autopilot_path.exists():
            return []
        best = self.pilots.entries[:1]
        return [
            t("table.autopilot_row", name=e.name, n=e.score, time=format_seconds(e.seconds))
            for e in best
        ]

    def close_name_box(self) -> None:
        if self.name_box is not None:
            self.name_box = None
            pygame.key.stop_text_input()

    def name_event(self, event: pygame.event.Event) -> str | None:
        """A key or typed text for the name box; SUBMIT stores the win, CANCEL skips it."""
        box = self.name_box
        if box is None:
            return None
        result = box.handle_event(event)
        if result == SUBMIT:
            self.close_name_box()
            self.stored_rank = self.table.add(box.value or "", *self._win)
            self._pass_on_notices()
            self.ready_for_next = True
        elif result == CANCEL:
            self.close_name_box()
            self.notices.news(t("win.not_stored"))
            self.ready_for_next = True
        return result

    def clear(self) -> None:
        self.stored_rank = None
        if self.table.reset():
            self.notices.news(t("scores.cleared"))
        if self._pilots is not None or self.autopilot_path.exists():
            self.pilots.reset()
        self._pass_on_notices()

    def footer(self, confirming: bool) -> list[str]:
        pilots = self.autopilot_lines()
        if confirming:
            return [*pilots, t("table.clear_confirm")]
        if self.ready_for_next:
            return [*pilots, t("win.next_player")]
        return [*pilots, t("table.footer")]
