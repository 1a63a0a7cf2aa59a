"""The applet's 640 x 672 scene: borders, title, cup, atoms, thermometer, messages.

Everything is drawn in logical pixels on the surface handed in (the app scales
that to the window). Positions and colours follow the original (SPEC section 1).
Overlays (help, high scores, settings, name entry) and the notice toasts are
drawn here too, from plain data the app hands in.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache

import numpy as np
import pygame

from evapcool.game.highscores import Entry, format_seconds
from evapcool.game.rules import Game
from evapcool.physics.simulation import (
    BORDER_BOTTOM,
    BORDER_LEFT,
    BORDER_RIGHT,
    BORDER_TOP,
    cup_vertex,
)
from evapcool.view.condensate import Condensate, draw_condensate
from evapcool.view.fonts import font as _font
from evapcool.view.sprites import draw_atoms
from evapcool.view.text_input import TextInput

SCENE_SIZE = (640, 672)
PLAY_RECT = pygame.Rect(
    BORDER_LEFT,
    BORDER_TOP,
    SCENE_SIZE[0] - BORDER_LEFT - BORDER_RIGHT,
    SCENE_SIZE[1] - BORDER_TOP - BORDER_BOTTOM,
)
PAUSE_RECT = pygame.Rect(64, 592, 64, 64)
RESTART_RECT = pygame.Rect(144, 592, 64, 64)
SLIDER_RECT = pygame.Rect(240, 611, 272, 8)
KNOB_RADIUS = 10

BACKGROUND = (159, 159, 159)
BORDER = (79, 79, 79)
CUP_COLOR = (0, 0, 0)
CUP_WIDTH = 6
TEXT = (255, 255, 255)
SHADOW = (30, 30, 30)
MERCURY = (220, 20, 20)
GLASS = (255, 255, 255)
ACCENT = (250, 215, 40)
OVERLAY_SHADE = (10, 10, 30, 225)
NOTICE_SHADE = (120, 20, 20, 235)

# Thermometer in the right border. The mercury top sits at row
# SCALE_ZERO - f (SCALE_ZERO - SCALE_FULL), f = T / (1.2 T0) clipped to [0, 1].
THERMO_X = BORDER_LEFT + PLAY_RECT.width + BORDER_RIGHT // 2  # 592
TUBE_WIDTH = 20
TUBE_TOP = 72
SCALE_FULL = 88
SCALE_ZERO = 572
BULB_CENTER = (THERMO_X, 598)
BULB_RADIUS = 20
MERCURY_WIDTH = 10
THERMO_MAX_FRACTION = 1.2  # full scale is 1.2 x the starting temperature


def mercury_fraction(temperature: float, initial_temperature: float) -> float:
    """Height of the mercury as a fraction of the scale: T / (1.2 T0), clipped."""
    if initial_temperature <= 0.0:
        return 0.0
    f = temperature / (THERMO_MAX_FRACTION * initial_temperature)
    return min(1.0, max(0.0, f))


def scale_row(fraction: float) -> int:
    """Pixel row of a thermometer reading (0 = empty, 1 = full scale)."""
    return round(SCALE_ZERO - fraction * (SCALE_ZERO - SCALE_FULL))


def cup_outline(
    curvature: float, rim_half_width: float, offset: float, samples: int = 161
) -> np.ndarray:
    """(samples, 2) trap-coordinate points at distance offset outside the wall y = a x^2.

    The wall is the one centres bounce on, so the curve at offset R is where a
    disk's edge touches; it is cut at the rim along the normal.
    """
    x = np.linspace(-rim_half_width, rim_half_width, samples)
    slope = 2.0 * curvature * x
    norm = np.sqrt(1.0 + slope * slope)
    return np.column_stack((x + offset * slope / norm, curvature * x * x - offset / norm))


@lru_cache(maxsize=256)
def _text(text: str, size: int, color: tuple[int, int, int], bold: bool = False) -> pygame.Surface:
    return _font(size, bold).render(text, True, color)


def _shadowed(surface: pygame.Surface, text: str, size: int, center: tuple[int, int]) -> None:
    for color, (dx, dy) in ((SHADOW, (3, 3)), (TEXT, (0, 0))):
        image = _text(text, size, color, True)
        surface.blit(image, image.get_rect(center=(center[0] + dx, center[1] + dy)))


class Scene:
    """Draws the game onto a 640 x 672 logical surface."""

    def __init__(self, surface: pygame.Surface) -> None:
        if surface.get_size() != SCENE_SIZE:
            raise ValueError(f"the scene surface must be {SCENE_SIZE}, not {surface.get_size()}")
        self.surface = surface
        self._cup_key: tuple[float, ...] | None = None
        self._cup_inner: list[tuple[float, float]] = []
        self._cup_outer: list[tuple[float, float]] = []
        self.condensate = Condensate()
        #: The condensate's fade-in at the last draw (0 before the win, up to 1).
        self.fade = 0.0
        self._atom_layer: pygame.Surface | None = None

    # -- the parts --------------------------------------------------------------------
    def draw(self, game: Game, t: float = 0.0) -> None:
        """Background, cup, atoms, borders, title, thermometer and status texts.

        t: animation clock in seconds (drives the condensate's fade and pulse).
        """
        s = self.surface
        s.fill(BACKGROUND, PLAY_RECT)
        s.set_clip(PLAY_RECT)  # escaping atoms slide under the borders
        self.draw_cup(game)
        self.draw_atoms(game, t)
        s.set_clip(None)
        self.draw_borders()
        self.draw_thermometer(game)
        self.draw_status(game)

    def draw_borders(self) -> None:
        s = self.surface
        w, h = SCENE_SIZE
        for rect in (
            (0, 0, w, BORDER_TOP),
            (0, h - BORDER_BOTTOM, w, BORDER_BOTTOM),
            (0, 0, BORDER_LEFT, h),
            (w - BORDER_RIGHT, 0, BORDER_RIGHT, h),
        ):
            s.fill(BORDER, rect)
        title = _text("Evaporation cooling", 40, TEXT)
        s.blit(title, title.get_rect(center=(w // 2, BORDER_TOP // 2 + 1)))

    def _cup_points(self, game: Game) -> tuple[list, list]:
        sim = game.sim
        radius = cup_vertex(sim.window)[1] - sim.screen_origin[1]
        key = (sim.trap_height, sim.curvature, radius, *sim.screen_origin)
        if key != self._cup_key:
            x_rim = sim.rim_half_width
            inner = sim.to_screen(cup_outline(sim.curvature, x_rim, radius))
            outer = sim.to_screen(cup_outline(sim.curvature, x_rim, radius + CUP_WIDTH))
            self._cup_inner = [tuple(p) for p in inner.tolist()]
            self._cup_outer = [tuple(p) for p in outer.tolist()]
            self._cup_key = key
        return self._cup_inner, self._cup_outer

    def draw_cup(self, game: Game) -> None:
        """A 6 px black band whose inner edge is where atom edges touch the wall."""
        inner, outer = self._cup_points(game)
        pygame.draw.polygon(self.surface, CUP_COLOR, inner + outer[::-1])
        pygame.draw.aalines(self.surface, CUP_COLOR, False, inner)
        pygame.draw.aalines(self.surface, CUP_COLOR, False, outer)

    def draw_atoms(self, game: Game, t: float = 0.0) -> None:
        """Atoms; after the win the trapped ones fade out under the condensate."""
        sim = game.sim
        if sim.n_escaped:
            draw_atoms(self.surface, sim.to_screen(sim.escaped_positions), sim.escaped_radii)
        fade = self.fade = self.condensate.update(sim, t)
        if sim.n_trapped and fade <= 0.0:
            draw_atoms(self.surface, sim.to_screen(sim.positions), sim.radii)
        elif sim.n_trapped and fade < 1.0:
            # Sprites carry per-pixel alpha, so dim them as one layer with a surface alpha.
            if self._atom_layer is None:
                self._atom_layer = pygame.Surface(PLAY_RECT.size, pygame.SRCALPHA)
            layer = self._atom_layer
            layer.fill((0, 0, 0, 0))
            draw_atoms(layer, sim.to_screen(sim.positions) - PLAY_RECT.topleft, sim.radii)
            layer.set_alpha(round(255 * (1.0 - fade)))
            self.surface.blit(layer, PLAY_RECT)
        if fade > 0.0:
            draw_condensate(self.surface, sim, sim.to_screen, t, fade)

    def draw_thermometer(self, game: Game) -> None:
        s = self.surface
        sim = game.sim
        tube = pygame.Rect(0, 0, TUBE_WIDTH, BULB_CENTER[1] - TUBE_TOP)
        tube.midtop = (THERMO_X, TUBE_TOP)
        pygame.draw.rect(s, GLASS, tube, border_radius=TUBE_WIDTH // 2)
        pygame.draw.circle(s, GLASS, BULB_CENTER, BULB_RADIUS)
        pygame.draw.circle(s, MERCURY, BULB_CENTER, BULB_RADIUS - 5)
        top = scale_row(mercury_fraction(sim.temperature, sim.initial_temperature))
        column = pygame.Rect(0, 0, MERCURY_WIDTH, BULB_CENTER[1] - top)
        column.midtop = (THERMO_X, top)
        s.fill(MERCURY, column)
        # Tick marks every tenth of the scale, then the critical temperature.
        for k in range(11):
            y = scale_row(k / 10)
            pygame.draw.line(s, (90, 90, 90), (tube.right - 5, y), (tube.right - 1, y))
        tc = scale_row(mercury_fraction(sim.critical_temperature, sim.initial_temperature))
        pygame.draw.line(s, (0, 0, 0), (tube.left - 6, tc), (tube.right + 2, tc), 2)
        label = _text("Tc", 26, TEXT)
        s.blit(label, label.get_rect(midright=(tube.left - 8, tc)))
        t_label = _text("T", 26, TEXT)
        s.blit(t_label, t_label.get_rect(midbottom=(THERMO_X, TUBE_TOP - 2)))

    def draw_status(self, game: Game) -> None:
        speed = game.speed
        text = f"speed {speed:g}x" if speed >= 1 else f"speed 1/{1 / speed:g}x"
        image = _text(text, 22, (220, 220, 220))
        self.surface.blit(image, image.get_rect(midleft=(10, BORDER_TOP // 2)))
        hint = _text("H: help", 22, (220, 220, 220))
        self.surface.blit(hint, hint.get_rect(midright=(SCENE_SIZE[0] - 10, BORDER_TOP // 2)))

    # -- messages over the play area ------------------------------------------------------
    def draw_score(self, score: int) -> None:
        """'Score: N' in large text over the play area (the win)."""
        _shadowed(self.surface, f"Score: {score}", 84, (PLAY_RECT.centerx, PLAY_RECT.top + 150))
        sub = _text("The gas has condensed!", 30, TEXT, True)
        self.surface.blit(sub, sub.get_rect(center=(PLAY_RECT.centerx, PLAY_RECT.top + 215)))

    def draw_empty(self) -> None:
        """Every atom has escaped: say so and offer a restart."""
        cx, y = PLAY_RECT.centerx, PLAY_RECT.top + 170
        _shadowed(self.surface, "All the atoms escaped!", 52, (cx, y))
        lines = ("Nothing left to cool.", "Press R or click restart to try again.")
        for k, line in enumerate(lines):
            image = _text(line, 30, TEXT, True)
            self.surface.blit(image, image.get_rect(center=(cx, y + 55 + 32 * k)))

    def draw_start_hint(self) -> None:
        image = _text("Press Space or click play to start", 28, TEXT, True)
        self.surface.blit(image, image.get_rect(center=(PLAY_RECT.centerx, PLAY_RECT.top + 40)))

    def _frame(self, rect: pygame.Rect) -> None:
        """A translucent dark panel with the accent border."""
        shade = pygame.Surface(rect.size, pygame.SRCALPHA)
        shade.fill(OVERLAY_SHADE)
        self.surface.blit(shade, rect)
        pygame.draw.rect(self.surface, ACCENT, rect, width=2, border_radius=4)

    def _overlay(self, title: str, height: int) -> pygame.Rect:
        """A translucent framed panel over the play area with a title; returns its rect."""
        panel = pygame.Rect(0, 0, PLAY_RECT.width - 24, min(height, PLAY_RECT.height - 8))
        panel.center = PLAY_RECT.center
        self._frame(panel)
        image = _text(title, 34, ACCENT, True)
        self.surface.blit(image, image.get_rect(midtop=(panel.centerx, panel.top + 12)))
        return panel

    def draw_help(self, rows: list[tuple[str, str]]) -> None:
        """A translucent panel listing (keys, what they do)."""
        # Rows shrink a little when there are many, so the list always fits.
        step = max(18, min(27, (PLAY_RECT.height - 70) // max(1, len(rows))))
        size = min(24, step - 2)
        panel = self._overlay("Controls", 60 + step * len(rows))
        col = panel.left + 18 + max(_text(k, size, TEXT, True).get_width() for k, _ in rows) + 16
        for k, (keys, what) in enumerate(rows):
            y = panel.top + 52 + step * k
            self.surface.blit(_text(keys, size, ACCENT, True), (panel.left + 18, y))
            self.surface.blit(_text(what, size, TEXT), (col, y))

    def draw_table(
        self, entries: list[Entry], highlight: int | None = None, footer: Sequence[str] = ()
    ) -> pygame.Rect:
        """The high-score table; row `highlight` (1-based) stands out; footer lines below."""
        panel = self._overlay("High scores", 100 + 30 * (max(1, len(entries)) + 1 + len(footer)))
        cols = (panel.left + 16, panel.left + 50, panel.left + 222, panel.left + 292)
        y = panel.top + 56
        for x, head in zip(cols, ("#", "name", "atoms", "time"), strict=True):
            self.surface.blit(_text(head, 22, ACCENT, True), (x, y))
        date_head = _text("date", 22, ACCENT, True)
        self.surface.blit(date_head, date_head.get_rect(topright=(panel.right - 16, y)))
        if not entries:
            image = _text("No scores yet: be the first!", 24, TEXT)
            self.surface.blit(image, (cols[1], y + 32))
        name_width = cols[2] - cols[1] - 8
        for k, e in enumerate(entries):
            y = panel.top + 88 + 30 * k
            mine = highlight == k + 1
            color = ACCENT if mine else TEXT
            cells = (f"{k + 1}", e.name, f"{e.score}", format_seconds(e.seconds))
            for x, cell in zip(cols, cells, strict=True):
                image = _text(cell, 24, color, mine)
                # A long name is cut at its column rather than running into the score.
                self.surface.blit(image, (x, y), pygame.Rect(0, 0, name_width, image.get_height()))
            date = _text(e.date[:10], 22, color)
            self.surface.blit(date, date.get_rect(topright=(panel.right - 16, y + 1)))
        y = panel.top + 88 + 30 * max(1, len(entries)) + 14
        for line in footer:
            image = _text(line, 24, ACCENT, True)
            self.surface.blit(image, image.get_rect(midtop=(panel.centerx, y)))
            y += 30
        return panel

    def draw_settings(
        self, rows: list[tuple[str, str]], selected: int, footer: Sequence[str] = ()
    ) -> pygame.Rect:
        """The settings screen: (label, value) rows, the selected one marked."""
        panel = self._overlay("Settings", 110 + 40 * len(rows) + 28 * len(footer))
        for k, (label, value) in enumerate(rows):
            y = panel.top + 60 + 40 * k
            if k == selected:
                pygame.draw.rect(
                    self.surface, (60, 60, 110), (panel.left + 8, y - 6, panel.w - 16, 34), 0, 4
                )
                self.surface.blit(_text(">", 26, ACCENT, True), (panel.left + 14, y))
            self.surface.blit(_text(label, 24, TEXT, k == selected), (panel.left + 34, y))
            v = _text(f"< {value} >" if k == selected else value, 24, ACCENT, True)
            self.surface.blit(v, v.get_rect(topright=(panel.right - 16, y)))
        y = panel.top + 72 + 40 * len(rows)
        for line in footer:
            image = _text(line, 22, TEXT)
            self.surface.blit(image, image.get_rect(midtop=(panel.centerx, y)))
            y += 28
        return panel

    def draw_name_entry(self, box: TextInput, prompt: str) -> pygame.Rect:
        """Below the score: the prompt and the name being typed; returns the text box."""
        frame = pygame.Rect(PLAY_RECT.left + 40, PLAY_RECT.top + 250, PLAY_RECT.width - 80, 120)
        self._frame(frame)
        image = _text(prompt, 26, ACCENT, True)
        self.surface.blit(image, image.get_rect(midtop=(frame.centerx, frame.top + 10)))
        field = pygame.Rect(frame.left + 20, frame.top + 40, frame.width - 40, 40)
        box.draw(self.surface, field, _font(32))
        hint = _text("Enter: store   Esc: skip", 22, TEXT)
        self.surface.blit(hint, hint.get_rect(midtop=(frame.centerx, field.bottom + 8)))
        return field

    def draw_notices(self, lines: list[str]) -> pygame.Rect | None:
        """Toasts at the bottom of the play area, wrapped to its width; returns their box."""
        if not lines:
            return None
        font = _font(22)
        width = PLAY_RECT.width - 32
        wrapped = [row for line in lines for row in _wrap(line, font, width)]
        box = pygame.Rect(0, 0, PLAY_RECT.width - 12, 12 + 20 * len(wrapped))
        box.midbottom = (PLAY_RECT.centerx, PLAY_RECT.bottom - 6)
        shade = pygame.Surface(box.size, pygame.SRCALPHA)
        shade.fill(NOTICE_SHADE)
        self.surface.blit(shade, box)
        for k, row in enumerate(wrapped):
            self.surface.blit(_text(row, 22, TEXT), (box.left + 10, box.top + 6 + 20 * k))
        return box


def _wrap(text: str, font: pygame.font.Font, width: int) -> list[str]:
    """Greedy word wrap to a pixel width (a word longer than the width gets its own row)."""
    rows: list[str] = []
    row = ""
    for word in text.split():
        candidate = f"{row} {word}" if row else word
        if row and font.size(candidate)[0] > width:
            rows.append(row)
            row = word
        else:
            row = candidate
    if row:
        rows.append(row)
    return rows or [""]


def scale_for(window: tuple[int, int], canvas: tuple[int, int]) -> tuple[float, pygame.Rect]:
    """Largest scale fitting canvas into window with the aspect kept, and where it goes."""
    s = min(window[0] / canvas[0], window[1] / canvas[1])
    w, h = max(1, math.floor(canvas[0] * s)), max(1, math.floor(canvas[1] * s))
    rect = pygame.Rect((window[0] - w) // 2, (window[1] - h) // 2, w, h)
    return s, rect
