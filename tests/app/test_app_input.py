"""The input state machine: modes and interleaved events, alone and inside the applet."""

from __future__ import annotations

import ast
from pathlib import Path

import pygame
import pytest
from apphelp import click, frames, key, post

from evapcool.app import charts as charts_module
from evapcool.app import input as input_module
from evapcool.app.charts import CHART_BUTTON_RECT
from evapcool.app.input import Binding, InputMachine, Mode
from evapcool.view.scene import PAUSE_RECT, SLIDER_RECT

pytestmark = pytest.mark.usefixtures("own_folders")
SRC = Path(input_module.__file__).parent


def ev(kind: int, **attrs) -> pygame.event.Event:
    return pygame.event.Event(kind, **attrs)


def keydown(k: int, text: str = "") -> pygame.event.Event:
    return ev(pygame.KEYDOWN, key=k, mod=0, unicode=text, scancode=0)


class FakeControls:
    """Records what the machine asks; the slider sits at x 100..300, y 0..20."""

    def __init__(self) -> None:
        self.calls: list[tuple] = []
        self.height = 400.0
        self.sliding = False
        self.name_results: list[str | None] = []

    def target_at(self, pos):
        if 100 <= pos[0] <= 300 and 0 <= pos[1] <= 20:
            return "slider"
        if pos == (10, 10):
            return "pause"
        if pos == (50, 50):
            return "close:path"
        return None

    def slider_press(self, pos):
        self.sliding = True
        self.height = pos[0]
        return True

    def slider_drag(self, pos):
        assert self.sliding, "dragged while no drag was on"
        self.height = pos[0]

    def slider_release(self):
        self.sliding = False
        self.calls.append(("release",))

    def name_event(self, event):
        self.calls.append(("name", event.type))
        return self.name_results.pop(0) if self.name_results else None

    def clear(self):
        self.calls.append(("clear_table",))

    def __getattr__(self, name):
        return lambda *args, **kw: self.calls.append((name, *args))


def machine() -> tuple[InputMachine, FakeControls]:
    """A machine whose controls, scores and settings are one recording stand-in."""
    c = FakeControls()
    m = InputMachine(
        c,
        c,
        c,
        [
            Binding((pygame.K_r,), "R", "restart", lambda ctl: ctl.restart(), ends_drag=True),
            Binding((pygame.K_SPACE,), "Space", "pause", lambda ctl: ctl.toggle_pause()),
            Binding((pygame.K_h,), "H", "help", mode=Mode.HELP),
            Binding((pygame.K_t,), "T", "table", mode=Mode.TABLE),
            Binding((pygame.K_x,), "X", "clear", mode=Mode.CONFIRM_CLEAR),
            Binding((pygame.K_o,), "O", "settings", mode=Mode.SETTINGS),
            Binding((pygame.K_ESCAPE,), "Esc", "close", mode=Mode.PLAY),
        ],
    )
    return m, c


def test_the_machine_does_not_import_the_app_and_charts_do_not_either():
    for module in (input_module, charts_module):
        tree = ast.parse(Path(module.__file__).read_text(encoding="utf-8"))
        names = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
        assert "evapcool.app.applet" not in names, module.__name__
    # No module of app/ imports applet.py, except cli.py, which starts it.
    for path in SRC.glob("*.py"):
        if path.name not in ("applet.py", "cli.py"):
            assert "evapcool.app.applet" not in path.read_text(encoding="utf-8"), path.name


def test_drag_follows_motion_and_ends_on_release():
    m, c = machine()
    m.handle(ev(pygame.MOUSEBUTTONDOWN, pos=(150, 10), button=1))
    assert m.mode is Mode.DRAG and c.height == 150
    m.handle(ev(pygame.MOUSEMOTION, pos=(250, 400), rel=(0, 0), buttons=(1, 0, 0)))
    assert c.height == 250
    m.handle(ev(pygame.MOUSEBUTTONUP, pos=(260, 400), button=1))
    assert m.mode is Mode.PLAY and c.height == 260 and not c.sliding
    m.handle(ev(pygame.MOUSEMOTION, pos=(120, 10), rel=(0, 0), buttons=(0, 0, 0)))
    assert c.height == 260  # no drag any more


