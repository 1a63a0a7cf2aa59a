"""The panels drawn over the play area: help, high scores, settings, the name box.

Which one shows is the input machine's mode; what each shows comes from its owner (the
key table, the scoreboard, the settings editor, the frame timings). The help's rows are
written from the key table, so the help lists exactly the keys there are.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from evapcool.app.input import Binding, InputMachine, Mode
from evapcool.app.options import SettingsEditor
from evapcool.app.scoring import Scoreboard
from evapcool.app.stats import FrameStats
from evapcool.app.words import t
from evapcool.view.pen import Pen
from evapcool.view.scene import PLAY_RECT, UNDER_MESSAGE, Scene

#: Mouse controls, listed in the help overlay after the keys.
MOUSE_HELP = [("help.key.mouse", "help.mouse"), ("", "help.mouse_more")]


def _word(label: str) -> str:
    """A key's name: a catalog key (help.key.*) translated, a key cap ("R", "F11") as is."""
    return t(label) if label.startswith("help.key.") else label


def help_rows(bindings: Sequence[Binding], numbers: dict[str, object]) -> list[tuple[str, str]]:
    """The help overlay's (keys, what they do) rows in the chosen language; numbers: the
    values its messages name."""
    mouse = Binding((), *MOUSE_HELP[0], more=(MOUSE_HELP[1][1],))
    rows = []
    for b in [*bindings, mouse]:
        rows.append((_word(b.label), t(b.help, **numbers)))
        rows.extend(("", t(line, **numbers)) for line in b.more)
    return rows


@dataclass
class Overlays:
    """Draws what the input machine has open over the play area; numbers: the values the
    help's messages name."""

    scene: Scene
    machine: InputMachine
    scores: Scoreboard
    options: SettingsEditor
    stats: FrameStats
    numbers: dict[str, object]

    def help_rows(self) -> list[tuple[str, str]]:
        return help_rows(self.machine.bindings, self.numbers)

    def draw(self, pen: Pen, won: bool, bottom: int = PLAY_RECT.bottom) -> None:
        """won: the score is on screen (the table opens under it); bottom: keep above."""
        overlay = self.machine.overlay
        if self.scores.name_box is not None:
            self.scene.draw_name_entry(pen, self.scores.name_box, t("win.top10"))
        elif overlay == "help":
            self.scene.draw_help(pen, self.help_rows(), self.stats.lines())
        elif overlay == "table":
            confirming = self.machine.mode is Mode.CONFIRM_CLEAR
            self.scene.draw_table(
                pen,
                self.scores.table.entries,
                self.scores.stored_rank,
                self.scores.footer(confirming),
                top=UNDER_MESSAGE if won else None,
                bottom=bottom,
            )
        elif overlay == "settings":
            self.scene.draw_settings(
                pen, self.options.rows(), self.options.row, self.options.footer()
            )
