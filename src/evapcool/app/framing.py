"""The window and what shares it with the scene: the charts, the layout, full screen.

`Framing` sizes the window for the scene (at the scale the player chose by resizing it)
and the charts shown, and says where each goes (`layout`).
"""

from __future__ import annotations

import pygame

from evapcool.app.charts import ChartColumn
from evapcool.app.layout import Layout, arrange, window_size_for
from evapcool.app.window import Window


class Framing:
    """The window, the chart column, and the scene's preferred scale."""

    def __init__(self, window: Window) -> None:
        self.window = window
        self.charts = ChartColumn()
        #: The scene's scale the player wants (1, or what they resized the window to).
        self.preferred_scale = min(1.0, arrange(window.usable(), 0).scale)
        self.fit()

    @property
    def layout(self) -> Layout:
        return arrange(self.window.size, len(self.charts.shown))

    def fit(self) -> None:
        """Size the window for the scene (and charts) at the preferred scale, on screen."""
        size, _ = window_size_for(
            self.preferred_scale, len(self.charts.shown), self.window.usable()
        )
        self.window.resize(size)

    def event(self, event: pygame.event.Event) -> None:
        """A resize by the user: their scale from now on."""
        if event.type == pygame.WINDOWRESIZED and not self.window.fullscreen:
            size = (event.x, event.y)
            if size != self.window.requested:
                self.preferred_scale = arrange(size, len(self.charts.shown)).scale

    def toggle_fullscreen(self) -> None:
        self.window.toggle_fullscreen()
        if not self.window.fullscreen:
            self.fit()  # charts may have come or gone meanwhile

    def toggle_chart(self, name: str) -> None:
        self.charts.toggle(name)
        self.fit()
