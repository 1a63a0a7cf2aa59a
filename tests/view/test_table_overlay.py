"""The high-score table hides what lies under it: the cup does not show through (issue 25.5)."""

from __future__ import annotations

import numpy as np
import pygame
import pytest

from evapcool.game.highscores import Entry
from evapcool.view.pen import Pen
from evapcool.view.scene import CUP_COLOR, Scene

SIZE = (640, 672)
MAGENTA = (255, 0, 255)
ENTRIES = [Entry("Ada", 31, 41.5, "2026-11-25 02:00"), Entry("Bo", 29, 44.0, "2026-11-24 09:30")]


@pytest.fixture(scope="module", autouse=True)
def _pygame() -> None:
    pygame.init()
    yield
    pygame.quit()


def _table_over(background: tuple[int, int, int]) -> tuple[np.ndarray, pygame.Rect]:
    surface = pygame.Surface(SIZE)
    surface.fill(background)
    rect = Scene().draw_table(Pen(surface), ENTRIES, highlight=1)
    return pygame.surfarray.array3d(surface), rect


@pytest.mark.parametrize("under", [CUP_COLOR, MAGENTA, (250, 250, 250)])
def test_nothing_under_the_table_shows_through(under: tuple[int, int, int]) -> None:
    seen, rect = _table_over(under)
    plain, same_rect = _table_over((40, 90, 40))
    assert rect == same_rect and rect.width > 100 and rect.height > 100
    inside = (slice(rect.left + 3, rect.right - 3), slice(rect.top + 3, rect.bottom - 3))
    assert np.array_equal(seen[inside], plain[inside])


def test_the_help_panel_stays_translucent() -> None:
    """The check above can fail: a translucent panel lets its background through."""
    surface = pygame.Surface(SIZE)
    surface.fill(MAGENTA)
    rect = Scene().draw_help(Pen(surface), [("A", "autopilot")])
    corner = surface.get_at((rect.left + 6, rect.bottom - 6))[:3]
    assert corner != (10, 10, 30) and corner[0] > 10
