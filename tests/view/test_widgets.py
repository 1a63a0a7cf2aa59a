"""The reusable widgets: geometry, state and looks, drawn through a Pen at any scale."""

from __future__ import annotations

import ast
import inspect

import pygame
import pytest

from evapcool.view import widgets
from evapcool.view.pen import Pen
from evapcool.view.widgets import Button, Pointer, Slider, ToggleButton

RED, GREEN, BLUE = (255, 0, 0), (0, 255, 0), (0, 0, 255)
CYAN, MAGENTA, YELLOWISH = (0, 255, 255), (255, 0, 255), (255, 255, 0)


@pytest.fixture(autouse=True)
def _pygame():
    pygame.font.init()
    yield


def solid(*colors):
    """Looks: one square image per colour, of the size asked for."""

    def looks(size: int) -> list[pygame.Surface]:
        images = []
        for color in colors:
            s = pygame.Surface((size, size))
            s.fill(color)
            images.append(s)
        return images

    return looks


def test_widgets_import_nothing_from_the_game():
    tree = ast.parse(inspect.getsource(widgets))
    names = [a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names]
    names += [n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.module]
    assert [n for n in names if n.startswith("evapcool")] == ["evapcool.view.pen"]


def test_button_hit_box_is_its_rectangle():
    b = Button((10, 10, 30, 30))
    assert b.hit((10, 10)) and b.hit((39, 39))
    assert not b.hit((40, 20)) and not b.hit(None)


def test_button_looks_follow_the_pointer():
    b = Button((0, 0, 10, 10))
    assert b.look(Pointer((30, 30))) == "idle"
    assert b.look(Pointer((5, 5))) == "hover"
    assert b.look(Pointer((5, 5), down=True)) == "down"
    assert b.look(Pointer((30, 30), down=True)) == "idle"
    assert b.look(Pointer()) == "idle"


def test_plain_button_draws_black():
    surf = pygame.Surface((100, 100))
    surf.fill(RED)
    Button((10, 10, 30, 30)).draw(Pen(surf))
    assert surf.get_at((25, 25))[:3] == (0, 0, 0)
    assert surf.get_at((45, 45))[:3] == RED


def test_button_draws_the_image_of_its_look_at_the_pen_scale():
    surf = pygame.Surface((200, 200))
    b = Button((40, 40, 20, 20), solid(RED, GREEN, BLUE))
    for pointer, colour in ((Pointer((0, 0)), RED), ((Pointer((45, 45))), GREEN)):
        b.draw(Pen(surf), pointer)
        assert surf.get_at((50, 50))[:3] == colour
    surf.fill((0, 0, 0))
    b.draw(Pen(surf, 2.0), Pointer((45, 45), down=True))  # 40 px at (80, 80)
    assert surf.get_at((81, 81))[:3] == BLUE and surf.get_at((118, 118))[:3] == BLUE
    assert surf.get_at((79, 79))[:3] == (0, 0, 0) and surf.get_at((121, 121))[:3] == (0, 0, 0)


def test_missing_looks_fall_back_to_the_one_before():
    surf = pygame.Surface((100, 100))
    b = Button((40, 40, 20, 20), solid(CYAN))
    b.draw(Pen(surf), Pointer((45, 45), down=True))
    assert surf.get_at((50, 50))[:3] == CYAN


def test_toggle_button_flips_and_draws_its_state():
    surf = pygame.Surface((100, 100))
    t = ToggleButton((0, 0, 20, 20), solid(GREEN), solid(RED))
    assert not t.is_on
    t.draw(Pen(surf))
    assert surf.get_at((10, 10))[:3] == RED
    assert t.toggle() is True
    t.draw(Pen(surf))
    assert surf.get_at((10, 10))[:3] == GREEN
    t.set_state(False)
    assert not t.is_on


def test_slider_maps_position_linearly_and_clamps():
    s = Slider((100, 50, 200, 8), 25.0, 450.0, 400.0)
    assert s.value == pytest.approx(400.0)
    assert s.value_at(100) == 25.0 and s.value_at(300) == 450.0
    assert s.value_at(200) == pytest.approx(237.5)
    assert s.value_at(-50) == 25.0 and s.value_at(1000) == 450.0
    s.set_value(1e9)
    assert s.value == 450.0


def test_slider_press_starts_a_drag_that_follows_until_release():
    s = Slider((100, 50, 200, 8), 0.0, 1.0, 0.5, knob_radius=10)
    assert not s.press((100, 80))  # below the hit box
    assert s.press((150, 54)) and s.sliding and s.value == pytest.approx(0.25)
    s.drag((250, 300))  # off the bar: still follows
    assert s.value == pytest.approx(0.75)
    s.release()
    s.drag((100, 54))
    assert s.value == pytest.approx(0.75) and not s.sliding


def test_disabled_slider_ignores_presses():
    s = Slider((100, 50, 200, 8), 0.0, 1.0, 0.5)
    s.enabled = False
    assert not s.press((150, 54)) and s.value == 0.5


def test_slider_draws_bar_knob_and_label_at_scale():
    for scale in (1.0, 2.0):
        surf = pygame.Surface((round(400 * scale), round(120 * scale)))
        surf.fill((79, 79, 79))
        s = Slider((100, 50, 200, 8), 0.0, 1.0, 0.5, label="Trap height")
        s.draw(Pen(surf, scale))
        kx, ky = round(200 * scale), round(54 * scale)
        assert surf.get_at((kx, ky))[:3] == widgets.YELLOW  # knob at the middle
        assert surf.get_at((round(120 * scale), ky))[:3] == widgets.WHITE  # the bar
        lit = [
            surf.get_at((x, y))[0] > 200
            for x in range(surf.get_width())
            for y in range(round(75 * scale), surf.get_height())
        ]
        assert sum(lit) > 40 * scale * scale  # the label, drawn at its size


def test_slider_needs_a_real_range():
    with pytest.raises(ValueError):
        Slider((0, 0, 10, 4), 1.0, 1.0)


def test_slider_follows_the_model_between_drags_and_owns_its_drag():
    """The knob rests at the model's value, read when drawn; a drag holds it (issue 26.2)."""
    model = {"height": 400.0}
    s = Slider((100, 50, 200, 8), 0.0, 400.0, knob_radius=10, follow=lambda: model["height"])
    assert s.value == 400.0 and s.knob_xy() == (300.0, 54)
    model["height"] = 100.0  # a key or the autopilot moves the rim: nobody tells the slider
    assert s.value == 100.0 and s.knob_xy() == (150.0, 54)
    assert s.press((250, 54)) and s.value == 300.0
    model["height"] = 50.0  # while dragged, the knob is the pointer's, not the model's
    s.drag((200, 54))
    assert s.value == 200.0
    surf = pygame.Surface((400, 120))
    s.draw(Pen(surf))
    assert model["height"] == 50.0  # drawing writes nothing back
    s.release()
    assert s.value == 50.0
