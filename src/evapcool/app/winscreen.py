"""The win: the name box and the high-score table, the replay code and its strip.

`WinScreen.settle` decides what a win means (a player's score, the autopilot's, a watched
replay's) and says it; the app then gives the keyboard to the name box if one opened.
While the name box is open it owns every letter, C too: the strip then says that C
copies the code once the name is stored or skipped.
"""

from __future__ import annotations

from dataclasses import dataclass

from evapcool.app.notices import Notices
from evapcool.app.replays import ReplayKeeper
from evapcool.app.scoring import Scoreboard
from evapcool.app.words import t
from evapcool.game.rules import Game


@dataclass(frozen=True)
class Won:
    """What a win asks of the app: the name box (the keyboard is its), a code to send."""

    ask_name: bool = False
    send: str | None = None


class WinScreen:
    """A won game's outcome: its score for the table or the autopilot's, its replay code."""

    def __init__(self, scores: Scoreboard, replays: ReplayKeeper, notices: Notices) -> None:
        self.scores = scores
        self.replays = replays
        self.notices = notices

    def settle(
        self,
        game: Game,
        *,
        watched: int | None,
        pilot: str | None,
        in_class: bool,
        name: str | None = None,
    ) -> Won:
        """The game just won. watched: the claimed score of a replay being watched (its
        win is nobody's); pilot: the autopilot's table name if it flew this game;
        in_class: a class challenge is on (a player's code goes to it); name: the class
        player's own name (--name), stored in the table without asking."""
        score, seconds = game.score or 0, game.won_at or 0.0
        if watched is not None:
            self.notices.news(t("desk.replay.won", n=score, claimed=watched))
            return Won()
        code = self.replays.finish(game)
        if pilot is not None:  # never in the players' table
            if in_class:
                self.notices.news(t("desk.class.autopilot"))
            self.scores.autopilot_win(pilot, score, seconds)
            return Won()
        send = code if in_class else None
        if send is not None:
            self.notices.news(t("desk.class.sending"))
        return Won(self.scores.win(score, seconds, name if in_class else None), send)

    def offered(self, game: Game) -> bool:
        """The win screen shows the replay strip (a won game that was recorded)."""
        return game.score is not None and self.replays.code is not None

    def copy(self, game: Game) -> None:
        """Key C or the strip: the won game's code to the clipboard (not while the name
        box is open: C is a letter there)."""
        if self.offered(game) and self.scores.name_box is None:
            self.replays.copy()

    def strip_label(self) -> str:
        """The strip's words: what C does now."""
        if self.scores.name_box is not None:
            return t("replay.button_after_name")
        return t("replay.button")

    @property
    def ready_for_next(self) -> bool:
        """The round is over (stored or skipped): Enter starts the next player's."""
        return self.scores.ready_for_next
