"""Shaded cyan spheres for the atoms, rendered once per radius and cached."""

from __future__ import annotations

import math
from functools import lru_cache
from itertools import repeat

import numpy as np
import pygame

ATOM_COLOR = (30, 215, 245)
#: Light from the upper left, towards the viewer (unit vector, screen y down).
_LIGHT = np.array([-0.45, -0.55, 0.70]) / np.linalg.norm([-0.45, -0.55, 0.70])


def sprite_key(radius: float) -> float:
    """Radii this close share a sprite (quarter pixels)."""
    return round(float(radius) * 4.0) / 4.0


@lru_cache(maxsize=64)
def _sprite(
    key: float, color: tuple[int, int, int], rim: tuple[int, int, int] | None = None
) -> pygame.Surface:
    r = max(key, 0.5)
    size = math.ceil(2.0 * r) + 2
    c = size / 2.0
    # Pixel centres relative to the sphere centre, indexed [x, y] like surfarray.
    x = (np.arange(size) + 0.5 - c)[:, None] / r
    y = (np.arange(size) + 0.5 - c)[None, :] / r
    d2 = x * x + y * y
    z = np.sqrt(np.clip(1.0 - d2, 0.0, 1.0))
    lambert = np.clip(x * _LIGHT[0] + y * _LIGHT[1] + z * _LIGHT[2], 0.0, 1.0)
    # Phong highlight from the reflected light around the view direction (0, 0, 1).
    refl_z = 2.0 * lambert * z - _LIGHT[2]
    spec = np.clip(refl_z, 0.0, 1.0) ** 12
    base = np.array(color, dtype=float)
    rgb = base[None, None, :] * (0.38 + 0.62 * lambert)[..., None] + 255.0 * 0.55 * spec[..., None]
    if rim is not None:  # a dark ring: touching atoms stay two atoms on a light background
        edge = np.clip((np.sqrt(d2) - 1.0) * r + max(1.5, 0.22 * r), 0.0, 1.0)[..., None]
        rgb = rgb * (1.0 - edge) + np.array(rim, dtype=float)[None, None, :] * edge
    # Coverage: one pixel wide soft edge gives smooth outlines at any size.
    alpha = np.clip((1.0 - np.sqrt(d2)) * r + 0.5, 0.0, 1.0)

    surf = pygame.Surface((size, size), pygame.SRCALPHA)
    pygame.surfarray.pixels3d(surf)[...] = np.clip(rgb, 0, 255).astype(np.uint8)
    pygame.surfarray.pixels_alpha(surf)[...] = (alpha * 255.0 + 0.5).astype(np.uint8)
    return surf


def atom_sprite(
    radius: float,
    color: tuple[int, int, int] = ATOM_COLOR,
    rim: tuple[int, int, int] | None = None,
) -> pygame.Surface:
    """A shaded sphere of this radius (px) on a transparent square, centre at its middle."""
    return _sprite(sprite_key(radius), tuple(color), rim)


def draw_atoms(
    surface: pygame.Surface,
    screen_xy: np.ndarray,
    radii: np.ndarray,
    color: tuple[int, int, int] = ATOM_COLOR,
    rim: tuple[int, int, int] | None = None,
) -> None:
    """Draw spheres centred at screen_xy (N, 2) with one batched fblits per radius."""
    n = len(screen_xy)
    if n == 0:
        return
    radii = np.asarray(radii, dtype=float)
    keys = np.round(radii * 4.0) / 4.0
    if n == 1 or np.all(keys == keys[0]):
        groups = [(float(keys[0]), slice(None))]
    else:
        groups = [(float(k), keys == k) for k in np.unique(keys)]
    for key, sel in groups:
        sprite = _sprite(key, tuple(color), rim)
        half = sprite.get_width() / 2.0
        corners = np.floor(screen_xy[sel] - half + 0.5).astype(np.int64)
        # A lazy iterator of (sprite, (x, y)): several times faster than building
        # a list of 10 000 pairs first (allocation and GC, measured).
        xs, ys = corners[:, 0].tolist(), corners[:, 1].tolist()
        surface.fblits(zip(repeat(sprite), zip(xs, ys, strict=True)))
