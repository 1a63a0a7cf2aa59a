"""The settings screen (key O): a draft edited with the arrow keys, saved or dropped."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import NamedTuple

import pygame

from evapcool.app.notices import Notices
from evapcool.app.words import choose, t
from evapcool.game import settings as settings_mod
from evapcool.game.settings import Settings, describe, load_settings, max_atoms, save_settings


class Looks(NamedTuple):
    """What the window looks and sounds like now (no restart needed)."""

    theme: str
    sound: str
    volume: int


class SettingsEditor:
    """Saved settings, this run's command-line overrides, and the draft on screen."""

    def __init__(
        self,
        path: Path,
        notices: Notices,
        settings: Settings | None = None,
        overrides: Mapping[str, object] | None = None,
    ) -> None:
        self.path = path
        self.notices = notices
        if settings is None:
            settings, problems = load_settings(path)
            notices.add_all(problems)
        self.settings = settings
        self.overrides = {k: v for k, v in (overrides or {}).items() if v is not None}
        self.draft = settings
        self.row = 0
        #: Fields a setup's link fixed (its `lock`): shown, not changeable; always this run's.
        self.locked: frozenset[str] = frozenset()

    def looks(self) -> Looks:
        """The theme, sound and volume in use: this run's override, else the saved one."""
        s, o = self.settings, self.overrides
        return Looks(str(o.get("theme", s.theme)), str(o.get("sound", s.sound)), int(s.volume))

    def for_run(self) -> Settings:
        """What a restart applies: the saved settings with this run's overrides on top."""
        try:
            return settings_mod.with_overrides(self.settings, **self.overrides)
        except ValueError as exc:
            self.notices.problem(t("notice.options_dropped", problem=exc))
            self.overrides = {}
            return self.settings

    def open(self) -> None:
        self.draft = self.settings
        self.row = 0

    def key(self, key: int) -> None:
        """Up/Down choose a row, Left/Right change its value."""
        names = settings_mod.FIELD_NAMES
        if key == pygame.K_UP:
            self.row = (self.row - 1) % len(names)
        elif key == pygame.K_DOWN:
            self.row = (self.row + 1) % len(names)
        elif key in (pygame.K_LEFT, pygame.K_RIGHT):
            if names[self.row] in self.locked:
                self.notices.news(t("desk.link.locked_setting"))
                return
            d = 1 if key == pygame.K_RIGHT else -1
            self.draft = settings_mod.step(self.draft, names[self.row], d)

    def close(self, save: bool) -> None:
        draft = self.draft
        if not save or draft == self.settings:
            return
        previous, self.settings = self.settings, draft
        # A choice made here beats the command line for the rest of the run; a link's locks stay.
        self.overrides = {k: v for k, v in self.overrides.items() if k in self.locked}
        # Only the fields changed here go over the file: another window's choices stay.
        if draft.language != previous.language:  # shown at once, no restart needed
            choose(None, draft.language)
        problems = save_settings(draft, self.path, base=previous)
        self.notices.add_all(problems)
        if not problems:
            self.notices.news(t("settings.saved"))

    def rows(self) -> list[tuple[str, str]]:
        return describe(self.draft)

    def footer(self) -> list[str]:
        r = self.draft.radius
        lines = [
            t("settings.max_atoms", n=max_atoms(r), radius=r),
            t("help.choose_change"),
            t("settings.save_cancel"),
        ]
        if self.overrides:
            names = ", ".join(sorted(self.overrides))
            lines.append(t("settings.overrides", names=names))
        return lines
