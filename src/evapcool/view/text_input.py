"""A one-line text entry driven by pygame events (typing a name for the score table).

Characters come from TEXTINPUT events (so keyboard layouts and accents work);
KEYDOWN handles Backspace, Enter (submit) and Escape (cancel). Time is passed
in through `update(dt)`, never read from a clock, so the widget is testable.
"""

from __future__ import annotations

from collections.abc import Callable

import pygame

from evapcool.view.pen import Pen

SUBMIT = "submit"
CANCEL = "cancel"
CHANGE = "change"

_SUBMIT_KEYS = (pygame.K_RETURN, pygame.K_KP_ENTER)


def printable(ch: str) -> bool:
    """Default filter: any printable character (letters of every script, digits, spaces)."""
    return ch.isprintable()


class TextInput:
    """Editable single line with a blinking cursor at the end.

    `handle_event(event)` returns SUBMIT, CANCEL, CHANGE or None (event not used).
    After SUBMIT `value` holds the text; after CANCEL it is None. `active` is
    False once either happened; `reset()` makes the widget ready again.
    """

    def __init__(
        self,
        max_length: int = 16,
        text: str = "",
        prompt: str = "",
        blink_period: float = 1.0,
        allowed: Callable[[str], bool] = printable,
    ) -> None:
        if max_length < 1:
            raise ValueError(f"max_length must be >= 1 (got {max_length!r})")
        self.max_length = int(max_length)
        self.prompt = prompt
        self.blink_period = float(blink_period)
        self.allowed = allowed
        self.reset(text)

    def reset(self, text: str = "") -> None:
        """Start editing again with this text."""
        self.text = ""
        self._insert(text)
        self.active = True
        self.value: str | None = None
        self._blink = 0.0

    def _insert(self, s: str) -> bool:
        room = self.max_length - len(self.text)
        kept = "".join(ch for ch in s if self.allowed(ch))[: max(0, room)]
        self.text += kept
        return bool(kept)

    # -- events -------------------------------------------------------------------
    def handle_event(self, event: pygame.event.Event) -> str | None:
        """Feed one event; returns what it did (SUBMIT, CANCEL, CHANGE) or None."""
        if not self.active:
            return None
        if event.type == pygame.TEXTINPUT:
            if self._insert(event.text):
                self._blink = 0.0  # keep the cursor visible while typing
                return CHANGE
            return None
        if event.type != pygame.KEYDOWN:
            return None
        if event.key in _SUBMIT_KEYS:
            self.active = False
            self.value = self.text
            return SUBMIT
        if event.key == pygame.K_ESCAPE:
            self.active = False
            self.value = None
            return CANCEL
        if event.key == pygame.K_BACKSPACE:
            if not self.text:
                return None
            # Ctrl+Backspace clears the field: quick for the next student.
            ctrl = getattr(event, "mod", 0) & pygame.KMOD_CTRL
            self.text = "" if ctrl else self.text[:-1]
            self._blink = 0.0
            return CHANGE
        return None

    def update(self, dt: float) -> None:
        """Advance the cursor blink by dt seconds."""
        self._blink += max(0.0, float(dt))

    @property
    def cursor_visible(self) -> bool:
        """On for the first half of each blink period (always off when not active)."""
        if not self.active:
            return False
        if self.blink_period <= 0:
            return True
        return (self._blink % self.blink_period) < 0.5 * self.blink_period

    # -- drawing ------------------------------------------------------------------
    def draw(
        self,
        pen: Pen,
        rect: pygame.Rect,
        size: int = 32,
        color: tuple[int, int, int] = (20, 20, 20),
        background: tuple[int, int, int] | None = (255, 255, 255),
    ) -> pygame.Rect:
        """Draw prompt, text and cursor into a logical rect at the pen's scale.

        Any script: letters the bundled font lacks come from the system's fonts
        (`evapcool.view.fonts`). Returns the cursor rectangle in pixels.
        """
        rect = pygame.Rect(rect)
        if background is not None:
            pen.box(background, rect)
            pen.box(color, rect, width=2)
        box = pen.rect(rect)
        pad = pen.size(max(4, rect.h // 6))
        img = pen.text_image(self.prompt + self.text, size, color)
        with pen.clip(rect):
            # If the text is wider than the box, keep its end (where typing happens) in view.
            x = box.x + pad + min(0, box.w - 2 * pad - img.get_width() - pen.size(4))
            pen.surface.blit(img, img.get_rect(midleft=(x, box.centery)))
            cursor = pygame.Rect(x + img.get_width() + 1, box.y + pad, pen.size(3), box.h - 2 * pad)
            if self.cursor_visible:
                pen.surface.fill(color, cursor)
        return cursor
