"""Side panels that show why evaporation cools, drawn with pygame only.

`EnergyPanel`: live histogram of the trapped atoms' energies, the cut at m g H
and the equilibrium curve N w P(E), P(E) ~ E^(3/2) exp(-5E / 2T) (T: the game's
temperature, the mean energy per atom).
`PathPanel`: the path in the (N, T) plane on log-log axes with T = Tc(N) and
the condensate region (T < Tc(N)) shaded.

Both: `record(sim)` once per frame, `draw(surface, rect, scale)` into any rectangle at
any scale (fonts and lines drawn at the size they are seen). Every word sits outside the
plotting area, in the header (title, legend, live readout) or by the axes, so data
never crosses a label. Static parts are cached per size, so a frame costs a blit
plus the live marks. Both reset themselves when handed a new `Simulation`.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
import pygame

from evapcool import i18n
from evapcool.view.fonts import text_image, text_size
from evapcool.view.simlike import SimLike

# Light background, dark ink: what survives a washed-out classroom projector.
BG = (244, 243, 238)
PLOT_BG = (255, 255, 255)
INK = (25, 25, 30)
BAR = (60, 150, 200)
CURVE = (20, 20, 20)
#: The chart's lines and the path at 7:1 or more on the white plot (issue 48: projectors).
CUT = (180, 0, 0)
ESCAPE_TINT = (252, 226, 226)
CONDENSATE = (188, 214, 246)
TC_LINE = (25, 60, 150)
PATH = (160, 40, 0)
#: Room kept free in a panel's top-right corner (logical px), for the app's close button.
CORNER_RESERVE = 40
KT_FRACTION = 0.4  # kT = 2/5 of the mean energy per atom in this cup (SPEC 4)
_GAMMA_5_2 = 0.75 * math.sqrt(math.pi)


# -- layout shared by both panels ------------------------------------------------------
@dataclass(frozen=True)
class LegendItem:
    """A legend entry: a swatch ('bar', 'line' or 'dot') in a colour, and its words."""

    mark: str
    color: tuple[int, int, int]
    text: str


@dataclass(frozen=True)
class PanelLayout:
    """Where everything of a panel goes, in surface pixels, for one rect and scale."""

    rect: pygame.Rect
    scale: float
    title_text: str
    font: int  # title size, px (smaller than the panel's font size if it had to fit)
    small: int  # legend, ticks and axis labels, px
    title: pygame.Rect
    legend: tuple[tuple[LegendItem, pygame.Rect], ...]
    readout: pygame.Rect  # the live numbers (N, T...), reserved at their widest
    plot: pygame.Rect

    def px(self, v: float) -> int:
        """A logical length at this scale, whole pixels, at least 1."""
        return max(1, round(v * self.scale))


def _font_size(rect: pygame.Rect, scale: float = 1.0) -> int:
    # Scale with the panel, but never below what reads from the back of a room.
    return round(scale * max(18, min(30, int(rect.h / scale) // 11)))


def layout(
    rect: pygame.Rect, scale: float, title: str, items: Sequence[LegendItem], readout: str
) -> PanelLayout:
    """Title on top, the legend flowing in rows below it, then the plot with its margins."""
    rect = pygame.Rect(rect)
    fs = _font_size(rect, scale)
    small = max(1, round(0.85 * fs))
    pad = max(1, round(6 * scale))
    # The title shrinks to fit between the corners (the top-right one is kept for a
    # close button), never below the legend's size.
    room = rect.w - 2 * round(CORNER_RESERVE * scale)
    title_size = fs
    while title_size > small and text_size(title, title_size, True)[0] > room:
        title_size -= 1
    tw, th = text_size(title, title_size, True)
    title_rect = pygame.Rect(0, rect.y + pad // 2, tw, th)
    title_rect.centerx = rect.centerx
    left, right = rect.x + int(2.6 * fs), rect.right - int(0.8 * fs)
    x0 = rect.x + 2 * pad  # the legend may use the width the y labels leave free
    row_h = text_size("Ag", small)[1]
    x, y = x0, title_rect.bottom + pad // 2
    placed = []
    widths = [(item, 2 * small + text_size(item.text, small)[0]) for item in items]
    widths.append((None, text_size(readout, small)[0]))
    readout_rect = pygame.Rect(0, 0, 0, 0)
    for item, w in widths:
        if x > x0 and x + w > right:
            x, y = x0, y + row_h
        r = pygame.Rect(x, y, w, row_h)
        if item is None:
            readout_rect = r
        else:
            placed.append((item, r))
        x += w + small
    top = y + row_h + pad
    bottom = rect.bottom - int(2.1 * fs)
    plot = pygame.Rect(left, top, max(10, right - left), max(10, bottom - top))
    return PanelLayout(
        rect, scale, title, title_size, small, title_rect, tuple(placed), readout_rect, plot
    )


def _blank(lay: PanelLayout) -> pygame.Surface:
    """The static layer: background, title, legend, empty plot (panel-local pixels)."""
    surf = pygame.Surface(lay.rect.size)
    surf.fill(BG)
    ox, oy = lay.rect.topleft
    surf.fill(PLOT_BG, lay.plot.move(-ox, -oy))
    image = text_image(lay.title_text, lay.font, INK, True)
    surf.blit(image, lay.title.move(-ox, -oy))
    for item, r in lay.legend:
        r = r.move(-ox, -oy)
        sw = pygame.Rect(r.x, r.y, int(1.5 * lay.small), r.h).inflate(0, -r.h // 3)
        if item.mark == "bar":
            surf.fill(item.color, sw)
        elif item.mark == "line":
            pygame.draw.line(surf, item.color, sw.midleft, sw.midright, lay.px(3))
        else:
            pygame.draw.circle(surf, item.color, sw.center, lay.px(5))
        image = text_image(item.text, lay.small, INK)
        surf.blit(image, image.get_rect(midleft=(r.x + 2 * lay.small, r.centery)))
    return surf


def _draw_frame(surf: pygame.Surface, lay: PanelLayout) -> None:
    ox, oy = lay.rect.topleft
    pygame.draw.rect(surf, INK, lay.plot.move(-ox, -oy), lay.px(2))


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
    return i18n.number(round(v)) if v >= 1000 else _g3(v)


def _g3(v: float) -> str:
    """Three significant digits, the language's decimal mark."""
    return i18n.number(float(f"{v:.3g}"))


