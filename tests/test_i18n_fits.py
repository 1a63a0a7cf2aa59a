"""Catalog strings against the desktop's real boxes, and Arabic/CJK with the font chain.

The scene is 640 x 672 logical px, so the smallest desktop layout (a 640 px wide window)
draws these boxes 1:1. BOXES: one line of (size, bold, width); keys matching WRAPPED are
wrapped by the view (view.scene.wrap: words, CJK runs cut where they must be), so only
the widest wrapped row counts. Other messages (the page's, the class server's) keep one
line of 16 px within a 600 px column. Every locale and the 40 %-longer pseudo-locale.
"""

from __future__ import annotations

import pygame
import pytest

from evapcool import i18n
from evapcool.game import settings
from evapcool.view import fonts
from evapcool.view.scene import (
    HELP_WIDTH,
    PLAY_RECT,
    REPLAY_RECT,
    SETTING_ROW,
    STATUS_WIDTH,
    TABLE_HEADS,
    TITLE_WIDTH,
    wrap,
)

TEXT_COLUMN = 600
PANEL = PLAY_RECT.width - 24  # the help, table and settings panels
WIDE = PLAY_RECT.width - 16  # the big messages over the play area
#: One-line boxes: (size, bold, width). A text that shrinks to fit (view.scene.fit_size)
#: is measured at the least size it may shrink to.
BOXES: dict[str, tuple[int, bool, int]] = {
    "app.title": (20, False, TITLE_WIDTH),  # between the speed and "H: help"
    "status.speed": (22, False, STATUS_WIDTH),
    "status.help_hint": (22, False, STATUS_WIDTH),
    "controls.title": (20, True, PANEL - 16),
    "scores.title": (20, True, PANEL - 16),
    "settings.title": (20, True, PANEL - 16),
    "scores.empty": (24, False, PANEL - 50),
    "table.rank": (12, True, TABLE_HEADS[0]),
    "table.name": (12, True, TABLE_HEADS[1]),
    "table.atoms": (12, True, TABLE_HEADS[2]),
    "table.time": (12, True, TABLE_HEADS[3]),
    "table.date": (12, True, TABLE_HEADS[4]),
    "win.score_big": (42, True, WIDE),
    "win.condensed": (18, True, WIDE),
    "win.top10": (12, True, PLAY_RECT.width - 80),
    "win.store_or_skip": (22, False, PLAY_RECT.width - 100 - 70),  # beside "16/16"
    "win.name_full": (22, True, 150),
    "lose.too_few": (26, True, WIDE),
    "replay.button": (12, True, REPLAY_RECT.width - 16),
    "controls.trap_height": (24, False, 336),
    "help.key.space": (16, True, 150),  # the help's key column
    "help.key.left_down": (16, True, 150),
    "help.key.right_up": (16, True, 150),
    "help.key.delete_x": (16, True, 150),
    "help.key.enter": (16, True, 150),
    "help.key.esc": (16, True, 150),
    "help.key.mouse": (16, True, 150),
}
#: The settings screen's rows: label (24) and "< value >" (24 bold) share one line.
#: Wrapped messages: notices (22 px in the play area), the help (at least 16 px beside its
#: key column), footers, the too-few reason, the progress screen.
WRAPPED = ("notice.", "lose.", "start.", "help.", "table.footer", "table.clear")
WRAPPED += ("table.autopilot_row", "settings.overrides", "settings.max_atoms", "settings.save")
WRAPPED += ("win.next_player", "win.not_stored", "scores.", "settings.saved", "desk.", "replay.")
WRAPPED += ("storage.", "status.slow", "help.choose")
# The debrief's best path in words: a paragraph for screen readers (wrapped by the page).
WRAPPED += ("debrief.describe",)
WRAP_WIDTH = HELP_WIDTH - 150 - 16
SAMPLE = {"n": 12345, "p": 0.667, "height": 400, "percent": 87, "problem": "disk full"}
SAMPLE |= {"radius": 2.5, "mode": "autopilot", "name": "Anonymous"}
# The class server's and the desktop's class words (a path, an address, a reason).
SAMPLE |= {"path": "~/.local/share/evapcool/replays/x.txt", "url": "http://10.0.0.2:8765/"}
SAMPLE |= dict(id=12, reason="the challenge is closed", detail="d", got=1, wanted=2, allowed="1..2")
SAMPLE |= dict(score=25, frames=1234, runs=5, first=6, last=7, escape="rim", seed=8)
SAMPLE |= dict(speed="1/2", step=5, fast=4, slow="1/4", low=80, high=450, fps=60, physics=2.5)
SAMPLE |= dict(drawing=3.1, t="0.123", tc="0.2", count="16/16", time="1:23.4", max=62)
SAMPLE |= dict(names="radius", default="'rim'", why="not valid JSON", s=12)
SAMPLE |= dict(done=2, total=6)
SAMPLE |= dict(edition="desktop", claimed=25)
# The page's placeholders (its messages are not measured here; the no-tofu test draws them).
_ENGLISH = i18n.Catalog(i18n.FALLBACK).english
_NAMES = {n for k, m in _ENGLISH.items() for n in i18n.placeholders(i18n.parse_message(m, k))}
SAMPLE = dict.fromkeys(_NAMES, 2) | SAMPLE