def test_r_during_a_drag_ends_the_drag_before_the_restart():
    m, c = machine()
    m.handle(ev(pygame.MOUSEBUTTONDOWN, pos=(150, 10), button=1))
    m.handle(keydown(pygame.K_r))
    assert c.calls[:2] == [("release",), ("restart",)]
    assert m.mode is Mode.PLAY
    # The mouse, still held, moves on: it no longer moves the trap.
    m.handle(ev(pygame.MOUSEMOTION, pos=(280, 10), rel=(0, 0), buttons=(1, 0, 0)))
    assert c.height == 150


def test_space_during_a_drag_keeps_the_drag():
    m, c = machine()
    m.handle(ev(pygame.MOUSEBUTTONDOWN, pos=(150, 10), button=1))
    m.handle(keydown(pygame.K_SPACE))
    assert m.mode is Mode.DRAG and ("toggle_pause",) in c.calls
    m.handle(ev(pygame.MOUSEMOTION, pos=(200, 10), rel=(0, 0), buttons=(1, 0, 0)))
    assert c.height == 200


def test_a_press_while_dragging_ends_the_drag_and_counts():
    """A release lost (outside the window, a touch screen): the next press still works."""
    m, c = machine()
    m.handle(ev(pygame.MOUSEBUTTONDOWN, pos=(150, 10), button=1))
    m.handle(ev(pygame.MOUSEBUTTONDOWN, pos=(50, 50), button=1))  # on a chart's close box
    assert ("release",) in c.calls and ("toggle_chart", "path") in c.calls
    assert m.mode is Mode.PLAY


def test_losing_focus_ends_a_drag():
    m, c = machine()
    m.handle(ev(pygame.MOUSEBUTTONDOWN, pos=(150, 10), button=1))
    m.handle(ev(pygame.WINDOWFOCUSLOST))
    assert m.mode is Mode.PLAY and not c.sliding


@pytest.mark.parametrize("k, mode", [(pygame.K_h, Mode.HELP), (pygame.K_o, Mode.SETTINGS)])
def test_opening_an_overlay_during_a_drag_ends_it(k, mode):
    m, c = machine()
    m.handle(ev(pygame.MOUSEBUTTONDOWN, pos=(150, 10), button=1))
    m.handle(keydown(k))
    assert m.mode is mode and not c.sliding


def test_a_drag_started_under_the_help_returns_to_it():
    m, _ = machine()
    m.handle(keydown(pygame.K_h))
    m.handle(ev(pygame.MOUSEBUTTONDOWN, pos=(150, 10), button=1))
    assert m.mode is Mode.DRAG and m.overlay == "help"
    m.handle(ev(pygame.MOUSEBUTTONUP, pos=(150, 10), button=1))
    assert m.mode is Mode.HELP


def test_modal_modes_take_every_key_and_ignore_the_mouse():
    m, c = machine()
    m.handle(keydown(pygame.K_x))
    assert m.mode is Mode.CONFIRM_CLEAR
    for k in (pygame.K_r, pygame.K_SPACE, pygame.K_h):
        m.handle(keydown(k))
    m.handle(ev(pygame.MOUSEBUTTONDOWN, pos=(10, 10), button=1))
    assert m.mode is Mode.CONFIRM_CLEAR and c.calls == []
    m.handle(keydown(pygame.K_y))
    assert m.mode is Mode.TABLE and c.calls == [("clear_table",)]


def test_name_entry_gets_keys_and_text_and_ends_on_submit():
    m, c = machine()
    m.ask_name()
    c.name_results = [None, None, None, "submit"]
    m.handle(keydown(pygame.K_r, "r"))
    m.handle(ev(pygame.TEXTINPUT, text="r"))
    m.handle(keydown(pygame.K_SPACE, " "))
    assert ("restart",) not in c.calls and ("toggle_pause",) not in c.calls
    m.handle(keydown(pygame.K_RETURN))
    assert m.mode is Mode.TABLE
    m.handle(ev(pygame.TEXTINPUT, text="q"))  # typed text outside the box: unused
    assert [x for x in c.calls if x[0] == "name"][-1] == ("name", pygame.KEYDOWN)


