"""The reusable widgets: one control(mouse) call per frame updates, draws, returns."""

from __future__ import annotations

import ast
import inspect

import pygame
import pytest

from evapcool.view import widgets
from evapcool.view.widgets import Button, ImageButton, MouseState, Slider, ToggleButton

RED, GREEN, BLUE = (255, 0, 0), (0, 255, 0), (0, 0, 255)
CYAN, MAGENTA, YELLOWISH = (0, 255, 255), (255, 0, 255), (255, 255, 0)


@pytest.fixture(autouse=True)
def _pygame():
    pygame.font.init()
    yield


def solid(color, size=(20, 20)) -> pygame.Surface:
    s = pygame.Surface(size)
    s.fill(color)
    return s


def test_widgets_module_imports_nothing_from_the_game():
    tree = ast.parse(inspect.getsource(widgets))
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.module]
    assert not [n for n in names if n.startswith("evapcool")]


def test_button_fires_only_on_a_click_inside():
    surf = pygame.Surface((100, 100))
    b = Button(surf, (10, 10, 30, 30))
    assert b.control(MouseState((20, 20), clicked=True, down=True)) is True
    assert b.control(MouseState((20, 20), clicked=False, down=True)) is False  # held, not new
    assert b.control(MouseState((60, 60), clicked=True, down=True)) is False  # outside
    assert b.control(MouseState((20, 20))) is False  # hover
    assert surf.get_at((25, 25))[:3] == (0, 0, 0)  # the plain button draws black


def test_button_looks_follow_the_mouse():
    b = Button(pygame.Surface((50, 50)), (0, 0, 10, 10))
    assert b.look(MouseState((30, 30))) == "idle"
    assert b.look(MouseState((5, 5))) == "hover"
    assert b.look(MouseState((5, 5), down=True)) == "down"
    assert b.look(MouseState((30, 30), down=True)) == "idle"


def test_image_button_draws_the_image_of_its_look():
    surf = pygame.Surface((100, 100))
    b = ImageButton(surf, (40, 40, 20, 20), solid(RED), solid(GREEN), solid(BLUE))
    b.control(MouseState((0, 0)))
    assert surf.get_at((50, 50))[:3] == RED
    b.control(MouseState((45, 45)))
    assert surf.get_at((50, 50))[:3] == GREEN
    assert b.control(MouseState((45, 45), clicked=True, down=True)) is True
    assert surf.get_at((50, 50))[:3] == BLUE


def test_image_button_defaults_hover_to_idle_and_down_to_hover():
    surf = pygame.Surface((100, 100))
    b = ImageButton(surf, (40, 40, 20, 20), solid(RED))
    b.control(MouseState((45, 45), down=True))
    assert surf.get_at((50, 50))[:3] == RED
    b = ImageButton(surf, (40, 40, 20, 20), solid(RED), solid(GREEN))
    b.control(MouseState((45, 45), down=True))
    assert surf.get_at((50, 50))[:3] == GREEN


def test_toggle_button_flips_on_click_and_returns_its_state():
    surf = pygame.Surface((100, 100))
    on = (solid(RED), solid(GREEN), solid(BLUE))
    off = (solid(CYAN), solid(MAGENTA), solid(YELLOWISH))
    t = ToggleButton(surf, (40, 40, 20, 20), on, off, is_on=False)
    away, over = MouseState((0, 0)), MouseState((45, 45))
    click = MouseState((45, 45), clicked=True, down=True)
    assert t.control(away) is False
    assert surf.get_at((50, 50))[:3] == CYAN
    assert t.control(click) is True  # toggled on, drawn pressed in the "on" set
    assert surf.get_at((50, 50))[:3] == BLUE
    assert t.control(over) is True
    assert surf.get_at((50, 50))[:3] == GREEN
    assert t.control(MouseState((45, 45), down=True)) is True  # still held: no second flip
    assert t.control(click) is False
    t.set_state(True)
    assert t.control(away) is True
    assert surf.get_at((50, 50))[:3] == RED


def test_toggle_button_rejects_missing_images():
    with pytest.raises(ValueError):
        ToggleButton(pygame.Surface((10, 10)), (0, 0, 5, 5), (), (solid(RED),))


def make_slider(surf=None) -> Slider:
    surf = surf or pygame.Surface((400, 100))
    return Slider(surf, (100, 46, 200, 8), 25.0, 450.0, 400.0, knob_radius=10, label="Trap")


def test_slider_starts_at_its_value_and_maps_position_linearly():
    s = make_slider()
    assert s.value == pytest.approx(400.0)
    assert s.knob_xy() == (round(100 + 200 * 375 / 425), 50)
    s.set_value(1000.0)
    assert s.value == 450.0
    s.set_value(-5.0)
    assert s.value == 25.0


def test_slider_press_jumps_drag_follows_even_off_the_bar_release_stops():
    s = make_slider()
    assert s.control(MouseState((150, 50), clicked=True, down=True)) == pytest.approx(
        25.0 + 0.25 * 425.0
    )
    assert s.sliding and s.changed
    # Held: follows the mouse although it left the hit box vertically, clamped at the end.
    assert s.control(MouseState((200, 95), down=True)) == pytest.approx(25.0 + 0.5 * 425.0)
    assert s.control(MouseState((390, 95), down=True)) == pytest.approx(450.0)
    # Released: the knob stays put whatever the mouse does.
    assert s.control(MouseState((120, 50))) == pytest.approx(450.0)
    assert not s.sliding and not s.changed


def test_slider_ignores_presses_outside_its_hit_box_and_when_disabled():
    s = make_slider()
    assert s.control(MouseState((150, 70), clicked=True, down=True)) == pytest.approx(400.0)
    assert s.control(MouseState((150, 50), down=True)) == pytest.approx(400.0)  # drag-in
    s.enabled = False
    assert s.control(MouseState((150, 50), clicked=True, down=True)) == pytest.approx(400.0)


def test_slider_draws_bar_knob_and_label():
    surf = pygame.Surface((400, 100))
    surf.fill((79, 79, 79))
    s = make_slider(surf)
    s.control(MouseState((0, 0)))
    kx, ky = s.knob_xy()
    assert surf.get_at((kx, ky))[:3] == s.knob_color
    assert surf.get_at((120, 50))[:3] == s.bar_color
    label_rows = [surf.get_at((x, y))[:3] for x in range(150, 250) for y in range(62, 90)]
    assert (255, 255, 255) in label_rows


def test_slider_needs_a_real_range():
    with pytest.raises(ValueError):
        Slider(pygame.Surface((10, 10)), (0, 0, 5, 5), 3.0, 3.0)
