"""The charts beside (or below, or over) the scene, and the chart button.

The charts themselves (`evapcool.view.panels`) know nothing of the app; this module
keeps which are shown, feeds them a record per frame the physics advanced, and draws
them into the rectangles the layout gives, each with a close button.
"""

from __future__ import annotations

import pygame

from evapcool.physics.simulation import Simulation
from evapcool.view.icons import FACE, SUPER
from evapcool.view.panels import INK, EnergyPanel, PathPanel
from evapcool.view.widgets import BLACK, LOOKS

#: The chart button, in the bottom border between the slider and the thermometer.
CHART_BUTTON_RECT = pygame.Rect(528, 600, 40, 40)
#: The close button of a chart: logical size, and its inset from the top-right corner.
CLOSE_SIZE = 26
CLOSE_INSET = 6
CHARTS = ("energy", "path")


class ChartColumn:
    """The energy and path charts; both always record, `shown` says which are drawn."""

    def __init__(self) -> None:
        self.panels = {"energy": EnergyPanel(), "path": PathPanel()}
        self.shown: list[str] = []
        #: Chart name -> pixel rectangle at the last draw (hit tests, tests).
        self.rects: dict[str, pygame.Rect] = {}
        self.close_rects: dict[str, pygame.Rect] = {}
        self._sim: Simulation | None = None
        self._time = -1.0

    @property
    def energy(self) -> EnergyPanel:
        return self.panels["energy"]

    @property
    def path(self) -> PathPanel:
        return self.panels["path"]

    @property
    def show_energy(self) -> bool:
        return "energy" in self.shown

    @property
    def show_path(self) -> bool:
        return "path" in self.shown

    def toggle(self, name: str) -> None:
        """Show or hide a chart; shown charts keep the order energy, path."""
        if name not in CHARTS:
            raise ValueError(f"chart must be one of {', '.join(CHARTS)} (got {name!r})")
        on = set(self.shown) ^ {name}
        self.shown = [c for c in CHARTS if c in on]
        self.rects = {k: v for k, v in self.rects.items() if k in on}

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

    def draw(self, surface: pygame.Surface, rects: tuple[pygame.Rect, ...], scale: float) -> None:
        """Each shown chart into its rectangle (window pixels) at this scale."""
        self.rects = dict(zip(self.shown, rects, strict=True))
        self.close_rects = {}
        for name, rect in self.rects.items():
            self.panels[name].draw(surface, rect, scale)
            self.close_rects[name] = close_button(surface, rect, scale)

    def target_at(self, pos: tuple[float, float]) -> str | None:
        """'close:<chart>' when pos (window pixels) is on a close button."""
        for name, r in self.close_rects.items():
            if r.collidepoint(pos):
                return f"close:{name}"
        return None


def close_button(surface: pygame.Surface, rect: pygame.Rect, scale: float) -> pygame.Rect:
    """A small framed cross in the chart's top-right corner; returns its rectangle."""
    size = max(12, round(CLOSE_SIZE * scale))
    inset = round(CLOSE_INSET * scale)
    r = pygame.Rect(rect.right - inset - size, rect.top + inset, size, size)
    pygame.draw.rect(surface, (225, 225, 220), r, border_radius=max(1, size // 6))
    pygame.draw.rect(surface, INK, r, max(1, round(1.5 * scale)), border_radius=max(1, size // 6))
    m = size // 4
    w = max(2, round(2.5 * scale))
    pygame.draw.line(surface, INK, (r.left + m, r.top + m), (r.right - m - 1, r.bottom - m - 1), w)
    pygame.draw.line(surface, INK, (r.left + m, r.bottom - m - 1), (r.right - m - 1, r.top + m), w)
    return r


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


_looks_cache: dict[int, tuple[pygame.Surface, ...]] = {}


def chart_button_looks(size: int = CHART_BUTTON_RECT.width) -> tuple[pygame.Surface, ...]:
    """(idle, hover, down) images of the energy-chart button at this pixel size."""
    cached = _looks_cache.get(size)
    if cached is not None:
        return cached
    images = []
    for look in LOOKS:
        s = size * SUPER
        big = pygame.Surface((s, s), pygame.SRCALPHA)
        face = pygame.Rect(0, 0, s, s).inflate(-2 * SUPER, -2 * SUPER)
        pygame.draw.rect(big, FACE[look], face, border_radius=s // 6)
        pygame.draw.rect(big, BLACK, face, width=3 * SUPER, border_radius=s // 6)
        _chart_symbol(big, look)
        images.append(pygame.transform.smoothscale(big, (size, size)))
    _looks_cache[size] = tuple(images)
    return _looks_cache[size]