def test_esc_closes_what_is_open_then_leaves():
    m, c = machine()
    m.handle(keydown(pygame.K_t))
    m.handle(keydown(pygame.K_ESCAPE))
    assert m.mode is Mode.PLAY and ("leave",) not in c.calls
    m.handle(keydown(pygame.K_ESCAPE))
    assert ("leave",) in c.calls


# -- inside the applet: real events, real widgets ------------------------------------------------


def _press_slider(app, x):
    post(pygame.MOUSEBUTTONDOWN, pos=(x, SLIDER_RECT.centery), button=1)
    frames(app)


def test_r_during_a_slider_drag_does_not_carry_the_drag_into_the_new_game(app):
    _press_slider(app, SLIDER_RECT.left + 68)
    assert app.game.trap_height == pytest.approx(25 + 0.25 * 425)
    key(app, pygame.K_r)
    assert app.game.trap_height == 400.0 and not app.slider.sliding
    # The button is still held and the mouse moves: the new game's trap stays put.
    post(pygame.MOUSEMOTION, pos=(SLIDER_RECT.left, 300), rel=(0, 0), buttons=(1, 0, 0))
    frames(app, 2)
    assert app.game.trap_height == 400.0 and app.slider.value == 400.0
    post(pygame.MOUSEBUTTONUP, pos=(SLIDER_RECT.left, 300), button=1)
    frames(app)
    assert app.game.trap_height == 400.0


def test_chart_clicks_during_a_drag_are_not_lost(app):
    _press_slider(app, SLIDER_RECT.left + 136)
    # The release is lost (it happened outside the window); the next press is the chart's.
    post(pygame.MOUSEBUTTONDOWN, pos=CHART_BUTTON_RECT.center, button=1)
    post(pygame.MOUSEBUTTONUP, pos=CHART_BUTTON_RECT.center, button=1)
    frames(app)
    assert app.charts.show_energy and not app.slider.sliding
    assert app.game.trap_height == pytest.approx(25 + 0.5 * 425)  # not dragged to the button
    # The chart's close box, in the same frame as a drag's press, motion and release.
    frames(app)
    close = app.charts.close_rects["energy"]
    _press_slider(app, SLIDER_RECT.left)
    post(pygame.MOUSEMOTION, pos=(SLIDER_RECT.left + 68, 300), rel=(0, 0), buttons=(1, 0, 0))
    post(pygame.MOUSEBUTTONUP, pos=(SLIDER_RECT.left + 68, 300), button=1)
    post(pygame.MOUSEBUTTONDOWN, pos=close.center, button=1)
    post(pygame.MOUSEBUTTONUP, pos=close.center, button=1)
    frames(app)
    assert not app.charts.show_energy
    assert app.game.trap_height == pytest.approx(25 + 0.25 * 425)


def test_keys_typed_into_the_name_do_nothing_else(app):
    app.game.paused = False
    frames(app, 2)
    app.game.sim.force_win()
    frames(app)
    assert app.input.mode is Mode.NAME
    sim, speed = app.game.sim, app.game.speed
    for k, text in ((pygame.K_r, "r"), (pygame.K_e, "e"), (pygame.K_PLUS, "+"), (pygame.K_h, "h")):
        key(app, k, text=text)
    click(app, PAUSE_RECT.center)  # the mouse does not reach the game either
    assert app.game.sim is sim and app.game.speed == speed and not app.charts.show_energy
    assert app.overlay is None and app.scores.name_box.text == "re+h"


def test_a_win_during_a_drag_ends_the_drag_and_opens_the_name_box(app):
    app.game.paused = False
    _press_slider(app, SLIDER_RECT.left + 200)
    app.game.sim.force_win()
    frames(app)
    assert app.input.mode is Mode.NAME and not app.slider.sliding
    post(pygame.MOUSEMOTION, pos=(SLIDER_RECT.left, 300), rel=(0, 0), buttons=(1, 0, 0))
    frames(app)
    assert app.game.trap_height == pytest.approx(25 + 200 / 272 * 425)
