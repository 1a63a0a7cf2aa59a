"""One cache of pygame's bundled font by size and weight, for every view module."""

from __future__ import annotations

import pygame

_cache: dict[tuple[int, bool], pygame.font.Font] = {}


def font(size: int, bold: bool = False) -> pygame.font.Font:
    """pygame's bundled font (present everywhere) at this pixel size."""
    if not pygame.font.get_init():
        pygame.font.init()
    key = (size, bold)
    f = _cache.get(key)
    if f is None:
        if not _cache:
            # A Font dies with the font module: forget them all when pygame quits, so
            # an applet reopened in one process (a notebook, the tests) gets live fonts.
            # pygame runs a quit callback once, hence one registration per filling.
            pygame.register_quit(_cache.clear)
        f = _cache[key] = pygame.font.Font(None, size)
        f.set_bold(bold)
    return f
