"""The condensate moment: after the win the atoms merge into one glowing wave packet.

The packet sits at the bottom of the cup and holds the area the N atoms would
fill there, so its size follows the score. It fades in as the atoms settle;
the applet may draw the atoms themselves with `1 - fade` opacity underneath.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pygame

from evapcool.view.simlike import SimLike

EDGE = np.array([255.0, 120.0, 40.0])  # orange rim: nothing like the cyan atoms
CORE = np.array([255.0, 250.0, 215.0])  # near-white centre
#: The packet holds this fraction of the area the N disks would cover: the
#: condensate is the ground state, far smaller than the thermal cloud was.
SHRINK = 0.35
FADE_SECONDS = 1.5
SETTLED_SPEED = 1.0  # px/frame: below this the post-win wall damping stops (SPEC 1)

ToPx = Callable[[np.ndarray], np.ndarray]


def packet_size(n_atoms: int, radius: float, curvature: float) -> tuple[float, float]:
    """(half width, height) in trap px of the packet holding n atoms of this radius.

    The region of the cup below height h has area (4/3) h sqrt(h / a); it is set
    equal to SHRINK times the area of the atoms, pi r^2 n. The disks add r all round.
    """
    if n_atoms <= 0:
        return 0.0, 0.0
    area = SHRINK * math.pi * radius * radius * n_atoms
    h = (0.75 * area * math.sqrt(curvature)) ** (2.0 / 3.0)
    return math.sqrt(h / curvature) + radius, h + 2.0 * radius


def _scale(to_px: ToPx) -> float:
    p = np.asarray(to_px(np.array([[0.0, 0.0], [1.0, 0.0]])), dtype=float)
    return float(np.hypot(*(p[1] - p[0]))) or 1.0


def draw_condensate(
    surface: pygame.Surface,
    sim: SimLike,
    to_px: ToPx,
    t: float,
    strength: float = 1.0,
) -> pygame.Rect | None:
    """Draw the wave packet with opacity `strength` (0..1) at wall-clock time t (s).

    to_px maps (k, 2) trap coordinates (y up) to screen pixels, like
    `ScreenMap.to_screen` (view/screen.py) or the applet's scaled version. Returns the rectangle
    drawn, or None if there was nothing to draw.
    """
    strength = min(1.0, max(0.0, float(strength)))
    n = int(sim.n_trapped)
    if n == 0 or strength <= 0.0:
        return None
    radii = sim.radii
    r = float(np.mean(radii)) if radii.size else 1.0
    half_w, height = packet_size(n, r, float(sim.curvature))
    breathe = 1.0 + 0.04 * math.sin(2.0 * math.pi * t / 1.3)  # a slow pulse: it is alive
    half_w *= breathe
    half_h = 0.5 * height * breathe
    centre = np.array([[0.0, -r + 0.9 * half_h]])  # rests on the drawn cup bottom
    scale = _scale(to_px)
    cx, cy = (float(v) for v in np.asarray(to_px(centre), dtype=float)[0])

    # Glow reaches 1.3 x the packet; sample the image in screen pixels.
    gw = max(4, int(2.6 * half_w * scale))
    gh = max(4, int(2.6 * half_h * scale))
    xs = (np.arange(gw) - gw / 2 + 0.5) / scale  # trap px from the centre
    ys = (np.arange(gh) - gh / 2 + 0.5) / scale
    u = xs[:, None] / half_w
    v = ys[None, :] / half_h
    envelope = np.exp(-3.0 * (u * u + v * v))
    # Matter-wave fringes drifting sideways: the "one wave" picture.
    wavelength = max(3.0, 1.6 * r)
    fringes = 0.82 + 0.18 * np.cos(2.0 * math.pi * xs[:, None] / wavelength - 4.0 * t)
    level = np.clip(envelope * fringes * 1.5, 0.0, 1.0)
    mix = (level**2)[..., None]
    rgb = EDGE * (1.0 - mix) + CORE * mix

    img = pygame.Surface((gw, gh), pygame.SRCALPHA)
    pygame.surfarray.pixels3d(img)[...] = rgb.astype(np.uint8)
    pygame.surfarray.pixels_alpha(img)[...] = (255.0 * strength * level).astype(np.uint8)
    dest = img.get_rect(center=(round(cx), round(cy)))
    surface.blit(img, dest)
    return dest


class Condensate:
    """Tracks the win and fades the packet in over FADE_SECONDS and as the atoms settle.

    Call `draw(surface, sim, to_px, t)` every frame (t in seconds, any clock);
    before the win it draws nothing. The fade never goes back down, and a new
    `Simulation` (restart) starts over.
    """

    def __init__(self, fade_seconds: float = FADE_SECONDS) -> None:
        self.fade_seconds = float(fade_seconds)
        self._sim: object | None = None
        self._t_win: float | None = None
        self.level = 0.0

    def update(self, sim: SimLike, t: float) -> float:
        """Advance the fade for this frame and return it (0 before the win, up to 1)."""
        if sim is not self._sim:
            self._sim, self._t_win, self.level = sim, None, 0.0
        if not sim.won:
            return 0.0
        if self._t_win is None:
            self._t_win = t
        by_time = (t - self._t_win) / self.fade_seconds if self.fade_seconds > 0 else 1.0
        vel = sim.velocities
        speed = float(np.mean(np.hypot(vel[:, 0], vel[:, 1]))) if len(vel) else 0.0
        # Fully settled once the mean speed is down to where the damping stops.
        by_speed = (3.0 * SETTLED_SPEED - speed) / (2.0 * SETTLED_SPEED)
        target = min(1.0, max(0.0, min(by_time, by_speed)))
        self.level = max(self.level, target)
        return self.level

    def draw(self, surface: pygame.Surface, sim: SimLike, to_px: ToPx, t: float) -> float:
        """Update the fade and draw the packet; returns the fade (dim the atoms by 1 - it)."""
        level = self.update(sim, t)
        if level > 0.0:
            draw_condensate(surface, sim, to_px, t, level)
        return level
