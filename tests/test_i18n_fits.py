"""Catalog strings against their boxes on the desktop, and Arabic/CJK with the font chain."""

from __future__ import annotations

import pygame
import pytest

from evapcool import i18n
from evapcool.view import fonts

# Provisional boxes (logical px at the 640 px layout) until the strings are wired:
# titles in bold 24, everything else one line of 16 within the 600 px text column.
TEXT_COLUMN = 600
BOXES = {"title": (24, True, TEXT_COLUMN), "line": (16, False, TEXT_COLUMN)}
SAMPLE = {"n": 12345, "p": 0.667, "height": 400, "percent": 87, "problem": "disk full"}
SAMPLE |= {"radius": 2.5, "mode": "autopilot", "name": "Anonymous"}
# The class server's and the desktop's class words (a path, an address, a reason).
SAMPLE |= {"path": "~/.local/share/evapcool/replays/x.txt", "url": "http://10.0.0.2:8765/"}
SAMPLE |= dict(id=12, reason="the challenge is closed", detail="d", got=1, wanted=2, allowed="1..2")
SAMPLE |= dict(score=25, frames=1234, runs=5, first=6, last=7, escape="rim", seed=8)
SAMPLE |= dict(edition="desktop", claimed=25)


def box_of(key: str) -> tuple[int, bool, int]:
    """Font size, boldness and width of the box a message is drawn in."""
    return BOXES["title" if key.endswith(".title") else "line"]


def overflows(locale: str) -> list[tuple[str, int, int]]:
    """(key, width, box width) of every message of `locale` wider than its box."""
    catalog = i18n.Catalog(locale)
    found = []
    for key in catalog.english:
        size, bold, width = box_of(key)
        drawn = fonts.text_size(catalog.t(key, **SAMPLE), size, bold)[0]
        if drawn > width:
            found.append((key, drawn, width))
    return found


@pytest.fixture(scope="module", autouse=True)
def _pygame() -> object:
    pygame.init()
    yield None
    pygame.quit()


@pytest.mark.parametrize("locale", [*i18n.shipped_locales(), i18n.PSEUDO])
def test_every_string_fits_its_box(locale: str) -> None:
    assert overflows(locale) == []


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
