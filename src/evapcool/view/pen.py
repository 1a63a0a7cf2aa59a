"""Drawing in logical pixels at any scale, straight onto the target surface.

The scene is laid out in the original's 640 x 672 logical pixels. A `Pen` maps those to
the window's pixels (scale, then offset) and draws every line, disk and letter at the
size it will be seen, so a scene scaled to a projector stays crisp: nothing is drawn
small and blown up. At scale 1 and offset 0 it draws exactly what plain pygame would.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from contextlib import contextmanager

import pygame

from evapcool.view.fonts import text_image

Color = tuple[int, ...]
Point = tuple[float, float]
RectLike = pygame.Rect | Sequence[float]


class Pen:
    """Draws logical shapes on `surface`: pixel = origin + scale x logical."""

    def __init__(
        self, surface: pygame.Surface, scale: float = 1.0, origin: tuple[int, int] = (0, 0)
    ) -> None:
        if not (math.isfinite(scale) and scale > 0):
            raise ValueError(f"scale must be a positive number (got {scale!r})")
        self.surface = surface
        self.scale = float(scale)
        self.origin = (int(origin[0]), int(origin[1]))

    # -- coordinates ------------------------------------------------------------------
    def xy(self, p: Point) -> tuple[float, float]:
        """A logical point in surface pixels (not rounded)."""
        return (self.origin[0] + p[0] * self.scale, self.origin[1] + p[1] * self.scale)

    def ixy(self, p: Point) -> tuple[int, int]:
        x, y = self.xy(p)
        return (round(x), round(y))

    def rect(self, r: RectLike) -> pygame.Rect:
        """A logical rectangle in pixels; neighbours share edges (both ends rounded)."""
        x, y, w, h = (r.x, r.y, r.w, r.h) if isinstance(r, pygame.Rect) else r
        x0, y0 = self.ixy((x, y))
        x1, y1 = self.ixy((x + w, y + h))
        return pygame.Rect(x0, y0, x1 - x0, y1 - y0)

    def size(self, v: float) -> int:
        """A logical length (line width, radius) in whole pixels, at least 1."""
        return max(1, round(v * self.scale))

    def to_logical(self, p: Point) -> tuple[float, float]:
        return ((p[0] - self.origin[0]) / self.scale, (p[1] - self.origin[1]) / self.scale)

    # -- shapes -------------------------------------------------------------------------
    def fill(self, color: Color, r: RectLike | None = None) -> None:
        self.surface.fill(color, None if r is None else self.rect(r))

    def box(
        self, color: Color, r: RectLike, width: float = 0, border_radius: float = 0
    ) -> pygame.Rect:
        """pygame.draw.rect in logical units (width 0 fills)."""
        w = self.size(width) if width else 0
        radius = round(border_radius * self.scale) if border_radius else 0
        return pygame.draw.rect(self.surface, color, self.rect(r), w, border_radius=radius)

    def line(self, color: Color, a: Point, b: Point, width: float = 1) -> None:
        pygame.draw.line(self.surface, color, self.ixy(a), self.ixy(b), self.size(width))

    def lines(self, color: Color, closed: bool, points: Sequence[Point], width: float = 1):
        pygame.draw.lines(
            self.surface, color, closed, [self.xy(p) for p in points], self.size(width)
        )

    def aalines(self, color: Color, closed: bool, points: Sequence[Point]) -> None:
        pygame.draw.aalines(self.surface, color, closed, [self.xy(p) for p in points])

    def polygon(self, color: Color, points: Sequence[Point]) -> None:
        pygame.draw.polygon(self.surface, color, [self.xy(p) for p in points])

    def circle(self, color: Color, center: Point, radius: float, width: float = 0) -> None:
        w = self.size(width) if width else 0
        pygame.draw.circle(self.surface, color, self.ixy(center), self.size(radius), w)

    # -- text and images -----------------------------------------------------------------
    def text_image(
        self, text: str, size: float, color: Color, bold: bool = False
    ) -> pygame.Surface:
        """Text rendered at `size` logical pixels, i.e. size x scale real ones."""
        return text_image(text, max(1, round(size * self.scale)), tuple(color[:3]), bold)

    def text(
        self, text: str, size: float, color: Color, bold: bool = False, **anchor: Point
    ) -> pygame.Rect:
        """Draw text with one anchor in logical units (topleft=..., center=...); its pixels."""
        image = self.text_image(text, size, color, bold)
        (name, point), *_ = anchor.items() or [("topleft", (0.0, 0.0))]
        where = image.get_rect(**{name: self.ixy(point)})
        self.surface.blit(image, where)
        return where

    def blit(self, image: pygame.Surface, r: RectLike, anchor: str = "center") -> pygame.Rect:
        """An image already drawn at this scale, placed at the anchor of a logical rect."""
        where = image.get_rect(**{anchor: getattr(self.rect(r), anchor)})
        self.surface.blit(image, where)
        return where

    @contextmanager
    def clip(self, r: RectLike | None) -> Iterator[None]:
        """Drawing inside the block stays in the logical rect (and any clip already set)."""
        old = self.surface.get_clip()
        self.surface.set_clip(None if r is None else self.rect(r).clip(old))
        try:
            yield
        finally:
            self.surface.set_clip(old)
