"""Both themes by their pixels (issue 48): every text and line at 7:1 or more against what is
behind it, atoms told apart from the wall and from each other, in a real rendered window
(SDL's dummy driver). Contrast ratios are computed from the pixels read back, not from
the theme's table."""

from __future__ import annotations

import numpy as np
import pygame
import pytest

from evapcool.app.applet import App
from evapcool.game.rules import Game, GameConfig
from evapcool.view.scene import (
    BORDER_TOP,
    PLAY_RECT,
    SCENE_SIZE,
    SLIDER_RECT,
    TUBE_TOP,
)
from evapcool.view.screen import ScreenMap
from evapcool.view.theme import DARK, PROJECTOR, THEMES, contrast

#: The ratio asked of every text and line (WCAG AAA for text).
TEXT_RATIO = 7.0


@pytest.fixture(params=sorted(THEMES))
def themed(request, tmp_path, monkeypatch):
    """An App at scale 1 in the theme, a few frames in, the start hint shown."""
    monkeypatch.setenv("EVAPCOOL_DATA_DIR", str(tmp_path / "data"))
    monkeypatch.setenv("EVAPCOOL_CONFIG_DIR", str(tmp_path / "config"))
    app = App(
        Game(GameConfig(seed=1)),
        data_dir=tmp_path / "data",
        config_dir=tmp_path / "config",
        screen=SCENE_SIZE,
        overrides={"theme": request.param},
    )
    app.draw()
    yield app
    app.close()


def window(app: App) -> np.ndarray:
    return pygame.surfarray.array3d(app.window.surface).astype(int)


def region(app: App, logical: pygame.Rect) -> np.ndarray:
    """The pixels (x, y, rgb) of a logical rectangle of the scene."""
    lay = app.layout
    x0 = round(lay.scene.x + logical.x * lay.scale)
    y0 = round(lay.scene.y + logical.y * lay.scale)
    x1 = round(lay.scene.x + logical.right * lay.scale)
    y1 = round(lay.scene.y + logical.bottom * lay.scale)
    return window(app)[x0:x1, y0:y1]


def ink_contrast(px: np.ndarray) -> tuple[float, tuple, tuple]:
    """The text's (or line's) contrast in a region: the commonest colour is the background,
    the ink is the colour farthest from it in luminance among those covering 3 % or more
    of the non-background pixels (the letters' solid core, not their smoothed edges)."""
    colors, counts = np.unique(px.reshape(-1, 3), axis=0, return_counts=True)
    background = tuple(colors[np.argmax(counts)])
    others = [(tuple(c), n) for c, n in zip(colors, counts, strict=True) if tuple(c) != background]
    total = sum(n for _, n in others)
    assert total > 0, "nothing drawn in the region"
    solid = [c for c, n in others if n >= 0.03 * total]
    ink = max(solid, key=lambda c: contrast(c, background))
    return contrast(ink, background), ink, background


def _regions(app: App) -> dict[str, pygame.Rect]:
    thermo_x = SCENE_SIZE[0] - 48
    return {
        "title": pygame.Rect(200, 4, 240, BORDER_TOP - 8),
        "speed": pygame.Rect(4, 4, 140, BORDER_TOP - 8),
        "help hint": pygame.Rect(SCENE_SIZE[0] - 150, 4, 146, BORDER_TOP - 8),
        "T label": pygame.Rect(thermo_x - 16, TUBE_TOP - 30, 32, 28),
        "slider label": pygame.Rect(SLIDER_RECT.left, SLIDER_RECT.bottom + 4, SLIDER_RECT.w, 30),
        "start hint": pygame.Rect(PLAY_RECT.left + 40, PLAY_RECT.top + 22, PLAY_RECT.w - 80, 34),
    }


def test_every_text_is_at_seven_to_one(themed):
    found = {}
    for name, rect in _regions(themed).items():
        ratio, ink, background = ink_contrast(region(themed, rect))
        found[name] = (round(ratio, 2), ink, background)
    low = {k: v for k, v in found.items() if v[0] < TEXT_RATIO}
    assert low == {}, low


def test_notices_and_the_settings_panel_read_at_seven_to_one(themed):
    themed.notify("Settings saved.")
    themed.draw()
    box = pygame.Rect(PLAY_RECT.left + 10, PLAY_RECT.bottom - 30, 200, 22)
    ratio, *_ = ink_contrast(region(themed, box))
    assert ratio >= TEXT_RATIO
    themed.input.set_mode(themed.input.mode.__class__.SETTINGS)
    themed.options.open()
    themed.draw()
    rows = pygame.Rect(PLAY_RECT.left + 40, PLAY_RECT.top + 90, 200, 26)
    ratio, *_ = ink_contrast(region(themed, rows))
    assert ratio >= TEXT_RATIO


