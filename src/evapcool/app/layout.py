"""Where the scene and the charts go in a window, and how big a window to ask for.

Pure geometry, no pygame display: `arrange(window, charts)` picks the arrangement that
shows the whole scene largest, charts beside it or below it, and returns the pixel
rectangles; nothing is ever cut off, the scene is scaled down instead. Below keeps
the scene at 2/3 or more of the size it has alone in any window (672 / 1008), so the
charts never need to cover it. `window_size_for` is the window to ask for so the scene
keeps a chosen scale where the screen has room.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pygame

SCENE = (640, 672)
#: The chart column beside the scene, and the chart row below it (logical px).
COLUMN_WIDTH = 520
ROW_HEIGHT = 336
ARRANGEMENTS = ("beside", "below")


def canvas(arrangement: str, n_charts: int) -> tuple[int, int]:
    """Logical size of scene plus charts in an arrangement."""
    if n_charts == 0 or arrangement == "alone":
        return SCENE
    if arrangement == "beside":
        return (SCENE[0] + COLUMN_WIDTH, SCENE[1])
    return (SCENE[0], SCENE[1] + ROW_HEIGHT)


def fit(window: tuple[int, int], size: tuple[int, int]) -> float:
    """The largest scale at which size fits in window."""
    return min(window[0] / size[0], window[1] / size[1])


@dataclass(frozen=True)
class Layout:
    """Pixel rectangles of the scene and of each chart, and the scale they are drawn at."""

    arrangement: str  # "alone", "beside" or "below"
    scale: float
    scene: pygame.Rect
    charts: tuple[pygame.Rect, ...]

    def to_scene(self, pos: tuple[float, float]) -> tuple[float, float]:
        """Window pixels to scene (logical) pixels."""
        return ((pos[0] - self.scene.x) / self.scale, (pos[1] - self.scene.y) / self.scale)

    def chart_at(self, pos: tuple[float, float]) -> int | None:
        """Index of the chart under a window pixel, or None."""
        for k, r in enumerate(self.charts):
            if r.collidepoint(pos):
                return k
        return None


def _split(area: pygame.Rect, n: int, vertical: bool) -> tuple[pygame.Rect, ...]:
    """n equal parts of area, stacked (vertical) or side by side; edges shared exactly."""
    out = []
    for k in range(n):
        if vertical:
            y0 = area.y + area.h * k // n
            y1 = area.y + area.h * (k + 1) // n
            out.append(pygame.Rect(area.x, y0, area.w, y1 - y0))
        else:
            x0 = area.x + area.w * k // n
            x1 = area.x + area.w * (k + 1) // n
            out.append(pygame.Rect(x0, area.y, x1 - x0, area.h))
    return tuple(out)


def best_arrangement(window: tuple[int, int], n_charts: int) -> str:
    """Beside or below, whichever shows the scene larger (beside on a tie)."""
    if n_charts == 0:
        return "alone"
    return max(ARRANGEMENTS, key=lambda a: fit(window, canvas(a, n_charts)))


def arrange(window: tuple[int, int], n_charts: int, arrangement: str | None = None) -> Layout:
    """Scene and charts in a window of this size, centred, aspect kept, nothing cut off."""
    name = arrangement or best_arrangement(window, n_charts)
    size = canvas(name, n_charts)
    s = fit(window, size)
    w, h = max(1, math.floor(size[0] * s)), max(1, math.floor(size[1] * s))
    x0, y0 = (window[0] - w) // 2, (window[1] - h) // 2
    scene_w, scene_h = round(SCENE[0] * s), round(SCENE[1] * s)
    scene = pygame.Rect(x0, y0, min(w, scene_w), min(h, scene_h))
    if name == "beside":
        charts = _split(pygame.Rect(scene.right, y0, x0 + w - scene.right, h), n_charts, True)
    elif name == "below":
        charts = _split(pygame.Rect(x0, scene.bottom, w, y0 + h - scene.bottom), n_charts, False)
    else:
        charts = ()
    return Layout(name, s, scene, charts)


def window_size_for(
    scale: float, n_charts: int, usable: tuple[int, int]
) -> tuple[tuple[int, int], str]:
    """The window that shows scene and charts at `scale`, or as large as fits `usable`.

    Returns (size, arrangement). Beside is preferred when it fits; otherwise the
    arrangement that keeps the scene largest on this screen.
    """
    if n_charts == 0:
        s = min(scale, fit(usable, SCENE))
        return (round(SCENE[0] * s), round(SCENE[1] * s)), "alone"
    best: tuple[float, str] | None = None
    for name in ARRANGEMENTS:
        s = min(scale, fit(usable, canvas(name, n_charts)))
        if best is None or s > best[0] + 1e-9:
            best = (s, name)
    s, name = best
    w, h = canvas(name, n_charts)
    return (round(w * s), round(h * s)), name
