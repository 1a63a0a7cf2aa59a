"""Immediate-mode buttons and a slider for any pygame applet (no game imports).

Every widget is driven by one call per frame, ``result = widget.control(mouse)``:
it reads the mouse, updates its state, draws itself on its surface and returns
its value (a click flag, a toggle state or the slider value).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import pygame

Color = tuple[int, int, int]

BLACK: Color = (0, 0, 0)
WHITE: Color = (255, 255, 255)
YELLOW: Color = (250, 215, 40)


class MouseState(NamedTuple):
    """The left mouse button this frame, in the widgets' surface coordinates."""

    xy: tuple[float, float]
    clicked: bool = False  # went down during this frame
    down: bool = False  # is held (or was pressed during this frame)


LOOKS = ("idle", "hover", "down")


class Button:
    """A rectangular click target drawn as a black rectangle; subclass for looks."""

    def __init__(self, surface: pygame.Surface, rect: pygame.Rect | Sequence[int]) -> None:
        self.surface = surface
        self.rect = pygame.Rect(rect)

    def check_mouse(self, mouse: MouseState) -> bool:
        """Whether the mouse is over the hit box (the bounding rectangle)."""
        return self.rect.collidepoint(mouse.xy)

    def is_active(self, mouse: MouseState) -> bool:
        """Clicked on this frame inside the hit box."""
        return mouse.clicked and self.check_mouse(mouse)

    def action(self) -> bool:
        return True

    def idle(self) -> bool:
        return False

    def look(self, mouse: MouseState) -> str:
        """'down' while pressed over the button, 'hover' when over it, else 'idle'."""
        if not self.check_mouse(mouse):
            return "idle"
        return "down" if mouse.down else "hover"

    def draw(self, mouse: MouseState) -> None:
        pygame.draw.rect(self.surface, BLACK, self.rect)

    def control(self, mouse: MouseState) -> bool:
        """Update from the mouse, draw, and return action() or idle()."""
        result = self.action() if self.is_active(mouse) else self.idle()
        self.draw(mouse)  # after the update, so the picture shows the new state
        return result


class ImageButton(Button):
    """A button drawn with an image per look (hover defaults to idle, down to hover)."""

    def __init__(
        self,
        surface: pygame.Surface,
        rect: pygame.Rect | Sequence[int],
        idle_image: pygame.Surface,
        hover_image: pygame.Surface | None = None,
        down_image: pygame.Surface | None = None,
    ) -> None:
        super().__init__(surface, rect)
        self.set_images(idle_image, hover_image, down_image)

    def set_images(
        self,
        idle_image: pygame.Surface,
        hover_image: pygame.Surface | None = None,
        down_image: pygame.Surface | None = None,
    ) -> None:
        self.idle_image = idle_image
        self.hover_image = hover_image or idle_image
        self.down_image = down_image or self.hover_image

    def image_for(self, look: str) -> pygame.Surface:
        return {"idle": self.idle_image, "hover": self.hover_image, "down": self.down_image}[look]

    def draw(self, mouse: MouseState) -> None:
        image = self.image_for(self.look(mouse))
        self.surface.blit(image, image.get_rect(center=self.rect.center))


class ToggleButton(ImageButton):
    """An on/off button: a click flips the state, control() returns the state.

    on_images and off_images are (idle, hover, down) looks; hover and down may be
    left out. Change the state from code with set_state() so the looks follow.
    """

    def __init__(
        self,
        surface: pygame.Surface,
        rect: pygame.Rect | Sequence[int],
        on_images: Sequence[pygame.Surface],
        off_images: Sequence[pygame.Surface],
        is_on: bool = False,
    ) -> None:
        self.on_images = tuple(on_images)
        self.off_images = tuple(off_images)
        if not 1 <= len(self.on_images) <= 3 or not 1 <= len(self.off_images) <= 3:
            raise ValueError("on_images and off_images must hold 1 to 3 images each")
        super().__init__(surface, rect, *self.off_images)
        self.set_state(is_on)

    def update_images(self) -> None:
        self.set_images(*(self.on_images if self.is_on else self.off_images))

    def set_state(self, is_on: bool) -> None:
        self.is_on = bool(is_on)
        self.update_images()

    def action(self) -> bool:
        self.set_state(not self.is_on)
        return self.is_on

    def idle(self) -> bool:
        return self.is_on


