"""Scene and charts fitted to the window and the screen (pure geometry), and in the app."""

from __future__ import annotations

import pygame
import pytest
from apphelp import frames, key, pixels
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.app.layout import SCENE, arrange, window_size_for
from evapcool.view.scene import BORDER

pytestmark = pytest.mark.usefixtures("own_folders")


@settings(max_examples=200, deadline=None)
@given(
    st.integers(min_value=200, max_value=4000),
    st.integers(min_value=200, max_value=3000),
    st.integers(min_value=0, max_value=2),
)
def test_everything_fits_the_window_and_nothing_overlaps(w, h, n):
    lay = arrange((w, h), n)
    window = pygame.Rect(0, 0, w, h)
    assert window.contains(lay.scene)
    assert abs(lay.scene.w / SCENE[0] - lay.scale) * SCENE[0] <= 1  # the whole scene, scaled
    assert len(lay.charts) == n
    for r in lay.charts:
        assert window.contains(r) and not r.colliderect(lay.scene) and r.w > 0 and r.h > 0
    for a, b in zip(lay.charts, lay.charts[1:], strict=False):
        assert not a.colliderect(b)
    if n:  # below always keeps 2/3 of the scene's size alone: charts never cover it
        assert lay.scale >= 2 / 3 * arrange((w, h), 0).scale - 1e-9


def test_beside_on_a_wide_window_below_on_a_tall_one():
    assert arrange((1160, 672), 1).arrangement == "beside"
    assert arrange((640, 1008), 2).arrangement == "below"
    lay = arrange((1160, 672), 2)
    assert lay.scale == 1.0 and lay.scene == pygame.Rect(0, 0, 640, 672)
    assert lay.charts == (pygame.Rect(640, 0, 520, 336), pygame.Rect(640, 336, 520, 336))


def test_window_sizes_keep_the_scale_where_the_screen_has_room():
    assert window_size_for(1.0, 1, (1900, 1000)) == ((1160, 672), "beside")
    assert window_size_for(1.5, 0, (1900, 1100)) == ((960, 1008), "alone")
    assert window_size_for(1.5, 0, (1900, 1000)) == ((952, 1000), "alone")  # as fits
    # A 1024 x 768 screen (less the bars): the scene shrinks to let the chart in beside it.
    (w, h), name = window_size_for(1.0, 1, (1008, 688))
    assert name == "beside" and w <= 1008 and h <= 688
    assert arrange((w, h), 1).scale == pytest.approx(1008 / 1160, abs=0.002)
    # A portrait screen: below.
    (w, h), name = window_size_for(1.0, 2, (760, 1200))
    assert name == "below" and (w, h) == (640, 1008)
    # Closing the charts gives the scene back its scale.
    assert window_size_for(1.0, 0, (1008, 688))[0] == (640, 672)


@pytest.mark.parametrize(
    ("screen", "arrangement"), [((1024, 768), "beside"), ((800, 1280), "below")]
)
def test_opening_charts_on_a_small_screen_keeps_the_window_on_it(make_app, screen, arrangement):
    app = make_app(screen=screen)
    key(app, pygame.K_e)
    key(app, pygame.K_g)
    w, h = app.window.size
    usable = app.window.usable()
    assert w <= usable[0] and h <= usable[1]
    lay = app.layout
    assert lay.arrangement == arrangement
    assert pygame.Rect(0, 0, w, h).contains(lay.scene) and len(lay.charts) == 2
    px = pixels(app)
    # The scene's corners are all there (borders), and the charts are drawn.
    for x, y in (lay.scene.topleft, (lay.scene.right - 1, lay.scene.bottom - 1)):
        assert tuple(px[x + 2 if x == lay.scene.x else x - 2, y + 2 if y == 0 else y - 2]) == BORDER
    for r in lay.charts:
        assert tuple(px[r.x + 3, r.y + 3]) == (244, 243, 238)  # the charts' background
    key(app, pygame.K_e)
    key(app, pygame.K_g)
    frames(app)
    assert app.window.size == (640, 672) or screen[1] - 80 < 672


def test_a_users_resize_sets_the_scale_charts_then_keep(make_app):
    app = make_app()  # a 1920 x 1080 screen
    app.window.win.size = (960, 1008)  # the user drags the corner...
    pygame.event.post(pygame.event.Event(pygame.WINDOWRESIZED, x=960, y=1008))
    frames(app)  # ...and the window says so
    assert app.preferred_scale == pytest.approx(1.5)
    key(app, pygame.K_e)
    lay = app.layout
    assert lay.arrangement == "beside"
    assert lay.scale == pytest.approx(min(1.5, 1000 / 672), abs=0.01)  # as big as still fits
    key(app, pygame.K_e)
    assert app.layout.scale == pytest.approx(min(1.5, 1000 / 672), abs=0.01)
    # Our own resizes do not count as the user's choice.
    assert app.preferred_scale == pytest.approx(1.5)
