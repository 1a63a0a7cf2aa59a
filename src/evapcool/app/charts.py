"""The side column beside the scene: the energy and path charts, and the chart button.

The charts themselves (`evapcool.view.panels`) know nothing of the app; this
module stacks the visible ones in one column that `App.add_panel` puts to the
right of the scene, and feeds them a record per frame the physics advanced.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pygame

from evapcool.view.icons import FACE, SUPER
from evapcool.view.panels import EnergyPanel, PathPanel
from evapcool.view.widgets import BLACK, LOOKS

if TYPE_CHECKING:
    from evapcool.app.applet import App
    from evapcool.physics.simulation import Simulation

#: Width of the chart column, logical px (the height is the scene's, 672).
COLUMN_WIDTH = 520
#: The chart button, in the bottom border between the slider and the thermometer.
CHART_BUTTON_RECT = pygame.Rect(528, 600, 40, 40)


class ChartColumn:
    """Energy and path charts stacked in one side panel (App.Panel protocol).

    Both charts always record (so opening one shows a filled history at once);
    `show_energy` / `show_path` only decide what is drawn.
    """

    width = COLUMN_WIDTH

    def __init__(self) -> None:
        self.energy = EnergyPanel()
        self.path = PathPanel()
        self.show_energy = False
        self.show_path = False
        #: Chart rectangles (column pixels) at the last draw, for tests and clicks.
        self.rects: dict[str, pygame.Rect] = {}
        self._sim: Simulation | None = None
        self._time = -1.0

    @property
    def visible(self) -> bool:
        return self.show_energy or self.show_path

    def reset(self) -> None:
        """Forget both histories (a restart)."""
        self.energy.reset()
        self.path.reset()
        self._sim, self._time = None, -1.0

    def observe(self, sim: Simulation) -> bool:
        """Record the frame if the physics moved (or the simulation is new); True if recorded.

        A new simulation is recorded once at its start, so the charts show where the
        path begins; after that only frames that advanced time count (not pauses).
        """
        if sim is self._sim and sim.time == self._time:
            return False
        self._sim, self._time = sim, sim.time
        self.energy.record(sim)
        self.path.record(sim)
        return True

    def layout(self, height: int) -> dict[str, pygame.Rect]:
        shown = [
            name for name, on in (("energy", self.show_energy), ("path", self.show_path)) if on
        ]
        if not shown:
            return {}
        h = height // len(shown)
        return {name: pygame.Rect(0, k * h, self.width, h) for k, name in enumerate(shown)}

    def draw(self, surface: pygame.Surface, app: App) -> None:
        self.rects = self.layout(surface.get_height())
        if "energy" in self.rects:
            self.energy.draw(surface, self.rects["energy"])
        if "path" in self.rects:
            self.path.draw(surface, self.rects["path"])

    def handle_event(self, event: pygame.event.Event, pos: tuple[float, float] | None) -> bool:
        return False  # the charts only show


def _chart_symbol(big: pygame.Surface, look: str) -> None:
    """Four bars of a histogram and a red cut line: 'show the energies'."""
    s = big.get_width()
    shift = 2 * SUPER if look == "down" else 0
    base = 0.76 * s + shift
    w = 0.11 * s
    for k, frac in enumerate((0.25, 0.48, 0.36, 0.16)):
        x = 0.2 * s + k * (w + 0.03 * s) + shift
        pygame.draw.rect(
            big, BLACK, pygame.Rect(round(x), round(base - frac * s), round(w), round(frac * s))
        )
    x_cut = round(0.72 * s + shift)
    pygame.draw.line(big, (200, 20, 20), (x_cut, 0.2 * s + shift), (x_cut, base), 3 * SUPER)


def chart_button_looks(size: int = CHART_BUTTON_RECT.width) -> tuple[pygame.Surface, ...]:
    """(idle, hover, down) images of the energy-chart button, drawn in code."""
    images = []
    for look in LOOKS:
        s = size * SUPER
        big = pygame.Surface((s, s), pygame.SRCALPHA)
        face = pygame.Rect(0, 0, s, s).inflate(-2 * SUPER, -2 * SUPER)
        pygame.draw.rect(big, FACE[look], face, border_radius=s // 6)
        pygame.draw.rect(big, BLACK, face, width=3 * SUPER, border_radius=s // 6)
        _chart_symbol(big, look)
        images.append(pygame.transform.smoothscale(big, (size, size)))
    return tuple(images)