def _blit_text(
    surface: pygame.Surface,
    text: str,
    size: int,
    color: tuple[int, int, int],
    bold: bool = False,
    **anchor: object,
) -> pygame.Rect:
    img = text_image(text, size, color, bold)
    r = img.get_rect(**anchor)
    surface.blit(img, r)
    return r


class _Panel:
    """What both panels share: layouts by size and scale, the static layer, clipped drawing."""

    title = ""
    legend_items: tuple[LegendItem, ...] = ()
    readout_template = ""

    def __init__(self) -> None:
        self.scale = 1.0
        #: Every text drawn at the last draw (surface pixels): none lies in the plot.
        self.label_rects: list[pygame.Rect] = []
        self._layouts: dict[tuple, PanelLayout] = {}

    def layout(self, rect: pygame.Rect, scale: float | None = None) -> PanelLayout:
        s = self.scale if scale is None else float(scale)
        rect = pygame.Rect(rect)
        key = (rect.x, rect.y, rect.w, rect.h, s, i18n.active().locale)
        lay = self._layouts.get(key)
        if lay is None:
            if len(self._layouts) > 16:
                self._layouts.clear()
            items = tuple(replace(i, text=i18n.t(i.text)) for i in self.legend_items)
            readout = i18n.t(self.readout_template, n=88888, t="8.88", tc="8.88")
            lay = self._layouts[key] = layout(rect, s, i18n.t(self.title), items, readout)
        return lay

    def plot_rect(self, rect: pygame.Rect, scale: float | None = None) -> pygame.Rect:
        """Where the data goes inside the panel rectangle (at the last drawn scale)."""
        return self.layout(rect, scale).plot

    def draw(self, surface: pygame.Surface, rect: pygame.Rect, scale: float = 1.0) -> None:
        """Draw the panel into rect on surface at this scale (nothing outside rect changes)."""
        self.scale = float(scale)
        lay = self.layout(rect)
        old_clip = surface.get_clip()
        surface.set_clip(lay.rect.clip(old_clip) if old_clip else lay.rect)
        try:
            words = [r.inflate(-2 * lay.small, 0).move(lay.small, 0) for _, r in lay.legend]
            self.label_rects = [lay.title, *words]
            self._draw(surface, lay)
        finally:
            surface.set_clip(old_clip)

    def _draw(self, surface: pygame.Surface, lay: PanelLayout) -> None:
        raise NotImplementedError

    def _readout(self, surface: pygame.Surface, lay: PanelLayout, text: str) -> None:
        r = _blit_text(surface, text, lay.small, INK, midleft=lay.readout.midleft)
        self.label_rects.append(r)

    def _label(self, surface: pygame.Surface, lay: PanelLayout, text: str, **anchor) -> pygame.Rect:
        r = _blit_text(surface, text, lay.small, INK, **anchor)
        self.label_rects.append(r)
        return r


