"""Buttons and a slider for any pygame applet (nothing of the game in here).

Widgets hold their geometry (logical pixels) and state; the app's input machine
decides what an event means and calls them (`Slider.press`, `drag`, `release`,
`ToggleButton.toggle`...). `draw(pen, pointer)` draws a widget at the pen's
scale, its look following the pointer (idle, hover, held down).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import NamedTuple

import pygame

from evapcool.view.pen import Pen

Color = tuple[int, int, int]
#: A widget's images for a size in real pixels: (idle, hover, down), hover and down optional.
Looks = Callable[[int], Sequence[pygame.Surface]]

BLACK: Color = (0, 0, 0)
WHITE: Color = (255, 255, 255)
YELLOW: Color = (250, 215, 40)
LOOKS = ("idle", "hover", "down")


class Pointer(NamedTuple):
    """The mouse as widgets see it: where (logical pixels; None when elsewhere), held or not."""

    xy: tuple[float, float] | None = None
    down: bool = False


NO_POINTER = Pointer()


class Button:
    """A rectangular click target; drawn with `looks` at the pen's scale, or black."""

    def __init__(self, rect: pygame.Rect | Sequence[int], looks: Looks | None = None) -> None:
        self.rect = pygame.Rect(rect)
        self.looks = looks

    def hit(self, xy: tuple[float, float] | None) -> bool:
        """Whether a logical point is on the button (its bounding rectangle)."""
        return xy is not None and self.rect.collidepoint(xy)

    def look(self, pointer: Pointer) -> str:
        """'down' while held over the button, 'hover' when over it, else 'idle'."""
        if not self.hit(pointer.xy):
            return "idle"
        return "down" if pointer.down else "hover"

    def images(self, pen: Pen) -> Sequence[pygame.Surface]:
        return self.looks(pen.size(self.rect.w)) if self.looks else ()

    def draw(self, pen: Pen, pointer: Pointer = NO_POINTER) -> None:
        images = self.images(pen)
        if not images:
            pen.box(BLACK, self.rect)
            return
        k = LOOKS.index(self.look(pointer))
        pen.blit(images[min(k, len(images) - 1)], self.rect, "center")


class ToggleButton(Button):
    """An on/off button: `toggle()` flips it; drawn with the looks of its state."""

    def __init__(
        self,
        rect: pygame.Rect | Sequence[int],
        on_looks: Looks,
        off_looks: Looks,
        is_on: bool = False,
    ) -> None:
        super().__init__(rect, off_looks)
        self.on_looks, self.off_looks = on_looks, off_looks
        self.set_state(is_on)

    def set_state(self, is_on: bool) -> None:
        self.is_on = bool(is_on)
        self.looks = self.on_looks if self.is_on else self.off_looks

    def toggle(self) -> bool:
        self.set_state(not self.is_on)
        return self.is_on


class Slider:
    """A horizontal slider for values in [min_value, max_value].

    A press anywhere on the bar (a hit box as tall as the knob) moves the knob there
    and starts a drag; the knob then follows the pointer, even off the bar, until
    `release()`. A disabled slider ignores presses and draws its knob grey.

    follow: where the knob rests when no drag holds it (e.g. the game's trap height),
    read when asked; the slider owns its drag, and nobody writes the model's value back
    into it. Without follow the knob stays where `set_value` or the last drag left it.
    """

    def __init__(
        self,
        rect: pygame.Rect | Sequence[int],
        min_value: float,
        max_value: float,
        value: float | None = None,
        *,
        knob_radius: int = 10,
        label: str = "",
        text_color: Color = WHITE,
        bar_color: Color = WHITE,
        knob_color: Color = YELLOW,
        outline_color: Color = BLACK,
        follow: Callable[[], float] | None = None,
    ) -> None:
        if not max_value > min_value:
            raise ValueError("max_value must be greater than min_value")
        self.rect = pygame.Rect(rect)
        self.min_value = float(min_value)
        self.max_value = float(max_value)
        self.knob_radius = int(knob_radius)
        self.label = label
        self.text_color = text_color
        self.bar_color = bar_color
        self.knob_color = knob_color
        self.outline_color = outline_color
        self.sliding = False
        self.enabled = True
        self.follow = follow
        self._activation = 0.0
        self.set_value(self.min_value if value is None else value)

    # -- value <-> knob position -------------------------------------------------------
    def activation_at(self, x: float) -> float:
        """Activation in [0, 1] for a knob at logical x."""
        return min(1.0, max(0.0, (x - self.rect.left) / self.rect.width))

    def value_at(self, x: float) -> float:
        return self.min_value + self.activation_at(x) * (self.max_value - self.min_value)

    @property
    def activation(self) -> float:
        """Knob position in [0, 1]: the drag's while one holds it, else follow's value."""
        if self.sliding or self.follow is None:
            return self._activation
        return self._clamped(self.follow())

    @activation.setter
    def activation(self, a: float) -> None:
        self._activation = a

    def _clamped(self, value: float) -> float:
        span = self.max_value - self.min_value
        return min(1.0, max(0.0, (float(value) - self.min_value) / span))

    def knob_xy(self) -> tuple[float, float]:
        return (self.rect.left + self.activation * self.rect.width, self.rect.centery)

    @property
    def value(self) -> float:
        return self.min_value + self.activation * (self.max_value - self.min_value)

    def set_value(self, value: float) -> None:
        """Place the knob so the slider returns value (clamped to the range)."""
        self._activation = self._clamped(value)

    # -- the pointer ----------------------------------------------------------------------
    def hit_box(self) -> pygame.Rect:
        """As wide as the bar (plus the knob's overhang), as tall as the knob."""
        r = self.knob_radius
        return pygame.Rect(
            self.rect.left - r, self.rect.centery - r, self.rect.width + 2 * r, 2 * r + 1
        )

    def hit(self, xy: tuple[float, float] | None) -> bool:
        return xy is not None and self.hit_box().collidepoint(xy)

    def press(self, xy: tuple[float, float]) -> bool:
        """Start a drag if xy is on the slider (and it is enabled); True if it did."""
        if not (self.enabled and self.hit(xy)):
            return False
        self.sliding = True
        self.activation = self.activation_at(xy[0])
        return True

    def drag(self, xy: tuple[float, float]) -> None:
        if self.sliding:
            self.activation = self.activation_at(xy[0])

    def release(self) -> None:
        self.sliding = False

    # -- drawing ----------------------------------------------------------------------------
    def draw(self, pen: Pen, pointer: Pointer = NO_POINTER) -> None:
        pen.box(self.bar_color, self.rect, border_radius=3)
        pen.box(self.outline_color, self.rect, width=1, border_radius=3)
        if self.label:
            top = self.rect.bottom + self.knob_radius + 4
            pen.text(self.label, 24, self.text_color, midtop=(self.rect.centerx, top))
        hot = self.sliding or (self.enabled and self.hit(pointer.xy))
        knob = tuple(min(255, c + 30) for c in self.knob_color) if hot else self.knob_color
        if not self.enabled:
            knob = (170, 170, 170)
        center = self.knob_xy()
        pen.circle(knob, center, self.knob_radius)
        pen.circle(self.outline_color, center, self.knob_radius, width=2)