class Slider:
    """A horizontal slider returning a value in [min_value, max_value].

    Press anywhere on the bar (a hit box as tall as the knob) and the knob jumps
    there and follows the mouse while the button stays down, even off the bar.
    """

    def __init__(
        self,
        surface: pygame.Surface,
        rect: pygame.Rect | Sequence[int],
        min_value: float,
        max_value: float,
        value: float | None = None,
        *,
        knob_radius: int = 10,
        label: str = "",
        font: pygame.font.Font | None = None,
        text_color: Color = WHITE,
        bar_color: Color = WHITE,
        knob_color: Color = YELLOW,
        outline_color: Color = BLACK,
    ) -> None:
        if not max_value > min_value:
            raise ValueError("max_value must be greater than min_value")
        self.surface = surface
        self.rect = pygame.Rect(rect)
        self.min_value = float(min_value)
        self.max_value = float(max_value)
        self.knob_radius = int(knob_radius)
        self.label = label
        self._font = font
        self.text_color = text_color
        self.bar_color = bar_color
        self.knob_color = knob_color
        self.outline_color = outline_color
        self.sliding = False
        #: A disabled slider ignores the mouse and draws its knob grey.
        self.enabled = True
        #: True if the last control() call moved the value (the user dragged).
        self.changed = False
        self.activation = 0.0
        self.set_value(self.min_value if value is None else value)
        self._label_image: pygame.Surface | None = None

    # -- value <-> knob position -------------------------------------------------------
    def activation_at(self, x: float) -> float:
        """Activation in [0, 1] for a knob at screen x."""
        return min(1.0, max(0.0, (x - self.rect.left) / self.rect.width))

    def knob_xy(self) -> tuple[int, int]:
        return (
            round(self.rect.left + self.activation * self.rect.width),
            self.rect.centery,
        )

    @property
    def value(self) -> float:
        return self.min_value + self.activation * (self.max_value - self.min_value)

    def set_value(self, value: float) -> None:
        """Place the knob so the slider returns value (clamped to the range)."""
        span = self.max_value - self.min_value
        self.activation = min(1.0, max(0.0, (float(value) - self.min_value) / span))

    # -- mouse -----------------------------------------------------------------------------
    def hit_box(self) -> pygame.Rect:
        """As wide as the bar (plus the knob's overhang), as tall as the knob."""
        r = self.knob_radius
        return pygame.Rect(
            self.rect.left - r, self.rect.centery - r, self.rect.width + 2 * r, 2 * r + 1
        )

    def check_mouse(self, mouse: MouseState) -> bool:
        return self.hit_box().collidepoint(mouse.xy)

    def is_sliding(self, mouse: MouseState) -> bool:
        """Starts with a press on the hit box, lasts while the button is held."""
        if not self.enabled:
            return False
        if mouse.clicked and self.check_mouse(mouse):
            return True
        return self.sliding and mouse.down

    # -- drawing ----------------------------------------------------------------------------
    @property
    def font(self) -> pygame.font.Font:
        if self._font is None:
            self._font = pygame.font.Font(None, 24)
        return self._font

    def draw(self, mouse: MouseState) -> None:
        pygame.draw.rect(self.surface, self.bar_color, self.rect, border_radius=3)
        pygame.draw.rect(self.surface, self.outline_color, self.rect, width=1, border_radius=3)
        if self.label:
            if self._label_image is None:
                self._label_image = self.font.render(self.label, True, self.text_color)
            pos = self._label_image.get_rect(
                midtop=(self.rect.centerx, self.rect.bottom + self.knob_radius + 4)
            )
            self.surface.blit(self._label_image, pos)
        hot = self.sliding or (self.enabled and self.check_mouse(mouse))
        knob = tuple(min(255, c + 30) for c in self.knob_color) if hot else self.knob_color
        if not self.enabled:
            knob = (170, 170, 170)
        center = self.knob_xy()
        pygame.draw.circle(self.surface, knob, center, self.knob_radius)
        pygame.draw.circle(self.surface, self.outline_color, center, self.knob_radius, width=2)

    def control(self, mouse: MouseState) -> float:
        """Update from the mouse, draw, and return the value."""
        before = self.activation
        self.sliding = self.is_sliding(mouse)
        if self.sliding:
            self.activation = self.activation_at(mouse.xy[0])
        self.changed = self.activation != before
        self.draw(mouse)
        return self.value