# ----------------------------------------------------------------------------------
class EnergyPanel(_Panel):
    """Smoothed histogram of the trapped atoms' energies, the cut and the equilibrium curve.

    Bins are fixed for a whole run (chosen at the first `record` of a simulation)
    so bars stay comparable while the gas cools. `heights` is the mean of the
    per-frame counts over the last `window_frames` recorded frames.
    """

    title = "chart.energies"
    legend_items = (
        LegendItem("bar", BAR, "chart.legend.atoms"),
        LegendItem("line", CURVE, "chart.legend.equilibrium"),
        LegendItem("bar", CUT, "chart.legend.cut"),
    )
    readout_template = "chart.readout_energy"

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
        super().__init__()
        self.n_bins_requested = n_bins
        self.window_frames = int(window_frames)
        self.e_max_requested = e_max
        self._static: tuple[tuple, pygame.Surface] | None = None
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
        #: The gas condensed: the chart holds the win's frame, as the path chart does (the
        #: settling after it is the condensate's picture, not a temperature: issue 49.7).
        self.held = False

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
        if self.held:
            return
        self.held = bool(sim.won)
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
        """The equilibrium curve's energy scale, 2/5 T in this cup (never shown as such)."""
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
    def _static_layer(self, lay: PanelLayout) -> pygame.Surface:
        key = (lay.rect.size, lay.scale, id(self.bin_edges), lay.title_text)
        if self._static is not None and self._static[0] == key:
            return self._static[1]
        surf = _blank(lay)
        plot = lay.plot.move(-lay.rect.x, -lay.rect.y)
        if self.bin_edges is not None:
            e_max = float(self.bin_edges[-1])
            step = _nice_step(e_max)
            v = 0.0
            while v <= e_max * (1 + 1e-9):
                x = round(plot.x + plot.w * v / e_max)
                pygame.draw.line(
                    surf, INK, (x, plot.bottom), (x, plot.bottom + lay.px(5)), lay.px(2)
                )
                _blit_text(surf, _tick_text(v), lay.small, INK, midtop=(x, plot.bottom + lay.px(6)))
                v += step
        _draw_frame(surf, lay)
        self._static = (key, surf)
        return surf

    def _draw(self, surface: pygame.Surface, lay: PanelLayout) -> None:
        surface.blit(self._static_layer(lay), lay.rect)
        plot = lay.plot
        rect = lay.rect
        self._label(
            surface,
            lay,
            i18n.t("chart.axis.energy"),
            midbottom=(plot.centerx, rect.bottom - lay.px(2)),
        )
        ylabel = pygame.transform.rotate(
            text_image(i18n.t("chart.axis.per_bin"), lay.small, INK), 90
        )
        self.label_rects.append(
            surface.blit(ylabel, ylabel.get_rect(midleft=(rect.x + lay.px(4), plot.centery)))
        )
        if self.bin_edges is None:
            self._label(surface, lay, i18n.t("chart.no_data"), midleft=lay.readout.midleft)
            return
        self._draw_data(surface, lay)
        # Count ticks move with the (slowly adapting) y range, so they are drawn per frame.
        for v in np.arange(0.0, self._y_max, _nice_step(self._y_max, 4)):
            y = round(self.count_to_y(v, rect))
            pygame.draw.line(surface, INK, (plot.x - lay.px(5), y), (plot.x, y), lay.px(2))
            self._label(surface, lay, _tick_text(v), midright=(plot.x - lay.px(6), y))
        self._readout(
            surface, lay, i18n.t("chart.readout_energy", n=self.n_trapped, t=_g3(self.temperature))
        )

    def _draw_data(self, surface: pygame.Surface, lay: PanelLayout) -> None:
        """Tint, bars, curve and cut, all clipped to the inside of the frame."""
        plot = lay.plot
        inner = plot.inflate(-2 * lay.px(2), -2 * lay.px(2))
        outer_clip = surface.get_clip()
        surface.set_clip(inner.clip(outer_clip))
        cx = self.cut_x(lay.rect)
        if cx < inner.right:  # tint the energies that leave the trap
            surface.fill(ESCAPE_TINT, (cx, inner.y, inner.right - cx, inner.h))
        # Bars: energy_to_x / count_to_y in bulk (the frame's hot path).
        e_max = float(self.bin_edges[-1])
        edges_x = (plot.x + plot.w * self.bin_edges / e_max).tolist()
        gap = lay.px(1)
        for i, h in enumerate(self.heights.tolist()):
            if h <= 0:
                continue
            x0, x1 = round(edges_x[i]), round(edges_x[i + 1])
            top = round(plot.bottom - plot.h * h / self._y_max)
            surface.fill(BAR, (x0 + gap, top, max(1, x1 - x0 - 2 * gap), plot.bottom - top))
        # Equilibrium curve, as atoms per bin so it sits on the bars.
        if self.n_trapped and self.kt > 0:
            es = np.linspace(0.0, e_max, 160)
            ys = self.equilibrium_density(es) * self.bin_width
            pts = np.column_stack(
                (plot.x + plot.w * es / e_max, plot.bottom - plot.h * ys / self._y_max)
            )
            pygame.draw.lines(surface, CURVE, False, pts.tolist(), lay.px(3))
        # The cut line on top of everything in the plot.
        if cx <= inner.right:
            w = max(3, lay.px(3))
            surface.fill(CUT, (cx - w // 2, inner.y, w, inner.h))
        surface.set_clip(outer_clip)


# ----------------------------------------------------------------------------------
class PathPanel(_Panel):
    """The player's path in the (N, T) plane, log-log, with T = Tc(N) and the condensate.

    Axes are fixed per run from the first `record`: N from 1 to 1.25 N0, T from
    half of Tc(1) to 1.6 T0. Points outside are drawn clamped to the frame.
    By default recording stops after the first frame with `sim.won` (the path
    ends where the gas condenses; the settling afterwards is not cooling).
    """

    title = "chart.path"
    legend_items = (
        LegendItem("dot", PATH, "chart.legend.your_path"),
        LegendItem("line", TC_LINE, "chart.legend.tc_line"),
        LegendItem("bar", CONDENSATE, "chart.legend.condensate"),
    )
    readout_template = "chart.readout_path"

    def __init__(self, stop_after_win: bool = True) -> None:
        super().__init__()
        self.stop_after_win = stop_after_win
        self._static: tuple[tuple, pygame.Surface] | None = None
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
        self._px_key: tuple | None = None

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
    def _static_layer(self, lay: PanelLayout) -> pygame.Surface:
        key = (
            lay.rect.topleft,
            lay.rect.size,
            lay.scale,
            self.n_range,
            self.t_range,
            lay.title_text,
        )
        key += (self.tc0, self.exponent, self.n0)
        if self._static is not None and self._static[0] == key:
            return self._static[1]
        surf = _blank(lay)
        ox, oy = lay.rect.topleft
        plot = lay.plot
        # Shading column by column, so pixel (x, y) is shaded exactly when the
        # (N, T) at its centre has T < Tc(N) (see from_pixel).
        xs = np.arange(plot.x, plot.right)
        ns = np.array([self.from_pixel(int(x), plot.y, lay.rect)[0] for x in xs])
        ybound = np.array([self.to_pixel(n, float(self.tc(n)), lay.rect)[1] for n in ns])
        first = np.floor(ybound - 0.5).astype(int) + 1
        for x, y0 in zip(xs, first, strict=True):
            y0 = max(int(y0), plot.y)
            if y0 < plot.bottom:
                surf.fill(CONDENSATE, (int(x) - ox, y0 - oy, 1, plot.bottom - y0))
        line = [(float(x) + 0.5 - ox, float(y) - oy) for x, y in zip(xs, ybound, strict=True)]
        surf.set_clip(plot.move(-ox, -oy))
        pygame.draw.lines(surf, TC_LINE, False, line, lay.px(3))
        surf.set_clip(None)
        for v in _log_ticks(*self.n_range):
            x = round(self.to_pixel(v, self.t_range[0], lay.rect)[0]) - ox
            pygame.draw.line(
                surf, INK, (x, plot.bottom - oy), (x, plot.bottom - oy + lay.px(5)), lay.px(2)
            )
            _blit_text(
                surf, _tick_text(v), lay.small, INK, midtop=(x, plot.bottom - oy + lay.px(6))
            )
        for v in _log_ticks(*self.t_range):
            y = round(self.to_pixel(self.n_range[0], v, lay.rect)[1]) - oy
            x0 = plot.x - ox
            pygame.draw.line(surf, INK, (x0 - lay.px(5), y), (x0, y), lay.px(2))
            _blit_text(surf, _tick_text(v), lay.small, INK, midright=(x0 - lay.px(6), y))
        _draw_frame(surf, lay)
        self._static = (key, surf)
        return surf

    def _path_pixels(self, lay: PanelLayout) -> list[tuple[int, int]]:
        """Recorded points as pixels, consecutive repeats dropped (cached, incremental)."""
        key = (lay.rect.x, lay.rect.y, lay.rect.w, lay.rect.h, lay.scale)
        if key != self._px_key:
            self._px, self._px_upto, self._px_key = [], 0, key
        plot = lay.plot.inflate(-4, -4)
        for n, t in zip(self._n[self._px_upto :], self._t[self._px_upto :], strict=True):
            x, y = self.pixel_of(n, t, lay.rect)
            p = (min(max(x, plot.x), plot.right - 1), min(max(y, plot.y), plot.bottom - 1))
            if not self._px or self._px[-1] != p:
                self._px.append(p)
        self._px_upto = len(self._n)
        return self._px

    @property
    def overlay_rects(self) -> list[pygame.Rect]:
        """Texts inside the plot: none (every label sits outside it)."""
        return []

    def _draw(self, surface: pygame.Surface, lay: PanelLayout) -> None:
        surface.blit(self._static_layer(lay), lay.rect)
        plot, rect = lay.plot, lay.rect
        self._label(
            surface,
            lay,
            i18n.t("chart.axis.atoms"),
            midbottom=(plot.centerx, rect.bottom - lay.px(2)),
        )
        ylabel = pygame.transform.rotate(
            text_image(i18n.t("chart.axis.temperature"), lay.small, INK), 90
        )
        where = ylabel.get_rect(midleft=(rect.x + lay.px(2), plot.centery))
        self.label_rects.append(surface.blit(ylabel, where))
        pts = self._path_pixels(lay)
        old = surface.get_clip()
        surface.set_clip(plot.inflate(-2 * lay.px(2), -2 * lay.px(2)).clip(old))
        if len(pts) >= 2:
            pygame.draw.lines(surface, PATH, False, pts, lay.px(3))
        for p in pts[:: max(1, len(pts) // 200)]:  # markers, thinned for long runs
            pygame.draw.circle(surface, PATH, p, lay.px(3))
        if pts:
            pygame.draw.circle(surface, INK, pts[-1], lay.px(8))
            pygame.draw.circle(surface, PATH, pts[-1], lay.px(6))
        surface.set_clip(old)
        if self._n:
            n, temp = self._n[-1], self._t[-1]
            tc = float(self.tc(n))
            self._readout(surface, lay, i18n.t("chart.readout_path", n=n, t=_g3(temp), tc=_g3(tc)))
