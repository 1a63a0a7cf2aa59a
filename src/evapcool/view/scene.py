"""The applet's 640 x 672 scene: borders, title, cup, atoms, thermometer, messages.

Everything is laid out in logical pixels (the original's positions and colours, SPEC
section 1) and drawn through a `Pen`, at the size it is seen: a scene at 1.5x or 2x
has 1.5x or 2x lines, atoms and letters, not a blown-up bitmap. Overlays (help, high
scores, settings, name entry), messages and notices are drawn here from plain data.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pygame

from evapcool import i18n
from evapcool.game.highscores import Entry, format_seconds
from evapcool.game.rules import Game
from evapcool.view.condensate import Condensate, draw_condensate
from evapcool.view.fonts import baseline, text_size
from evapcool.view.pen import Pen
from evapcool.view.screen import (
    BORDER_BOTTOM,
    BORDER_LEFT,
    BORDER_RIGHT,
    BORDER_TOP,
    WINDOW,
    ScreenMap,
)
from evapcool.view.sprites import draw_atoms
from evapcool.view.text_input import TextInput
from evapcool.view.theme import DARK, Theme

SCENE_SIZE = WINDOW
PLAY_RECT = pygame.Rect(
    BORDER_LEFT,
    BORDER_TOP,
    SCENE_SIZE[0] - BORDER_LEFT - BORDER_RIGHT,
    SCENE_SIZE[1] - BORDER_TOP - BORDER_BOTTOM,
)
PAUSE_RECT = pygame.Rect(64, 592, 64, 64)
RESTART_RECT = pygame.Rect(144, 592, 64, 64)
#: "Save this run" (issue 48): a small button in the bottom border's left corner.
SAVE_RUN_RECT = pygame.Rect(6, 604, 40, 40)
SLIDER_RECT = pygame.Rect(240, 611, 272, 8)
KNOB_RADIUS = 10

# The original's colours (SPEC 1): the dark theme's (view/theme.py holds both themes).
BACKGROUND = DARK.background
BORDER = DARK.border
CUP_COLOR = DARK.cup
CUP_WIDTH = DARK.cup_width
TEXT = DARK.text
SHADOW = DARK.shadow
MERCURY = DARK.mercury
GLASS = DARK.glass
ACCENT = (250, 215, 40)
OVERLAY_SHADE = (10, 10, 30, 225)
#: The high-score table hides the cup under it: the rows must not compete with the gas (issue 25).
TABLE_SHADE = (10, 10, 30, 255)
NOTICE_SHADE = (120, 20, 20, 235)
#: A notice's colour: news (a code copied, settings saved) calm, a problem the warning red.
NEWS_SHADE = (25, 55, 95, 235)
NOTICE_SHADES = {False: NEWS_SHADE, True: NOTICE_SHADE}

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

#: "Score: N" and the other big messages sit at the top of the play area, so the
#: condensate below and any panel under them (name box, high scores) leave them in view.
MESSAGE_Y = PLAY_RECT.top + 62
#: Panels shown under a message start here.
UNDER_MESSAGE = PLAY_RECT.top + 150
#: The win screen's replay-code button (key C too): a strip under the cup's lowest point,
#: so the condensate stays in view.
REPLAY_RECT = pygame.Rect(PLAY_RECT.left + 12, PLAY_RECT.bottom - 27, PLAY_RECT.width - 24, 25)


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


def fit_size(text: str, size: int, width: float, bold: bool = False, least: int = 12) -> int:
    """The largest size up to `size` (at least `least`) at which text is no wider than width."""
    while size > least and text_size(text, size, bold)[0] > width:
        size -= 1
    return size


def _shadowed(
    pen: Pen, text: str, size: int, center: tuple[float, float], theme: Theme = DARK
) -> pygame.Rect:
    size = fit_size(text, size, PLAY_RECT.width - 16, True, size // 2)
    w, h = text_size(text, size, True)
    _band(pen, (center[0] - w / 2 - 8, center[1] - h / 2 - 2, w + 16, h + 4), theme)
    pen.text(text, size, theme.shadow, True, center=(center[0] + 3, center[1] + 3))
    return pen.text(text, size, theme.text, True, center=center)


def _band(pen: Pen, rect: tuple[float, float, float, float], theme: Theme) -> None:
    """The theme's band behind a message over the play area: the gas never sits behind its
    letters (7:1 against the band)."""
    _shade(pen, pygame.Rect(*(round(v) for v in rect)), theme.message_band)


def _shade(pen: Pen, rect: pygame.Rect, color: tuple[int, int, int, int]) -> pygame.Rect:
    """A translucent fill of a logical rect; returns its pixels."""
    r = pen.rect(rect)
    shade = pygame.Surface(r.size, pygame.SRCALPHA)
    shade.fill(color)
    pen.surface.blit(shade, r)
    return r


def to_pixels(pen: Pen, sim_to_screen, xy: np.ndarray) -> np.ndarray:
    """Trap coordinates to the pen's pixels (float)."""
    return np.asarray(sim_to_screen(xy), dtype=float) * pen.scale + np.array(pen.origin)


