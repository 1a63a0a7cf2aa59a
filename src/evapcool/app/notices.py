"""Short messages shown for a few seconds at the bottom of the play area.

Two kinds, drawn apart: news (a code copied, settings saved, the autopilot's turn) belongs to
the game it was said in, so the next game's start drops it; a problem (a damaged file, a
folder that cannot be written, a class server that did not answer) stays its full time,
whatever starts meanwhile, and is drawn on the warning colour.
"""

from __future__ import annotations

from dataclasses import dataclass

#: How long a notice (damaged file, read-only folder...) stays on screen, s.
NOTICE_SECONDS = 8.0
#: At most this many notices at once; older ones make room.
NOTICE_MAX = 3


@dataclass(frozen=True)
class Notice:
    text: str
    until: float
    #: Something went wrong (drawn as a warning, kept across a restart).
    problem: bool


class Notices:
    """Messages with an expiry on the app's animation clock (seconds)."""

    def __init__(self) -> None:
        self._items: list[Notice] = []
        self.now = 0.0

    def _add(self, text: str, problem: bool) -> None:
        self._items.append(Notice(text, self.now + NOTICE_SECONDS, problem))
        del self._items[:-NOTICE_MAX]

    def news(self, text: str) -> None:
        """Something that happened as asked; it lasts until the next game starts at most."""
        self._add(text, False)

    def problem(self, text: str) -> None:
        """Something that went wrong; it lasts its full time."""
        self._add(text, True)

    def add_all(self, texts: list[str] | tuple[str, ...]) -> None:
        """Problems found before the window opened (damaged files)."""
        for text in texts:
            self.problem(text)

    def new_game(self) -> None:
        """A game starts: the last game's news is over."""
        self._items = [n for n in self._items if n.problem]

    @property
    def shown(self) -> list[Notice]:
        return [n for n in self._items if n.until > self.now]

    @property
    def visible(self) -> list[str]:
        return [n.text for n in self.shown]
