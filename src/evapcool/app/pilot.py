"""Who moves the trap: the player, or an autopilot (key A, `evapcool --autopilot FILE`)."""

from __future__ import annotations

from evapcool.app.notices import Notices
from evapcool.app.words import t
from evapcool.game.autopilot import Autopilot
from evapcool.game.rules import Game


class PilotSeat:
    """The autopilot, if any, and whether it has the trap; says each change as news."""

    def __init__(self, notices: Notices, autopilot: Autopilot | None = None) -> None:
        self.notices = notices
        self.autopilot = autopilot

    def seat(self, game: Game) -> None:
        """At the start (`--autopilot`): it sets its start height and waits for Space."""
        if self.autopilot is not None:
            self.notices.news(t("notice.autopilot_ready", name=self.autopilot.label))
            self.autopilot.steer(game)  # the start height it wants, shown before Space

    def toggle(self, game: Game) -> None:
        """Key A: the autopilot takes the trap (the demo if none was given) and plays at
        once, as its notice says; or it hands the trap back."""
        if self.autopilot is None:
            self.autopilot = Autopilot.load("demo")
        elif self.autopilot.toggle() is False:
            self.notices.news(t("notice.you_have_trap"))
            return
        self.autopilot.engage()
        if game.paused and not game.won and game.too_few_atoms is None:
            game.toggle_pause()  # "plays" is what happens next, not after Space
        self.autopilot.steer(game)
        self.notices.news(t("notice.autopilot_plays", name=self.autopilot.label))

    def take_over(self) -> None:
        """The player touched the trap's controls: the autopilot lets go."""
        if self.autopilot is not None and self.autopilot.engaged:
            self.autopilot.take_over()
            self.notices.news(t("notice.you_have_trap"))

    def steer(self, game: Game) -> None:
        """The trap for this frame, from the gas now (nothing if the player has it)."""
        if self.autopilot is not None:
            self.autopilot.steer(game)

    def new_game(self, game: Game) -> None:
        if self.autopilot is not None:
            self.autopilot.new_game()
            self.autopilot.steer(game)

    @property
    def flew(self) -> bool:
        """The autopilot moved the trap in this game: its win is not a player's."""
        return self.autopilot is not None and self.autopilot.flew
