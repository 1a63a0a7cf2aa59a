"""Side panels that show why evaporation cools, drawn with pygame only.

`EnergyPanel`: live histogram of the trapped atoms' energies, the cut at m g H
and the equilibrium curve N w P(E), P(E) ~ E^(3/2) exp(-E/kT), kT = 2/5 T.
`PathPanel`: the path in the (N, T) plane on log-log axes with T = Tc(N) and
the condensate region (T < Tc(N)) shaded.

Both: `record(sim)` once per frame, `draw(surface, rect)` into any rectangle.
Static parts (axes, ticks, shading) are cached per rectangle size, so a frame
costs a blit plus the live marks. Both reset themselves when handed a new
`Simulation` (a restart), so the applet needs no extra bookkeeping.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable
from typing import Protocol

import numpy as np
import pygame

from evapcool.view.fonts import font as _font

# Light background, dark ink: what survives a washed-out classroom projector.
BG = (244, 243, 238)
PLOT_BG = (255, 255, 255)
INK = (25, 25, 30)
BAR = (60, 150, 200)
CURVE = (20, 20, 20)
CUT = (205, 25, 25)
ESCAPE_TINT = (252, 226, 226)
CONDENSATE = (188, 214, 246)
TC_LINE = (25, 60, 150)
PATH = (215, 95, 10)
KT_FRACTION = 0.4  # kT = 2/5 of the mean energy per atom in this cup (SPEC 4)
_GAMMA_5_2 = 0.75 * math.sqrt(math.pi)


def _blank_canvas(
    rect: pygame.Rect, plot_rect: Callable[[pygame.Rect], pygame.Rect]
) -> tuple[pygame.Surface, pygame.Rect, pygame.Rect]:
    """A panel-sized surface in the background colour with its plot area filled."""
    local = pygame.Rect(0, 0, rect.w, rect.h)
    surf = pygame.Surface(local.size)
    surf.fill(BG)
    plot = plot_rect(local)
    pygame.draw.rect(surf, PLOT_BG, plot)
    return surf, local, plot


class SimLike(Protocol):
    """What the panels read from `evapcool.Simulation`."""

    n_atoms: int
    n_trapped: int
    temperature: float
    initial_temperature: float
    critical_temperature: float
    tc_exponent: float
    trap_height: float
    gravity: float
    won: bool

    @property
    def masses(self) -> np.ndarray: ...

    def energies(self) -> np.ndarray: ...


def _font_size(rect: pygame.Rect) -> int:
    # Scale with the panel, but never below what reads from the back of a room.
    return max(18, min(30, rect.h // 11))


def _margins(rect: pygame.Rect) -> pygame.Rect:
    """The plotting area inside a panel rectangle (room for title, ticks and labels)."""
    fs = _font_size(rect)
    left, right = int(2.6 * fs), int(0.8 * fs)
    top, bottom = int(1.5 * fs), int(2.1 * fs)
    return pygame.Rect(
        rect.x + left,
        rect.y + top,
        max(10, rect.w - left - right),
        max(10, rect.h - top - bottom),
    )


def _nice_step(span: float, target: int = 5) -> float:
    raw = span / max(1, target)
    mag = 10.0 ** math.floor(math.log10(raw))
    for m in (1.0, 2.0, 2.5, 5.0, 10.0):
        if m * mag >= raw:
            return m * mag
    return 10.0 * mag


def _log_ticks(lo: float, hi: float) -> list[float]:
    """1-2-5 ticks inside [lo, hi]; only powers of ten if that gives too many."""
    k0, k1 = math.floor(math.log10(lo)), math.ceil(math.log10(hi))
    for mantissas in ((1, 2, 5), (1, 3), (1,)):
        ticks = [m * 10.0**k for k in range(k0, k1 + 1) for m in mantissas]
        ticks = [t for t in ticks if lo <= t <= hi]
        if len(ticks) <= 7:
            return ticks
    return ticks


def _tick_text(v: float) -> str:
    if v >= 1000:
        return f"{v:.0f}"
    return f"{v:.3g}"


def _blit_text(
    surface: pygame.Surface,
    text: str,
    font: pygame.font.Font,
    color: tuple[int, int, int],
    **anchor: object,
) -> pygame.Rect:
    img = font.render(text, True, color)
    r = img.get_rect(**anchor)
    surface.blit(img, r)
    return r


# ----------------------------------------------------------------------------------
class EnergyPanel:
    """Smoothed histogram of the trapped atoms' energies, the cut and the equilibrium curve.

    Bins are fixed for a whole run (chosen at the first `record` of a simulation)
    so bars stay comparable while the gas cools. `heights` is the mean of the
    per-frame counts over the last `window_frames` recorded frames.
    """

    def __init__(
        self,
        n_bins: int | None = None,
        window_frames: int = 30,
        e_max: float | None = None,
    ) -> None:
        if window_frames < 1:
            raise ValueError(f"window_frames must be >= 1 (got {window_frames!r})")
        if n_bins is not None and n_bins < 1:
            raise ValueError(f"n_bins must be >= 1 (got {n_bins!r})")
        self.n_bins_requested = n_bins
        self.window_frames = int(window_frames)
        self.e_max_requested = e_max
        self._static: tuple[tuple[int, int, int], pygame.Surface] | None = None
        self._label_cache: dict[tuple[str, int], pygame.Surface] = {}
        self.reset()

    def reset(self) -> None:
        """Forget the history and the bins (the next `record` chooses new ones)."""
        self._sim: object | None = None
        self._history: deque[np.ndarray] = deque(maxlen=self.window_frames)
        self.bin_edges: np.ndarray | None = None
        self.n_trapped = 0
        self.temperature = 0.0
        self.cut_energy = math.inf
        self._y_max = 1.0
        self._static = None

    # -- data -------------------------------------------------------------------
    def _choose_bins(self, sim: SimLike, energies: np.ndarray) -> np.ndarray:
        if self.e_max_requested is not None:
            e_max = float(self.e_max_requested)
        else:
            # Room for the starting cut and the hot tail (T = 5/2 kT: 1.8 T is 4.5 kT).
            e_max = 1.8 * sim.initial_temperature
            cut = self._cut_energy(sim)
            if math.isfinite(cut):
                e_max = max(e_max, cut)
            if energies.size:
                e_max = max(e_max, float(energies.max()))
            e_max *= 1.1
        if not (math.isfinite(e_max) and e_max > 0):
            e_max = 1.0
        n = self.n_bins_requested
        if n is None:
            n = int(np.clip(round(2.0 * math.sqrt(max(1, sim.n_atoms))), 12, 40))
        return np.linspace(0.0, e_max, n + 1)

    @staticmethod
    def _cut_energy(sim: SimLike) -> float:
        masses = sim.masses
        m = float(np.mean(masses)) if masses.size else 1.0
        return m * sim.gravity * sim.trap_height

    def record(self, sim: SimLike) -> None:
        """Add this frame's histogram (call once per frame)."""
        if sim is not self._sim:
            self.reset()
            self._sim = sim
        energies = np.asarray(sim.energies(), dtype=float)
        if self.bin_edges is None:
            self.bin_edges = self._choose_bins(sim, energies)
        counts, _ = np.histogram(energies, bins=self.bin_edges)
        self._history.append(counts)
        self.n_trapped = int(sim.n_trapped)
        self.temperature = float(sim.temperature)
        self.cut_energy = self._cut_energy(sim)
        # The y range grows at once and shrinks slowly, so the axes do not jitter.
        target = 1.15 * max(1.0, float(self.heights.max()), float(self.equilibrium_counts().max()))
        if target > self._y_max:
            self._y_max = target
        else:
            self._y_max += 0.03 * (target - self._y_max)

    update = record

    @property
    def frames_in_window(self) -> int:
        return len(self._history)

    @property
    def heights(self) -> np.ndarray:
        """Bar heights: mean atoms per bin over the smoothing window."""
        if not self._history:
            n = 0 if self.bin_edges is None else len(self.bin_edges) - 1
            return np.zeros(n)
        return np.mean(np.stack(self._history), axis=0)

    @property
    def bin_width(self) -> float:
        return 0.0 if self.bin_edges is None else float(self.bin_edges[1] - self.bin_edges[0])

    @property
    def kt(self) -> float:
        return KT_FRACTION * self.temperature

    def equilibrium_density(self, energy: np.ndarray | float) -> np.ndarray:
        """N P(E) in atoms per unit energy at the current temperature (0 if undefined)."""
        e = np.clip(np.asarray(energy, dtype=float), 0.0, None)
        kt = self.kt
        if kt <= 0 or self.n_trapped == 0:
            return np.zeros_like(e)
        return self.n_trapped * e**1.5 * np.exp(-e / kt) / (_GAMMA_5_2 * kt**2.5)

    def equilibrium_counts(self) -> np.ndarray:
        """Expected atoms per bin: N P(E) w at bin centres (the curve's area is N)."""
        if self.bin_edges is None:
            return np.zeros(0)
        centres = 0.5 * (self.bin_edges[:-1] + self.bin_edges[1:])
        return self.equilibrium_density(centres) * self.bin_width

    # -- geometry ---------------------------------------------------------------
    def plot_rect(self, rect: pygame.Rect) -> pygame.Rect:
        """Where the bars go inside the panel rectangle."""
        return _margins(pygame.Rect(rect))

    def energy_to_x(self, energy: float, rect: pygame.Rect) -> float:
        """Screen x (float) of an energy on the panel's axis."""
        plot = self.plot_rect(rect)
        e_max = 1.0 if self.bin_edges is None else float(self.bin_edges[-1])
        return plot.x + plot.w * float(energy) / e_max

    def cut_x(self, rect: pygame.Rect) -> int:
        """Pixel column of the cut line m g H (may lie beyond the plot if H is huge)."""
        return (
            round(self.energy_to_x(self.cut_energy, rect))
            if math.isfinite(self.cut_energy)
            else self.plot_rect(rect).right
        )

    def count_to_y(self, count: float, rect: pygame.Rect) -> float:
        plot = self.plot_rect(rect)
        return plot.bottom - plot.h * float(count) / self._y_max

    # -- drawing ----------------------------------------------------------------
    def _static_layer(self, rect: pygame.Rect) -> pygame.Surface:
        key = (rect.w, rect.h, id(self.bin_edges))
        if self._static is not None and self._static[0] == key:
            return self._static[1]
        surf, local, plot = _blank_canvas(rect, self.plot_rect)
        fs = _font_size(local)
        font, small = _font(fs, bold=True), _font(int(fs * 0.85))
        _blit_text(surf, "Energies of the trapped atoms", font, INK, midtop=(local.centerx, 4))
        if self.bin_edges is not None:
            e_max = float(self.bin_edges[-1])
            step = _nice_step(e_max)
            v = 0.0
            while v <= e_max * (1 + 1e-9):
                x = round(plot.x + plot.w * v / e_max)
                pygame.draw.line(surf, INK, (x, plot.bottom), (x, plot.bottom + 5), 2)
                _blit_text(surf, _tick_text(v), small, INK, midtop=(x, plot.bottom + 6))
                v += step
        _blit_text(surf, "energy E", small, INK, midbottom=(plot.centerx, local.bottom - 2))
        ylabel = pygame.transform.rotate(small.render("atoms per bin", True, INK), 90)
        surf.blit(ylabel, ylabel.get_rect(midleft=(4, plot.centery)))
        pygame.draw.rect(surf, INK, plot, 2)
        self._static = (key, surf)
        return surf

    def _tick_label(
        self, v: float, font: pygame.font.Font, **anchor: object
    ) -> tuple[pygame.Surface, pygame.Rect]:
        key = (_tick_text(v), font.get_height())
        img = self._label_cache.get(key)
        if img is None:
            img = self._label_cache[key] = font.render(key[0], True, INK)
        return img, img.get_rect(**anchor)

    def draw(self, surface: pygame.Surface, rect: pygame.Rect) -> None:
        """Draw the panel into rect on surface (nothing outside rect is touched)."""
        rect = pygame.Rect(rect)
        old_clip = surface.get_clip()
        surface.set_clip(rect.clip(old_clip) if old_clip else rect)
        try:
            self._draw(surface, rect)
        finally:
            surface.set_clip(old_clip)

    def _draw(self, surface: pygame.Surface, rect: pygame.Rect) -> None:
        surface.blit(self._static_layer(rect), rect)
        plot = self.plot_rect(rect)
        inner = plot.inflate(-4, -4)
        fs = _font_size(rect)
        small = _font(int(fs * 0.85))
        if self.bin_edges is None:
            _blit_text(surface, "no data yet", small, INK, center=plot.center)
            return
        outer_clip = surface.get_clip()
        surface.set_clip(inner.clip(outer_clip))
        cx = self.cut_x(rect)
        if cx < inner.right:  # tint the energies that leave the trap
            pygame.draw.rect(surface, ESCAPE_TINT, (cx, inner.y, inner.right - cx, inner.h))
        # Bars. Positions are energy_to_x / count_to_y in bulk (the same arithmetic,
        # without recomputing the plot rectangle per point: it is the frame's hot path).
        e_max = float(self.bin_edges[-1])
        edges_x = (plot.x + plot.w * self.bin_edges / e_max).tolist()
        for i, h in enumerate(self.heights.tolist()):
            if h <= 0:
                continue
            x0, x1 = round(edges_x[i]), round(edges_x[i + 1])
            top = round(plot.bottom - plot.h * h / self._y_max)
            surface.fill(BAR, (x0 + 1, top, max(1, x1 - x0 - 2), plot.bottom - top))
        # Equilibrium curve, as atoms per bin so it sits on the bars.
        if self.n_trapped and self.kt > 0:
            es = np.linspace(0.0, e_max, 120)
            ys = self.equilibrium_density(es) * self.bin_width
            pts = np.column_stack(
                (plot.x + plot.w * es / e_max, plot.bottom - plot.h * ys / self._y_max)
            )
            pygame.draw.lines(surface, CURVE, False, pts.tolist(), 3)
        # The cut line on top of everything in the plot.
        if cx <= inner.right:
            pygame.draw.rect(surface, CUT, (cx - 1, inner.y, 3, inner.h))
        surface.set_clip(outer_clip)
        # Count ticks move with the (slowly adapting) y range, so they are drawn per frame.
        for v in np.arange(0.0, self._y_max, _nice_step(self._y_max, 4)):
            y = round(self.count_to_y(v, rect))
            pygame.draw.line(surface, INK, (plot.x - 5, y), (plot.x, y), 2)
            surface.blit(*self._tick_label(v, small, midright=(plot.x - 6, y)))
        # Labels and legend.
        if cx <= inner.right:
            lab = small.render("cut m g H", True, CUT)
            lr = lab.get_rect(topright=(cx - 6, inner.y + 4))
            if lr.left < inner.left + 4:
                lr.topleft = (cx + 6, inner.y + 4)
            surface.blit(lab, lr)
        else:
            _blit_text(surface, "cut m g H ->", small, CUT, topright=(inner.right - 4, inner.y + 4))
        legend = f"N = {self.n_trapped}   kT = {self.kt:.3g}"
        _blit_text(surface, legend, small, INK, topright=(inner.right - 4, inner.y + 8 + fs))
        ly = inner.y + 14 + 2 * fs
        pygame.draw.line(surface, CURVE, (inner.right - 150, ly), (inner.right - 125, ly), 3)
        _blit_text(surface, "equilibrium", small, INK, midright=(inner.right - 4, ly))


