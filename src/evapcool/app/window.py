"""The applet's one window: made once, resized and switched to full screen in place.

`pygame.display.set_mode` re-creates the window on every size change, and under a
window manager each re-creation lands a title bar's height lower: a window that
creeps down the screen. A `pygame.Window` is resized and made full screen in place,
so it stays where the user (or the window manager) put it. A chart opened where the
screen has no room to the window's right moves the window left just enough to show it,
and closing it puts the window back where it was (unless the user moved it meanwhile).
"""

from __future__ import annotations

import io
import os

import pygame

from evapcool.fileio import atomic_write_bytes

#: Room left on the screen for the title bar and a task bar when sizing the window.
DECORATION = (16, 80)
#: Room for a window manager's frame (borders, title bar) when keeping a window on screen.
FRAME = (16, 40)


class Window:
    """The OS window; `screen` overrides the desktop size (tests, screenshots)."""

    def __init__(
        self,
        title: str,
        size: tuple[int, int],
        icon: pygame.Surface | None = None,
        screen: tuple[int, int] | None = None,
    ) -> None:
        pygame.display.init()
        self._screen = screen
        self.win = pygame.Window(title, size, resizable=True)
        if icon is not None:
            self.win.set_icon(icon)
        self.fullscreen = False
        #: The last size we asked for: resize events of that size are ours, not the user's.
        self.requested = tuple(size)
        #: (where the user had the window, its size there, where we moved it to make
        #: room), or None.
        self._moved: tuple[tuple[int, int], tuple[int, int], tuple[int, int]] | None = None

    @property
    def surface(self) -> pygame.Surface:
        return self.win.get_surface()

    @property
    def size(self) -> tuple[int, int]:
        return tuple(self.win.size)

    @property
    def position(self) -> tuple[int, int]:
        return tuple(self.win.position)

    def screen_size(self) -> tuple[int, int]:
        """The desktop the window is on (displays assumed side by side, left to right)."""
        if self._screen is not None:
            return self._screen
        sizes = pygame.display.get_desktop_sizes() or [(1024, 768)]
        x = self.win.position[0] + self.win.size[0] // 2 if not self.fullscreen else 0
        for w, h in sizes:
            if x < w:
                return (w, h)
            x -= w
        return sizes[0]

    def usable(self) -> tuple[int, int]:
        """What a window may take of the screen, leaving room for decorations."""
        w, h = self.screen_size()
        return (max(160, w - DECORATION[0]), max(160, h - DECORATION[1]))

    def resize(self, size: tuple[int, int]) -> None:
        """Ask for a new windowed size (ignored in full screen), kept on the screen."""
        size = (max(1, int(size[0])), max(1, int(size[1])))
        if self.fullscreen or size == self.size:
            return
        here, before = self.position, self.size
        self.requested = size
        self.win.size = size
        if self._moved is not None and not _near(here, self._moved[2]):
            self._moved = None  # moved by the user since: where it is now is theirs
        home, home_size = self._moved[:2] if self._moved is not None else (here, before)
        # Back at the size it had there: back there, exactly where the user had it.
        there = home if size == home_size else self._on_screen(home, size)
        if there != here:
            self.win.position = there
        self._moved = (home, home_size, there) if there != home else None

    def _on_screen(self, at: tuple[int, int], size: tuple[int, int]) -> tuple[int, int]:
        """The nearest place to `at` where a window of this size is on the screen, frame
        and all (a window manager may do the same; asking for room to spare, so it has
        nothing left to correct, and nothing creeps)."""
        x, y = at
        sw, sh = self.screen_size()
        mx, my = FRAME
        if x + size[0] + mx > sw or y + size[1] + my > sh:
            return (max(0, min(x, sw - size[0] - mx)), max(0, min(y, sh - size[1] - my)))
        return at

    def toggle_fullscreen(self) -> None:
        if self.fullscreen:
            self.win.set_windowed()
        else:
            self.win.set_fullscreen(desktop=True)
        self.fullscreen = not self.fullscreen

    def flip(self) -> None:
        self.win.flip()

    def screenshot(self, path: str | os.PathLike[str]) -> None:
        """Save what the window shows as a PNG (written atomically)."""
        buf = io.BytesIO()
        pygame.image.save(self.surface, buf, "png")
        atomic_write_bytes(path, buf.getvalue())

    def close(self) -> None:
        self.win.destroy()


def _near(a: tuple[int, int], b: tuple[int, int]) -> bool:
    """The same place, give or take the pixels a window manager's frame may shift it."""
    return abs(a[0] - b[0]) <= 2 and abs(a[1] - b[1]) <= 2