#: The page's own words (the browser's boxes): measured by web/test/i18n.fits.test.ts.
PAGE_ONLY = ("page.", "hint.", "button.", "control.", "verify.", "reason.", "help.autopilot_page")
PAGE_ONLY += ("help.verify", "help.escape_page", "help.mouse_page", "settings.language_browser")
#: The console's paragraphs (what to do on a refusal page, a confirmation's question, a
#: link shown once): HTML text the browser wraps in its column, not one-line boxes.
PAGE_ONLY += (
    "console.todo.",
    "console.error.archived",
    "console.admin.confirm_retire",
    "console.admin.once",
    "console.lecturer.confirm_text",
)


def overflows(locale: str) -> list[tuple[str, int, int]]:
    """(key, width, box width) of every message of `locale` wider than its box."""
    catalog = i18n.Catalog(locale)
    found = []
    for key in catalog.english:
        if key.startswith(PAGE_ONLY):
            continue
        args = SAMPLE | {"n": 999} if key == "win.score_big" else SAMPLE
        text = catalog.t(key, **args)
        if key in BOXES:
            size, bold, width = BOXES[key]
            drawn = fonts.text_size(text, size, bold)[0]
        elif key.startswith(WRAPPED):
            width = WRAP_WIDTH
            drawn = max(fonts.text_size(row, 22)[0] for row in wrap(text, 22, width))
        else:
            width = TEXT_COLUMN
            drawn = fonts.text_size(text, 16)[0]
        if drawn > width:
            found.append((key, drawn, width))
    return found


def setting_overflows(locale: str) -> list[tuple[str, int, int]]:
    """Settings rows whose label and marked value do not fit side by side."""
    i18n.use(locale)
    try:
        found = []
        for language in ("auto", "pt-BR", "ar"):
            s = settings.Settings(n_atoms=1000, radius=12.0, escape="knife", language=language)
            for label, value in settings.describe(s):
                # The label shrinks (to 12 px at least) to leave the value its room.
                drawn = fonts.text_size(label, 12)[0] + fonts.text_size(f"< {value} >", 24, True)[0]
                if drawn > SETTING_ROW:
                    found.append((label, drawn, SETTING_ROW))
        return found
    finally:
        i18n.use(i18n.FALLBACK)


@pytest.fixture(scope="module", autouse=True)
def _pygame() -> object:
    pygame.init()
    yield None
    pygame.quit()


@pytest.mark.parametrize("locale", [*i18n.shipped_locales(), i18n.PSEUDO])
def test_every_string_fits_its_box(locale: str) -> None:
    assert overflows(locale) == []


@pytest.mark.parametrize("locale", [*i18n.shipped_locales(), i18n.PSEUDO])
def test_every_settings_row_fits(locale: str) -> None:
    assert setting_overflows(locale) == []


def test_overflow_is_detected() -> None:
    assert fonts.text_size("W" * 80, 16)[0] > TEXT_COLUMN


@pytest.mark.parametrize("locale", ["ar", "ja", "zh-CN", "ko"])
def test_no_tofu(locale: str) -> None:
    catalog = i18n.Catalog(locale)
    for key in catalog.english:
        assert fonts.missing(catalog.t(key, **SAMPLE)) == [], key


def test_arabic_is_shaped_and_right_to_left() -> None:
    word = "سلام"
    widths = [fonts.text_size(ch, 32)[0] for ch in word]
    assert min(widths) > 0 and len(set(widths)) > 1
    assert fonts.text_size(word, 32)[0] < sum(widths)  # joined forms are narrower
    image = fonts.text_image("اب", 48, (0, 0, 0))  # alef, then beh
    mask = pygame.mask.from_surface(image)
    columns = [
        sum(mask.get_at((x, y)) for y in range(mask.get_size()[1]))
        for x in range(mask.get_size()[0])
    ]
    tallest = max(range(len(columns)), key=columns.__getitem__)
    assert tallest > len(columns) / 2  # alef, read first, stands on the right
