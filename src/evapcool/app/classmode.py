"""The applet in a class competition (`evapcool --class URL`): the challenge and its news.

`ClassMode` starts the link, turns what the class server says into notices, and holds the
challenge being played; it never restarts the game itself: `news` says when the app should
(the challenge arrived before the game began).
"""

from __future__ import annotations

from evapcool.app.classlink import Challenge, ClassLink, Event
from evapcool.app.notices import Notices
from evapcool.app.words import t


class ClassMode:
    """One class server's link (or none: then every call does nothing)."""

    def __init__(self, link: ClassLink | None, notices: Notices) -> None:
        self.link = link
        self.notices = notices
        #: The class challenge being played (its settings and seed on every restart).
        self.challenge: Challenge | None = None
        self._joined = ""

    def start(self) -> None:
        if self.link is not None:
            self.notices.news(t("desk.class.joining", url=self.link.base))
            self.link.start()

    def send(self, code: str) -> None:
        """A player's winning code, to be ranked by the class server."""
        if self.link is not None and self.challenge is not None:
            self.link.submit(code)

    @property
    def counts_lost(self) -> bool:
        """The challenge being played takes lost games (ranked with 0 atoms)."""
        return self.link is not None and self.challenge is not None and self.challenge.lost

    def send_lost(self, code: str) -> None:
        """A game lost for good, when the challenge counts lost games."""
        if self.counts_lost:
            self.notices.news(t("desk.class.sending"))
            self.send(code)

    def news(self, begun: bool) -> bool:
        """What the server said since the last frame, as notices. begun: the game has
        started. True if a challenge arrived that the unbegun game should restart into
        (the app restarts, then calls `joined`)."""
        if self.link is None:
            return False
        restart = False
        for event in self.link.poll():
            restart = self._event(event, begun) or restart
        return restart

    def _event(self, event: Event, begun: bool) -> bool:
        if event.kind == "joined":
            ch: Challenge = event.value
            self.challenge = ch
            self._joined = t("desk.class.joined", id=ch.id, n=ch.settings.n_atoms, name=event.name)
            if not begun:  # switch to the challenge's atoms now: said after the restart
                return True
            self.joined()
            self.notices.news(t("desk.class.press_r"))
        elif event.kind == "result":
            doc = event.value
            self.notices.news(
                t("desk.class.result", n=doc["rank"], score=doc["score"], frames=doc["frames"])
            )
        elif event.kind == "refused":
            self.notices.problem(t("desk.class.refused", reason=event.value))
        else:
            why = t(f"desk.class.why.{event.value}", seconds=round(self.link_timeout))
            self.notices.problem(t("desk.class.unreachable", problem=why))
        return False

    def joined(self) -> None:
        """Say which challenge is being played (once the game shows its atoms)."""
        self.notices.news(self._joined)

    @property
    def player_name(self) -> str | None:
        """The name the player gave (--name), known before any win; None if not given."""
        link = self.link
        return link.name if link is not None and link.named else None

    @property
    def link_timeout(self) -> float:
        return self.link.timeout if self.link is not None else 0.0
