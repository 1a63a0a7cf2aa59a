"""The win's name entry and the high-score table, for one applet session."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pygame

from evapcool.app.storage import folder_problem
from evapcool.game.highscores import NAME_MAX, HighScoreTable
from evapcool.view.text_input import CANCEL, SUBMIT, TextInput


class Scoreboard:
    """Asks a winner's name, stores it, and says what the table overlay shows.

    notify: where messages for the player go (the app's notices).
    """

    def __init__(self, path: Path, notify: Callable[[str], None]) -> None:
        self.notify = notify
        self.table = HighScoreTable(path)
        problem = folder_problem(self.table.path)
        if problem:
            notify(f"High scores cannot be saved ({problem}); they last this session only.")
        self._pass_on_notices()
        self.name_box: TextInput | None = None
        #: Rank (1-based) of the score stored this round, highlighted in the table.
        self.stored_rank: int | None = None
        #: The round is over (stored or skipped): Enter starts the next player's.
        self.ready_for_next = False
        #: The win being entered: (atoms, seconds).
        self._win = (0, 0.0)

    def _pass_on_notices(self) -> None:
        for text in self.table.take_notices():
            self.notify(text)

    def new_round(self) -> None:
        self.close_name_box()
        self.stored_rank = None
        self.ready_for_next = False

    def win(self, score: int, seconds: float) -> bool:
        """The gas condensed: True if the score makes the table (the name box opens)."""
        self._win = (score, seconds)
        if self.table.qualifies(score, seconds):
            self.name_box = TextInput(max_length=NAME_MAX)
            pygame.key.start_text_input()  # the IME / on-screen keyboard, if any
            return True
        self.notify(f"Score {score} is not in the top 10 this time. Enter: next player.")
        self.ready_for_next = True
        return False

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
            self.notify("Score not stored. Enter: next player.")
            self.ready_for_next = True
        return result

    def clear(self) -> None:
        self.stored_rank = None
        if self.table.reset():
            self.notify("The high-score table was cleared.")
        self._pass_on_notices()

    def footer(self, confirming: bool) -> list[str]:
        if confirming:
            return ["Clear all scores?  Y: yes   N or Esc: no"]
        if self.ready_for_next:
            return ["Enter: next player"]
        return ["T: close   Delete or X: clear the table"]
