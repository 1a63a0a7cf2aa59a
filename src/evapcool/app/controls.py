"""The scene's own controls: play/pause, restart, the trap slider and the chart button."""

from __future__ import annotations

from collections.abc import Callable, Collection

from evapcool.app.charts import CHART_BUTTON_RECT, chart_button_looks
from evapcool.app.words import t
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN, HEIGHT_START, Game
from evapcool.view.icons import button_looks, save_button_looks
from evapcool.view.pen import Pen
from evapcool.view.scene import KNOB_RADIUS, PAUSE_RECT, RESTART_RECT, SAVE_RUN_RECT, SLIDER_RECT
from evapcool.view.theme import Theme
from evapcool.view.widgets import Button, Pointer, Slider, ToggleButton


class SceneControls:
    """The widgets in the bottom border, at the original's places (logical pixels)."""

    def __init__(
        self,
        trap_height: Callable[[], float] | None = None,
        hide: Collection[str] = (),
        locked: Collection[str] = (),
    ) -> None:
        """trap_height: the game's height asked for, where the knob rests between drags.
        hide: buttons a setup's link leaves out ('pause', 'restart', 'chart'); locked: 'trap' greys
        the slider (shown, not changeable)."""
        self.hidden = frozenset(hide)
        self.locked = frozenset(locked)
        self.save = Button(SAVE_RUN_RECT, save_button_looks)
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
        for name, widget in self._shown():
            if widget.hit(xy):
                return name
        return None

    def _shown(self) -> list[tuple[str, Button | Slider]]:
        widgets: list[tuple[str, Button | Slider]] = [
            ("slider", self.slider),
            ("save", self.save),
        ]
        if "pause" not in self.hidden:
            widgets.append(("pause", self.pause))
        if "restart" not in self.hidden:
            widgets.append(("restart", self.restart))
        if "chart" not in self.hidden:
            widgets.append(("chart", self.chart))
        return widgets

    def theme(self, theme: Theme) -> None:
        """The slider's colours for the scene's theme (its label is on the border)."""
        self.slider.text_color = theme.text
        self.slider.bar_color = theme.slider_bar
        self.slider.outline_color = theme.slider_outline

    def draw(self, pen: Pen, pointer: Pointer, game: Game) -> None:
        """Draw them showing the game's state (paused, trap height, frozen after a win)."""
        self.pause.set_state(game.paused)
        self.slider.enabled = not game.won and "trap" not in self.locked
        self.slider.label = t("controls.trap_height")  # the language may change meanwhile
        for _, widget in self._shown():
            widget.draw(pen, pointer)