# ----------------------------------------------------------------------------------
class PathPanel:
    """The player's path in the (N, T) plane, log-log, with T = Tc(N) and the condensate.

    Axes are fixed per run from the first `record`: N from 1 to 1.25 N0, T from
    half of Tc(1) to 1.6 T0. Points outside are drawn clamped to the frame.
    By default recording stops after the first frame with `sim.won` (the path
    ends where the gas condenses; the settling afterwards is not cooling).
    """

    def __init__(self, stop_after_win: bool = True) -> None:
        self.stop_after_win = stop_after_win
        self._static: tuple[tuple, pygame.Surface] | None = None
        self.overlay_rects: list[pygame.Rect] = []
        self._overlay_local: list[pygame.Rect] = []
        self.reset()

    def reset(self) -> None:
        self._sim: object | None = None
        self._n: list[int] = []
        self._t: list[float] = []
        self._done = False
        self.n0 = 1
        self.t0 = 1.0
        self.tc0 = 0.75
        self.exponent = 2.0 / 3.0
        self.n_range = (1.0, 1.25)
        self.t_range = (0.1, 1.6)
        self._static = None
        self._px: list[tuple[int, int]] = []
        self._px_upto = 0
        self._px_key: tuple[int, int, int, int] | None = None

    # -- data -------------------------------------------------------------------
    def _adopt(self, sim: SimLike) -> None:
        self.reset()
        self._sim = sim
        self.n0 = int(sim.n_atoms)
        self.t0 = float(sim.initial_temperature)
        self.exponent = float(sim.tc_exponent)
        n = int(sim.n_trapped)
        # Read Tc0 off the simulation's own law, so the line is exactly the one that decides.
        if n > 0:
            self.tc0 = float(sim.critical_temperature) / (n / self.n0) ** self.exponent
        else:
            self.tc0 = 0.75 * self.t0
        self.n_range = (1.0, 1.25 * max(self.n0, 2))
        t_lo = 0.5 * min(self.tc(1.0), self.t0)
        self.t_range = (max(t_lo, 1e-12), max(1.6 * self.t0, 2 * t_lo))

    def record(self, sim: SimLike) -> bool:
        """Add the current (N, T) as one point; False if nothing was added.

        Nothing is added for an empty cup (no point on log axes) or after the win.
        """
        if sim is not self._sim:
            self._adopt(sim)
        if self._done:
            return False
        n, t = int(sim.n_trapped), float(sim.temperature)
        if n <= 0 or not (t > 0 and math.isfinite(t)):
            return False
        self._n.append(n)
        self._t.append(t)
        if self.stop_after_win and sim.won:
            self._done = True
        return True

    update = record

    @property
    def points(self) -> np.ndarray:
        """(k, 2) array of recorded (N, T), oldest first."""
        if not self._n:
            return np.zeros((0, 2))
        return np.column_stack((np.asarray(self._n, float), np.asarray(self._t)))

    def tc(self, n: float | np.ndarray) -> float | np.ndarray:
        """Tc(N) = Tc0 (N / N0)^p for the recorded run."""
        return self.tc0 * (np.asarray(n, dtype=float) / self.n0) ** self.exponent

    def in_condensate(self, n: float, t: float) -> bool:
        """True where the shading is: T < Tc(N)."""
        return bool(t < self.tc(n))

    # -- geometry ---------------------------------------------------------------
    def plot_rect(self, rect: pygame.Rect) -> pygame.Rect:
        return _margins(pygame.Rect(rect))

    def _log_frac(self, v: float | np.ndarray, lo: float, hi: float) -> np.ndarray:
        return (np.log(np.asarray(v, dtype=float)) - math.log(lo)) / (math.log(hi) - math.log(lo))

    def to_pixel(self, n: float, t: float, rect: pygame.Rect) -> tuple[float, float]:
        """Screen (x, y) of the point (N, T) as floats; the pixel is (floor(x), floor(y))."""
        plot = self.plot_rect(rect)
        fx = float(self._log_frac(n, *self.n_range))
        fy = float(self._log_frac(t, *self.t_range))
        return plot.x + plot.w * fx, plot.bottom - plot.h * fy

    def pixel_of(self, n: float, t: float, rect: pygame.Rect) -> tuple[int, int]:
        x, y = self.to_pixel(n, t, rect)
        return math.floor(x), math.floor(y)

    def from_pixel(self, px: int, py: int, rect: pygame.Rect) -> tuple[float, float]:
        """(N, T) at the centre of screen pixel (px, py)."""
        plot = self.plot_rect(rect)
        fx = (px + 0.5 - plot.x) / plot.w
        fy = (plot.bottom - (py + 0.5)) / plot.h
        (n_lo, n_hi), (t_lo, t_hi) = self.n_range, self.t_range
        return n_lo * (n_hi / n_lo) ** fx, t_lo * (t_hi / t_lo) ** fy

    def pixel_in_condensate(self, px: int, py: int, rect: pygame.Rect) -> bool:
        """Whether the shading covers pixel (px, py) (inside the plot)."""
        plot = self.plot_rect(rect)
        return plot.collidepoint(px, py) and self.in_condensate(*self.from_pixel(px, py, rect))

    # -- drawing ----------------------------------------------------------------
    def _static_layer(self, rect: pygame.Rect) -> pygame.Surface:
        key = (rect.w, rect.h, self.n_range, self.t_range, self.tc0, self.exponent, self.n0)
        if self._static is not None and self._static[0] == key:
            return self._static[1]
        surf, local, plot = _blank_canvas(rect, self.plot_rect)
        # Shading column by column, so pixel (x, y) is shaded exactly when the
        # (N, T) at its centre has T < Tc(N) (see from_pixel).
        xs = np.arange(plot.x, plot.right)
        ns = np.array([self.from_pixel(int(x), plot.y, local)[0] for x in xs])
        ybound = np.array([self.to_pixel(n, float(self.tc(n)), local)[1] for n in ns])
        first = np.floor(ybound - 0.5).astype(int) + 1
        for x, y0 in zip(xs, first, strict=True):
            y0 = max(int(y0), plot.y)
            if y0 < plot.bottom:
                surf.fill(CONDENSATE, (int(x), y0, 1, plot.bottom - y0))
        line = [(float(x) + 0.5, float(y)) for x, y in zip(xs, ybound, strict=True)]
        surf.set_clip(plot)
        pygame.draw.lines(surf, TC_LINE, False, line, 3)
        surf.set_clip(None)

        fs = _font_size(local)
        font, small = _font(fs, bold=True), _font(int(fs * 0.85))
        _blit_text(surf, "Path to condensation", font, INK, midtop=(local.centerx, 4))
        for v in _log_ticks(*self.n_range):
            x = round(self.to_pixel(v, self.t_range[0], local)[0])
            pygame.draw.line(surf, INK, (x, plot.bottom), (x, plot.bottom + 5), 2)
            _blit_text(surf, _tick_text(v), small, INK, midtop=(x, plot.bottom + 6))
        for v in _log_ticks(*self.t_range):
            y = round(self.to_pixel(self.n_range[0], v, local)[1])
            pygame.draw.line(surf, INK, (plot.x - 5, y), (plot.x, y), 2)
            _blit_text(surf, _tick_text(v), small, INK, midright=(plot.x - 6, y))
        _blit_text(
            surf, "atoms in the cup N", small, INK, midbottom=(plot.centerx, local.bottom - 2)
        )
        ylabel = pygame.transform.rotate(small.render("temperature T", True, INK), 90)
        surf.blit(ylabel, ylabel.get_rect(midleft=(2, plot.centery)))

        # Labels inside the plot: remembered (panel-relative) so tests can skip them.
        self._overlay_local = []
        lab = font.render("condensate", True, TC_LINE)
        lr = lab.get_rect(bottomright=(plot.right - 8, plot.bottom - 8))
        surf.blit(lab, lr)
        self._overlay_local.append(lr)
        # "T = Tc(N)" just above the line, a third of the way across.
        lab2 = small.render("T = Tc(N)", True, TC_LINE)
        xl = plot.x + plot.w // 3
        span = np.interp([xl, xl + lab2.get_width()], xs, ybound)
        lr2 = lab2.get_rect(bottomleft=(xl, round(float(span.min())) - 8))
        lr2.clamp_ip(plot.inflate(-8, -8))
        surf.blit(lab2, lr2)
        self._overlay_local.append(lr2)
        pygame.draw.rect(surf, INK, plot, 2)
        self._static = (key, surf)
        return surf

    def _path_pixels(self, rect: pygame.Rect) -> list[tuple[int, int]]:
        """Recorded points as pixels, consecutive repeats dropped (cached, incremental)."""
        key = (rect.x, rect.y, rect.w, rect.h)
        if key != self._px_key:
            self._px, self._px_upto, self._px_key = [], 0, key
        plot = self.plot_rect(rect).inflate(-4, -4)
        for n, t in zip(self._n[self._px_upto :], self._t[self._px_upto :], strict=True):
            x, y = self.pixel_of(n, t, rect)
            p = (min(max(x, plot.x), plot.right - 1), min(max(y, plot.y), plot.bottom - 1))
            if not self._px or self._px[-1] != p:
                self._px.append(p)
        self._px_upto = len(self._n)
        return self._px

    def draw(self, surface: pygame.Surface, rect: pygame.Rect) -> None:
        """Draw the panel into rect on surface (nothing outside rect is touched)."""
        rect = pygame.Rect(rect)
        old_clip = surface.get_clip()
        surface.set_clip(rect.clip(old_clip) if old_clip else rect)
        try:
            surface.blit(self._static_layer(rect), rect)
            self.overlay_rects = [r.move(rect.x, rect.y) for r in self._overlay_local]
            pts = self._path_pixels(rect)
            if len(pts) >= 2:
                pygame.draw.lines(surface, PATH, False, pts, 3)
            for p in pts[:: max(1, len(pts) // 200)]:  # markers, thinned for long runs
                pygame.draw.circle(surface, PATH, p, 3)
            if pts:
                pygame.draw.circle(surface, INK, pts[-1], 8)
                pygame.draw.circle(surface, PATH, pts[-1], 6)
                fs = _font_size(rect)
                small = _font(int(fs * 0.85))
                n, t = self._n[-1], self._t[-1]
                text = f"N = {n}   T = {t:.3g}   Tc = {float(self.tc(n)):.3g}"
                plot = self.plot_rect(rect)
                r = _blit_text(surface, text, small, INK, topleft=(plot.x + 8, plot.y + 6))
                self.overlay_rects.append(r)
        finally:
            surface.set_clip(old_clip)