class Scene:
    """Draws the game in the 640 x 672 logical scene through a Pen."""

    def __init__(self, theme: Theme = DARK) -> None:
        #: The colours drawn with (settings, --theme): changed between frames at will.
        self.theme = theme
        self._cup_key: tuple[float, ...] | None = None
        self._cup_inner: list[tuple[float, float]] = []
        self._cup_outer: list[tuple[float, float]] = []
        self.condensate = Condensate()
        #: The condensate's fade-in at the last draw (0 before the win, up to 1).
        self.fade = 0.0
        self._atom_layer: pygame.Surface | None = None
        self._help_cache: dict[tuple[object, ...], _HelpFit] = {}

    # -- the parts --------------------------------------------------------------------
    def draw(self, pen: Pen, game: Game, t: float = 0.0) -> None:
        """Background, cup, atoms, borders, title, thermometer and status texts.

        t: animation clock in seconds (drives the condensate's fade and pulse).
        """
        pen.fill(self.theme.background, PLAY_RECT)
        with pen.clip(PLAY_RECT):  # escaping atoms slide under the borders
            self.draw_cup(pen, game)
            self.draw_atoms(pen, game, t)
        self.draw_borders(pen)
        self.draw_thermometer(pen, game)
        self.draw_status(pen, game)

    def draw_borders(self, pen: Pen, title: str | None = None) -> None:
        w, h = SCENE_SIZE
        for rect in (
            (0, 0, w, BORDER_TOP),
            (0, h - BORDER_BOTTOM, w, BORDER_BOTTOM),
            (0, 0, BORDER_LEFT, h),
            (w - BORDER_RIGHT, 0, BORDER_RIGHT, h),
        ):
            pen.fill(self.theme.border, rect)
        shown = i18n.t("app.title") if title is None else title
        size = fit_size(shown, 40, TITLE_WIDTH, least=20)
        pen.text(shown, size, self.theme.text, center=(w // 2, BORDER_TOP // 2 + 1))

    def _cup_points(self, game: Game) -> tuple[list, list]:
        sim = game.sim
        screen = ScreenMap.of(sim)
        radius = screen.origin_lift
        width = self.theme.cup_width
        key = (sim.trap_height, sim.curvature, screen, width)
        if key != self._cup_key:
            x_rim = sim.rim_half_width
            inner = screen.to_screen(cup_outline(sim.curvature, x_rim, radius))
            outer = screen.to_screen(cup_outline(sim.curvature, x_rim, radius + width))
            self._cup_inner = [tuple(p) for p in inner.tolist()]
            self._cup_outer = [tuple(p) for p in outer.tolist()]
            self._cup_key = key
        return self._cup_inner, self._cup_outer

    def draw_cup(self, pen: Pen, game: Game) -> None:
        """A black band (6 px, the projector's 10) whose inner edge is where atom edges touch
        the wall."""
        inner, outer = self._cup_points(game)
        color = self.theme.cup
        pen.polygon(color, inner + outer[::-1])
        pen.aalines(color, False, inner)
        pen.aalines(color, False, outer)

    def draw_atoms(self, pen: Pen, game: Game, t: float = 0.0) -> None:
        """Atoms; after the win the trapped ones fade out under the condensate."""
        sim = game.sim
        s = pen.scale
        to_screen = ScreenMap.of(sim).to_screen
        look = {"color": self.theme.atom, "rim": self.theme.atom_rim}
        if sim.n_escaped:
            xy = to_pixels(pen, to_screen, sim.escaped_positions)
            draw_atoms(pen.surface, xy, sim.escaped_radii * s, **look)
        fade = self.fade = self.condensate.update(sim, t)
        if sim.n_trapped and fade <= 0.0:
            draw_atoms(pen.surface, to_pixels(pen, to_screen, sim.positions), sim.radii * s, **look)
        elif sim.n_trapped and fade < 1.0:
            # Sprites carry per-pixel alpha, so dim them as one layer with a surface alpha.
            play = pen.rect(PLAY_RECT)
            if self._atom_layer is None or self._atom_layer.get_size() != play.size:
                self._atom_layer = pygame.Surface(play.size, pygame.SRCALPHA)
            layer = self._atom_layer
            layer.fill((0, 0, 0, 0))
            xy = to_pixels(pen, to_screen, sim.positions) - np.array(play.topleft)
            draw_atoms(layer, xy, sim.radii * s, **look)
            layer.set_alpha(round(255 * (1.0 - fade)))
            pen.surface.blit(layer, play)
        if fade > 0.0:
            draw_condensate(pen.surface, sim, lambda xy: to_pixels(pen, to_screen, xy), t, fade)

    def draw_thermometer(self, pen: Pen, game: Game) -> None:
        sim, theme = game.sim, self.theme
        thick = 2.0 if theme.glass_edge is not None else 1.0  # the projector's lines
        tube = pygame.Rect(0, 0, TUBE_WIDTH, BULB_CENTER[1] - TUBE_TOP)
        tube.midtop = (THERMO_X, TUBE_TOP)
        if theme.glass_edge is not None:  # white glass on a light border needs an outline
            pen.box(theme.glass_edge, tube.inflate(4, 4), border_radius=TUBE_WIDTH // 2 + 2)
            pen.circle(theme.glass_edge, BULB_CENTER, BULB_RADIUS + 2)
        pen.box(theme.glass, tube, border_radius=TUBE_WIDTH // 2)
        pen.circle(theme.glass, BULB_CENTER, BULB_RADIUS)
        pen.circle(theme.mercury, BULB_CENTER, BULB_RADIUS - 5)
        top = scale_row(mercury_fraction(sim.temperature, sim.initial_temperature))
        column = pygame.Rect(0, 0, MERCURY_WIDTH, BULB_CENTER[1] - top)
        column.midtop = (THERMO_X, top)
        pen.fill(theme.mercury, column)
        # Tick marks every tenth of the scale, then the critical temperature.
        for k in range(11):
            y = scale_row(k / 10)
            pen.line(theme.ticks, (tube.right - 6, y), (tube.right - 1, y), thick)
        tc = scale_row(mercury_fraction(sim.critical_temperature, sim.initial_temperature))
        pen.line(theme.tc_line, (tube.left - 6, tc), (tube.right + 2, tc), 2 * thick)
        size = round(26 * theme.text_scale)
        pen.text("Tc", size, theme.text, thick > 1, midright=(tube.left - 8, tc))
        pen.text("T", size, theme.text, thick > 1, midbottom=(THERMO_X, TUBE_TOP - 2))

    def draw_status(self, pen: Pen, game: Game) -> None:
        speed = game.speed
        shown = i18n.number(speed) if speed >= 1 else f"1/{i18n.number(1 / speed)}"
        text = i18n.t("status.speed", speed=shown)
        theme = self.theme
        bold = theme.text_scale > 1
        hint = i18n.t("status.help_hint")
        size = fit_size(text, round(22 * theme.text_scale), STATUS_WIDTH, bold)
        pen.text(text, size, theme.text, bold, midleft=(10, BORDER_TOP // 2))
        size = fit_size(hint, round(22 * theme.text_scale), STATUS_WIDTH, bold)
        pen.text(hint, size, theme.text, bold, midright=(SCENE_SIZE[0] - 10, BORDER_TOP // 2))

    # -- messages over the play area ------------------------------------------------------
    def draw_score(self, pen: Pen, score: int) -> pygame.Rect:
        """'Score: N' in large text at the top of the play area (the win); its pixels."""
        theme = self.theme
        r = _shadowed(
            pen, i18n.t("win.score_big", n=score), 84, (PLAY_RECT.centerx, MESSAGE_Y), theme
        )
        text = i18n.t("win.condensed")
        size = fit_size(text, 30, PLAY_RECT.width - 16, True, 18)
        self._lines(pen, [text], size, MESSAGE_Y + 58 - size // 2, size + 4)
        return r

    def _lines(self, pen: Pen, lines: Sequence[str], size: int, top: float, step: int) -> None:
        """Centred bold lines over the play area, on the theme's band."""
        if not lines:
            return
        width = max(text_size(line, size, True)[0] for line in lines)
        cx = PLAY_RECT.centerx
        _band(pen, (cx - width / 2 - 8, top - 4, width + 16, step * len(lines) + 6), self.theme)
        for k, line in enumerate(lines):
            pen.text(line, size, self.theme.text, True, midtop=(cx, top + step * k))

    def draw_too_few(self, pen: Pen, reason: str) -> None:
        """The gas can no longer condense: say why and offer a restart."""
        cx = PLAY_RECT.centerx
        _shadowed(pen, i18n.t("lose.too_few"), 52, (cx, MESSAGE_Y), self.theme)
        width = PLAY_RECT.width - 40
        lines = [*wrap(reason, 26, width, True), *wrap(i18n.t("lose.press_r"), 26, width, True)]
        self._lines(pen, lines, 26, MESSAGE_Y + 48 - 15, 30)

    def draw_start_hint(self, pen: Pen) -> None:
        lines = wrap(i18n.t("start.press_space"), 28, PLAY_RECT.width - 24, True)
        self._lines(pen, lines, 28, PLAY_RECT.top + 40 - 15, 30)

    def _frame(
        self, pen: Pen, rect: pygame.Rect, shade: tuple[int, int, int, int] = OVERLAY_SHADE
    ) -> None:
        """A dark panel (translucent unless shade says otherwise) with the accent border."""
        _shade(pen, rect, shade)
        pen.box(ACCENT, rect, width=2, border_radius=4)

    def _overlay(
        self,
        pen: Pen,
        title: str,
        height: int,
        top: int | None = None,
        shade: tuple[int, int, int, int] = OVERLAY_SHADE,
        bottom: int = PLAY_RECT.bottom,
    ) -> pygame.Rect:
        """A framed panel over the play area (centred, or from `top` down to at most
        `bottom`); returns it."""
        room = bottom - 4 - (PLAY_RECT.top + 4 if top is None else top)
        panel = pygame.Rect(0, 0, PLAY_RECT.width - 24, min(height, room))
        panel.centerx = PLAY_RECT.centerx
        if top is None:
            panel.centery = PLAY_RECT.centery
        else:
            panel.top = top
        self._frame(pen, panel, shade)
        size = fit_size(title, 34, panel.width - 16, True, 20)
        pen.text(title, size, ACCENT, True, midtop=(panel.centerx, panel.top + 12))
        return panel

    def draw_help(
        self, pen: Pen, rows: list[tuple[str, str]], footer: Sequence[str] = ()
    ) -> pygame.Rect:
        """A panel listing (keys, what they do), then footer lines (the frame rate)."""
        # Rows shrink a little when there are many, so the list always fits; a long
        # description wraps onto rows of its own (a longer language, a narrow window).
        # Finding that size measures every row at every size: done once per list of rows,
        # the rows' images drawn once too (text_image's cache), so an open help costs
        # a frame little more than the blits.
        key = (tuple(rows), len(footer), i18n.active().locale, i18n.is_rtl())
        fitted = self._help_cache.get(key)
        if fitted is None:
            if len(self._help_cache) > 8:
                self._help_cache.clear()
            fitted = self._help_cache[key] = _HelpFit.of(rows, footer)
        size, step = fitted.size, fitted.step
        lines = [row for line in footer for row in wrap(line, size, HELP_WIDTH)]
        n = len(fitted.rows) + len(lines)
        panel = self._overlay(pen, i18n.t("controls.title"), 64 + step * n)
        col = panel.left + 18 + fitted.keys_width
        for k, (keys, what) in enumerate(fitted.rows):
            y = panel.top + 52 + step * k
            # Both on one baseline: a Latin key name beside a Japanese or Arabic description
            # comes from another font, whose letters sit lower in their image.
            line = max(baseline(keys, size, True), baseline(what, size))
            # Right to left: the keys at the right, their descriptions right-aligned beside.
            at = y + line - baseline(keys, size, True)
            pen.text(keys, size, ACCENT, True, **_start(panel, panel.left + 18, at))
            pen.text(what, size, TEXT, **_start(panel, col, y + line - baseline(what, size)))
        for k, row in enumerate(lines):
            y = panel.top + 56 + step * (len(fitted.rows) + k)
            pen.text(row, size, (190, 220, 255), **_start(panel, panel.left + 18, y))
        return panel

    def draw_table(
        self,
        pen: Pen,
        entries: list[Entry],
        highlight: int | None = None,
        footer: Sequence[str] = (),
        top: int | None = None,
        bottom: int = PLAY_RECT.bottom,
    ) -> pygame.Rect:
        """The high-score table; row `highlight` (1-based) stands out; footer lines below.

        top: put the panel's top edge there (under the score) and fit the rows below it;
        bottom: keep it above there (the win screen's replay button).
        """
        rows = max(1, len(entries))
        footer = [row for line in footer for row in wrap(line, 24, PLAY_RECT.width - 56, True)]
        room = bottom - 4 - (PLAY_RECT.top + 4 if top is None else top)
        step = max(20, min(30, (room - 96 - 28 * len(footer)) // rows))
        height = 96 + step * rows + 28 * len(footer)
        panel = self._overlay(pen, i18n.t("scores.title"), height, top, TABLE_SHADE, bottom)
        cols = (panel.left + 16, panel.left + 50, panel.left + 222, panel.left + 292)
        y = panel.top + 54
        heads = ("table.rank", "table.name", "table.atoms", "table.time")
        # Right to left: the columns from the right (rank at the right, date at the left).
        rtl = i18n.is_rtl()
        for x, head, room in zip(cols, heads, TABLE_HEADS[:4], strict=True):
            text = i18n.t(head)
            pen.text(text, fit_size(text, 22, room, True), ACCENT, True, **_start(panel, x, y))
        date = i18n.t("table.date")
        size = fit_size(date, 22, TABLE_HEADS[-1], True)
        date_at = {"topleft": (panel.left + 16, y)} if rtl else {"topright": (panel.right - 16, y)}
        pen.text(date, size, ACCENT, True, **date_at)
        if not entries:
            pen.text(i18n.t("scores.empty"), 24, TEXT, **_start(panel, cols[1], y + 30))
        size = min(24, step - 4)
        name_width = cols[2] - cols[1] - 8
        for k, e in enumerate(entries):
            y = panel.top + 84 + step * k
            mine = highlight == k + 1
            color = ACCENT if mine else TEXT
            time = format_seconds(e.seconds).replace(".", i18n.decimal_mark())
            cells = (i18n.number(k + 1), e.name, i18n.number(e.score), time)
            for x, cell in zip(cols, cells, strict=True):
                # A long name is cut at its column rather than running into the score.
                left = panel.left + panel.right - x - name_width if rtl else x
                with pen.clip(pygame.Rect(left, y - 4, name_width, step + 4)):
                    pen.text(cell, size, color, mine, **_start(panel, x, y))
            date_at = (
                {"topleft": (panel.left + 16, y + 1)}
                if rtl
                else {"topright": (panel.right - 16, y + 1)}
            )
            pen.text(e.date[:10], min(22, size), color, **date_at)
        y = panel.top + 84 + step * rows + 8
        for line in footer:
            pen.text(line, 24, ACCENT, True, midtop=(panel.centerx, y))
            y += 28
        return panel

    def draw_settings(
        self, pen: Pen, rows: list[tuple[str, str]], selected: int, footer: Sequence[str] = ()
    ) -> pygame.Rect:
        """The settings screen: (label, value) rows, the selected one marked."""
        footer = [row for line in footer for row in wrap(line, 22, PLAY_RECT.width - 48)]
        panel = self._overlay(
            pen, i18n.t("settings.title"), 110 + 40 * len(rows) + 28 * len(footer)
        )
        for k, (label, value) in enumerate(rows):
            y = panel.top + 60 + 40 * k
            rtl = i18n.is_rtl()
            if k == selected:
                pen.box((60, 60, 110), (panel.left + 8, y - 6, panel.w - 16, 34), 0, 4)
                pen.text("<" if rtl else ">", 26, ACCENT, True, **_start(panel, panel.left + 14, y))
            shown = f"< {value} >" if k == selected else value
            room = SETTING_ROW - text_size(f"< {value} >", 24, True)[0]
            size = fit_size(label, 24, room, k == selected)
            pen.text(label, size, TEXT, k == selected, **_start(panel, panel.left + 34, y))
            # The value at the row's other end: the left one in a right-to-left language.
            end = {"topleft": (panel.left + 16, y)} if rtl else {"topright": (panel.right - 16, y)}
            pen.text(shown, 24, ACCENT, True, **end)
        y = panel.top + 72 + 40 * len(rows)
        for line in footer:
            pen.text(line, 22, TEXT, midtop=(panel.centerx, y))
            y += 28
        return panel

    def draw_name_entry(self, pen: Pen, box: TextInput, prompt: str) -> pygame.Rect:
        """Under the score: the prompt, the name being typed and its length; the field."""
        frame = pygame.Rect(PLAY_RECT.left + 30, UNDER_MESSAGE, PLAY_RECT.width - 60, 136)
        self._frame(pen, frame)
        size = fit_size(prompt, 26, frame.width - 20, True)
        pen.text(prompt, size, ACCENT, True, midtop=(frame.centerx, frame.top + 10))
        field = pygame.Rect(frame.left + 20, frame.top + 40, frame.width - 40, 44)
        box.draw(pen, field, 32)
        count = f"{len(box.text)}/{box.max_length}"
        full = len(box.text) >= box.max_length
        # The count at the line's end, the keys' hint at its start (mirrored right to left).
        below = field.bottom + 8
        rtl = i18n.is_rtl()
        end = {"topleft": (field.left, below)} if rtl else {"topright": (field.right, below)}
        shown = i18n.t("win.name_full", count=count) if full else count
        pen.text(shown, 22, ACCENT if full else TEXT, full, **end)
        pen.text(i18n.t("win.store_or_skip"), 22, TEXT, **_start(field, field.left, below))
        return field

    def draw_replay_button(self, pen: Pen, label: str, hover: bool) -> pygame.Rect:
        """The win screen's 'Replay code: C copies it' button; returns its pixels."""
        self._frame(pen, REPLAY_RECT, (40, 40, 90, 235) if hover else TABLE_SHADE)
        size = fit_size(label, 20, REPLAY_RECT.width - 16, True)
        pen.text(label, size, ACCENT, True, center=REPLAY_RECT.center)
        return pen.rect(REPLAY_RECT)

    def draw_notices(
        self, pen: Pen, notices: Sequence[tuple[str, bool]], bottom: int = PLAY_RECT.bottom
    ) -> pygame.Rect | None:
        """Toasts at the bottom of the play area (or above `bottom`), wrapped to its width,
        each (text, problem?): a problem on the warning red, news on the calm blue;
        returns their box."""
        if not notices:
            return None
        width = PLAY_RECT.width - 32
        wrapped = [(row, bad) for text, bad in notices for row in wrap(text, 22, width)]
        box = pygame.Rect(0, 0, PLAY_RECT.width - 12, 12 + 20 * len(wrapped))
        box.midbottom = (PLAY_RECT.centerx, bottom - 6)
        # Each toast's band: its rows, the box's 6 px margins with the first and last.
        edges, rows = [box.top], 0
        for text, _ in notices:
            rows += len(wrap(text, 22, width))
            edges.append(box.top + 6 + 20 * rows)
        edges[-1] = box.bottom
        for (_, bad), top, end in zip(notices, edges, edges[1:], strict=False):
            _shade(pen, pygame.Rect(box.left, top, box.width, end - top), NOTICE_SHADES[bad])
        for k, (row, _) in enumerate(wrapped):
            pen.text(row, 22, TEXT, **_start(box, box.left + 10, box.top + 6 + 20 * k))
        return box


def _start(panel: pygame.Rect, x: float, y: float) -> dict[str, tuple[float, float]]:
    """Where a line starts: at x, or, in a right-to-left language, at its mirror in the
    panel, anchored by the line's right end."""
    if i18n.is_rtl():
        return {"topright": (panel.left + panel.right - x, y)}
    return {"topleft": (x, y)}


#: The status texts' room at each end of the top border, and the title's between them.
STATUS_WIDTH = 136
TITLE_WIDTH = SCENE_SIZE[0] - 2 * (STATUS_WIDTH + 18)
#: The high-score table's column headers: room for each (#, name, atoms, time, date).
TABLE_HEADS = (32, 164, 62, 80, 100)
#: A settings row: its label and its value side by side.
SETTING_ROW = PLAY_RECT.width - 24 - 34 - 16 - 12
#: The help panel's width for keys and descriptions (inside its margins), logical px.
HELP_WIDTH = PLAY_RECT.width - 24 - 36


@dataclass(frozen=True)
class _HelpFit:
    """The help's rows wrapped at the text size that fits them all, and their spacing."""

    size: int
    step: int
    rows: list[tuple[str, str]]
    keys_width: int

    @classmethod
    def of(cls, rows: list[tuple[str, str]], footer: Sequence[str]) -> _HelpFit:
        size, out, lines = _help_rows(rows, footer)
        n = len(out) + len(lines)
        step = max(size + 2, min(27, (PLAY_RECT.height - 76) // max(1, n)))
        keys = max(text_size(k, size, True)[0] for k, _ in out) + 16
        return cls(size, step, out, keys)


def _help_rows(
    rows: list[tuple[str, str]], footer: Sequence[str]
) -> tuple[int, list[tuple[str, str]], list[str]]:
    """The text size and the help's rows and footer wrapped to the panel at that size."""
    for size in range(24, 11, -1):
        keys = max(text_size(k, size, True)[0] for k, _ in rows) + 16
        out = [
            (keys_text if i == 0 else "", part)
            for keys_text, what in rows
            for i, part in enumerate(wrap(what, size, HELP_WIDTH - keys))
        ]
        lines = [row for line in footer for row in wrap(line, size, HELP_WIDTH)]
        step = (PLAY_RECT.height - 76) // max(1, len(out) + len(lines))
        if size <= step - 2 or size == 12:
            return size, out, lines
    raise AssertionError("unreachable")


def _pieces(text: str, size: int, width: float, bold: bool) -> list[str]:
    """The words of text; a word wider than the width (Chinese, Japanese: no spaces) is cut
    into runs of characters that fit."""
    out: list[str] = []
    for word in text.split():
        while text_size(word, size, bold)[0] > width and len(word) > 1:
            k = len(word) - 1
            while k > 1 and text_size(word[:k], size, bold)[0] > width:
                k -= 1
            out.append(word[:k])
            word = word[k:]
        out.append(word)
    return out


def wrap(text: str, size: int, width: float, bold: bool = False) -> list[str]:
    """Greedy word wrap to a logical width (a word wider than it is cut where it must be)."""
    whole = " ".join(text.split())
    if text_size(whole, size, bold)[0] <= width:  # one measure for a line that fits
        return [whole]
    rows: list[str] = []
    row = ""
    for word in _pieces(text, size, width, bold):
        candidate = f"{row} {word}" if row else word
        if row and text_size(candidate, size, bold)[0] > width:
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
