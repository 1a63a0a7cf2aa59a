"""The scene's own controls: play/pause, restart, the trap slider and the chart button."""

from __future__ import annotations

from collections.abc import Callable

from evapcool.app.charts import CHART_BUTTON_RECT, chart_button_looks
from evapcool.app.words import t
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN, HEIGHT_START, Game
from evapcool.view.icons import button_looks
from evapcool.view.pen import Pen
from evapcool.view.scene import KNOB_RADIUS, PAUSE_RECT, RESTART_RECT, SLIDER_RECT
from evapcool.view.widgets import Button, Pointer, Slider, ToggleButton


class SceneControls:
    """The widgets in the bottom border, at the original's places (logical pixels)."""

    def __init__(self, trap_height: Callable[[], float] | None = None) -> None:
        """trap_height: the game's height asked for, where the knob rests between drags."""
        self.pause = ToggleButton(
            PAUSE_RECT,
            lambda size: button_looks("play", size),
            lambda size: button_looks("pause", size),
            is_on=True,
        )
        self.restart = Button(RESTART_RECT, lambda size: button_looks("restart", size))
        self.chart = Button(CHART_BUTTON_RECT, chart_button_looks)
        self.slider = Slider(
            SLIDER_RECT,
            HEIGHT_MIN,
            HEIGHT_MAX,
            HEIGHT_START,
            knob_radius=KNOB_RADIUS,
            label=t("controls.trap_height"),
            follow=trap_height,
        )

    def target_at(self, xy: tuple[float, float]) -> str | None:
        """'slider', 'pause', 'restart' or 'chart' under a logical point, or None."""
        for name, widget in (
            ("slider", self.slider),
            ("pause", self.pause),
            ("restart", self.restart),
            ("chart", self.chart),
        ):
            if widget.hit(xy):
                return name
        return None

    def draw(self, pen: Pen, pointer: Pointer, game: Game) -> None:
        """Draw them showing the game's state (paused, trap height, frozen after a win)."""
        self.pause.set_state(game.paused)
        self.slider.enabled = not game.won
        self.slider.label = t("controls.trap_height")  # the language may change meanwhile
        for widget in (self.pause, self.restart, self.slider, self.chart):
            widget.draw(pen, pointer)