def test_the_cup_and_the_thermometer_lines_at_seven_to_one(themed):
    sim = themed.game.sim
    screen = ScreenMap.of(sim)
    x, y = screen.to_screen(np.array([[0.0, -sim.radii[0] - themed.scene.theme.cup_width / 2]]))[0]
    cup = pygame.Rect(round(x) - 2, round(y) - 30, 4, 60)  # across the band of the bottom
    ratio, *_ = ink_contrast(region(themed, cup))
    assert ratio >= TEXT_RATIO
    # The Tc mark across the tube, against the glass.
    thermo = pygame.Rect(SCENE_SIZE[0] - 48 - 4, TUBE_TOP + 20, 8, 470)
    px = region(themed, thermo)
    tc_row = np.flatnonzero((px == themed.scene.theme.tc_line).all(axis=2).any(axis=0))
    assert tc_row.size, "the Tc mark is not drawn"
    assert contrast(themed.scene.theme.tc_line, themed.scene.theme.glass) >= TEXT_RATIO


def test_atoms_stand_apart_from_the_wall_the_background_and_each_other(themed):
    theme = themed.scene.theme
    sim = themed.game.sim
    lay = themed.layout
    to_screen = ScreenMap.of(sim).to_screen
    centres = to_screen(sim.positions)
    px = window(themed)
    cores, rims = [], []
    r = float(sim.radii[0]) * lay.scale
    ring = [(np.cos(a), np.sin(a)) for a in np.linspace(0, 2 * np.pi, 16, endpoint=False)]
    for cx, cy in centres[:12]:
        wx, wy = lay.scene.x + cx * lay.scale, lay.scene.y + cy * lay.scale
        cores.append(tuple(px[round(wx), round(wy)]))
        # The median round a ring just inside the edge: the atom's outline.
        edge = [px[round(wx + 0.8 * r * c), round(wy + 0.8 * r * s)] for c, s in ring]
        rims.append(tuple(np.median(np.array(edge), axis=0)))
    core = tuple(np.median(np.array(cores), axis=0).astype(int))
    rim = tuple(np.median(np.array(rims), axis=0).astype(int))
    # Told from the wall and from the play area by colour and brightness alike.
    assert np.abs(np.subtract(core, theme.cup)).sum() > 150
    assert np.abs(np.subtract(core, theme.background)).sum() > 150
    if theme is PROJECTOR:  # light background: the atoms must be dark enough to see at once
        assert contrast(core, theme.background) >= 4.5
    # Two touching atoms: each one's edge is darker than the cores (no merged glow).
    assert sum(rim) < sum(core) - 60


def test_the_projector_theme_has_thicker_lines_and_larger_numbers():
    assert PROJECTOR.cup_width > DARK.cup_width
    assert PROJECTOR.text_scale > DARK.text_scale
    assert sum(PROJECTOR.background) > 3 * 240 and sum(DARK.background) < 3 * 200


def test_the_charts_lines_and_letters_at_seven_to_one():
    """The energy and path charts are light in both themes: their ink on the plot's white."""
    from evapcool.view import panels

    for name in ("INK", "CURVE", "CUT", "TC_LINE", "PATH"):
        color = getattr(panels, name)
        assert contrast(color, panels.PLOT_BG) >= TEXT_RATIO, name
        assert contrast(color, panels.BG) >= TEXT_RATIO or name != "INK", name


@pytest.mark.parametrize("theme", sorted(THEMES))
def test_the_command_line_chooses_the_theme(theme, tmp_path, monkeypatch):
    """`evapcool --theme projector` (and the settings' Theme row it overrides for the run)."""
    from evapcool.app import cli

    monkeypatch.setenv("EVAPCOOL_DATA_DIR", str(tmp_path / "data"))
    monkeypatch.setenv("EVAPCOOL_CONFIG_DIR", str(tmp_path / "config"))
    shot = tmp_path / "shot.png"
    assert cli.main(["--theme", theme, "--frames", "1", "--screenshot", str(shot)]) == 0
    image = pygame.image.load(str(shot))
    w, h = image.get_size()
    scale = min(w / SCENE_SIZE[0], h / SCENE_SIZE[1])
    at = (round((PLAY_RECT.left + 6) * scale), round((PLAY_RECT.top + 6) * scale))
    assert tuple(image.get_at(at))[:3] == THEMES[theme].background
