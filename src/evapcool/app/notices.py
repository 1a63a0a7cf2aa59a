"""Short messages shown for a few seconds at the bottom of the play area."""

from __future__ import annotations

#: How long a notice (damaged file, read-only folder...) stays on screen, s.
NOTICE_SECONDS = 8.0
#: At most this many notices at once; older ones make room.
NOTICE_MAX = 3


class Notices:
    """Messages with an expiry on the app's animation clock (seconds)."""

    def __init__(self) -> None:
        self._items: list[tuple[str, float]] = []
        self.now = 0.0

    def add(self, text: str) -> None:
        self._items.append((text, self.now + NOTICE_SECONDS))
        del self._items[:-NOTICE_MAX]

    def add_all(self, texts: list[str] | tuple[str, ...]) -> None:
        for text in texts:
            self.add(text)

    @property
    def visible(self) -> list[str]:
        return [text for text, until in self._items if until > self.now]
