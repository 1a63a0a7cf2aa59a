"""Button icons and the window icon, drawn in code (no image files).

Shapes are drawn at SUPER times the size and smoothed down, which gives
anti-aliased edges with plain pygame.draw calls.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import lru_cache

import pygame

from evapcool.view.widgets import BLACK, LOOKS, YELLOW

SUPER = 4

#: Button face per look: idle yellow, lighter under the mouse, darker when pressed.
FACE = {"idle": YELLOW, "hover": (255, 236, 120), "down": (222, 180, 20)}

Painter = Callable[[pygame.Surface, float, tuple[float, float]], None]


def _smooth(big: pygame.Surface, size: int) -> pygame.Surface:
    return pygame.transform.smoothscale(big, (size, size))


def _face(big: pygame.Surface, look: str) -> None:
    s = big.get_width()
    rect = pygame.Rect(0, 0, s, s).inflate(-2 * SUPER, -2 * SUPER)
    radius = s // 6
    pygame.draw.rect(big, FACE[look], rect, border_radius=radius)
    pygame.draw.rect(big, BLACK, rect, width=3 * SUPER, border_radius=radius)
    if look == "down":  # a pressed button: inner shadow along the top and left
        inner = rect.inflate(-6 * SUPER, -6 * SUPER)
        pygame.draw.line(big, (150, 120, 10), inner.topleft, inner.topright, 2 * SUPER)
        pygame.draw.line(big, (150, 120, 10), inner.topleft, inner.bottomleft, 2 * SUPER)


def _play(big: pygame.Surface, s: float, c: tuple[float, float]) -> None:
    cx, cy = c
    h = 0.40 * s
    left = cx - 0.33 * h
    pts = [(left, cy - h / 2), (left, cy + h / 2), (cx + 0.55 * h, cy)]
    pygame.draw.polygon(big, BLACK, pts)


def _pause(big: pygame.Surface, s: float, c: tuple[float, float]) -> None:
    cx, cy = c
    w, h, gap = 0.12 * s, 0.40 * s, 0.08 * s
    for x0 in (cx - gap / 2 - w, cx + gap / 2):
        pygame.draw.rect(big, BLACK, pygame.Rect(round(x0), round(cy - h / 2), round(w), round(h)))


def _restart(big: pygame.Surface, s: float, c: tuple[float, float]) -> None:
    """A clockwise circular arrow; the gap at the upper left, the head pointing up-right."""
    cx, cy = c
    r_out, r_in = 0.24 * s, 0.15 * s
    a0, a1 = math.radians(-200), math.radians(95)  # angles counterclockwise, y up

    def at(r: float, a: float) -> tuple[float, float]:
        return cx + r * math.cos(a), cy - r * math.sin(a)

    steps = 48
    angles = [a0 + (a1 - a0) * k / steps for k in range(steps + 1)]
    ring = [at(r_out, a) for a in angles] + [at(r_in, a) for a in reversed(angles)]
    pygame.draw.polygon(big, BLACK, ring)
    # Arrow head at the a0 end, pointing along the clockwise direction.
    r_mid, w = (r_out + r_in) / 2, 0.13 * s
    tip = at(r_mid, a0 - 0.6)
    base_l, base_r = at(r_mid + w, a0 + 0.05), at(r_mid - w, a0 + 0.05)
    pygame.draw.polygon(big, BLACK, [base_l, tip, base_r])


def _save(big: pygame.Surface, s: float, c: tuple[float, float]) -> None:
    """An arrow down into a tray: the run saved to a file."""
    cx, cy = c
    w = 0.09 * s
    pygame.draw.rect(
        big, BLACK, pygame.Rect(round(cx - w / 2), round(cy - 0.26 * s), round(w), round(0.22 * s))
    )
    pygame.draw.polygon(
        big,
        BLACK,
        [(cx - 0.16 * s, cy - 0.06 * s), (cx + 0.16 * s, cy - 0.06 * s), (cx, cy + 0.12 * s)],
    )
    tray = [
        (cx - 0.26 * s, cy + 0.06 * s),
        (cx - 0.26 * s, cy + 0.24 * s),
        (cx + 0.26 * s, cy + 0.24 * s),
        (cx + 0.26 * s, cy + 0.06 * s),
    ]
    pygame.draw.lines(big, BLACK, False, tray, round(0.07 * s))


SYMBOLS: dict[str, Painter] = {"play": _play, "pause": _pause, "restart": _restart, "save": _save}


def save_button_looks(size: int) -> tuple[pygame.Surface, ...]:
    """(idle, hover, down) of the "Save this run" button."""
    return button_looks("save", size)


def button_icon(symbol: str, look: str = "idle", size: int = 64) -> pygame.Surface:
    """A yellow button face with a black outline and symbol, in one of LOOKS."""
    if symbol not in SYMBOLS:
        raise ValueError(f"symbol must be one of {', '.join(SYMBOLS)} (got {symbol!r})")
    if look not in LOOKS:
        raise ValueError(f"look must be one of {', '.join(LOOKS)} (got {look!r})")
    s = size * SUPER
    big = pygame.Surface((s, s), pygame.SRCALPHA)
    _face(big, look)
    shift = 2 * SUPER if look == "down" else 0  # the symbol sinks when pressed
    SYMBOLS[symbol](big, s, (s / 2 + shift, s / 2 + shift))
    return _smooth(big, size)


@lru_cache(maxsize=64)
def button_looks(symbol: str, size: int = 64) -> tuple[pygame.Surface, ...]:
    """(idle, hover, down) images of one symbol, drawn for this size in real pixels."""
    return tuple(button_icon(symbol, look, size) for look in LOOKS)


def window_icon(size: int = 64) -> pygame.Surface:
    """The application icon: atoms sitting in a black cup on a grey tile."""
    from evapcool.view.sprites import atom_sprite

    s = size * SUPER
    big = pygame.Surface((s, s), pygame.SRCALPHA)
    pygame.draw.rect(big, (159, 159, 159), big.get_rect(), border_radius=s // 6)
    pygame.draw.rect(big, (79, 79, 79), big.get_rect(), width=2 * SUPER, border_radius=s // 6)
    # Cup y = k x^2 through (±0.38 s, 0.30 s) with its bottom at 0.80 s.
    k = (0.80 - 0.30) / (0.38 * s) ** 2 * s
    pts = [(s / 2 + x, 0.80 * s - k * x * x) for x in range(-int(0.38 * s), int(0.38 * s) + 1, 4)]
    pygame.draw.lines(big, BLACK, False, pts, 4 * SUPER)
    r = 0.085 * s
    for fx, fy in ((0.5, 0.70), (0.34, 0.62), (0.66, 0.62), (0.5, 0.52), (0.6, 0.30)):
        sprite = atom_sprite(r)
        big.blit(sprite, sprite.get_rect(center=(fx * s, fy * s - 2 * SUPER)))
    return _smooth(big, size)
