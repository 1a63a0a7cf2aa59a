"""Helpers for driving the pygame applet in tests: posted events, whole frames, pixels.

Imported by the app test modules as `from apphelp import ...` (pytest puts tests/ on sys.path).
The fixtures that go with them (`make_app`, `app`, `own_folders`) live in conftest.py.
"""

from __future__ import annotations

import numpy as np
import pygame

from evapcool.app.applet import HEIGHT_STEP, App
from evapcool.view.scene import MESSAGE_Y, PLAY_RECT

#: Where "Score: N" and the other big messages appear, at the top of the play area
#: (below the start hint's line).
SCORE_BOX = pygame.Rect(PLAY_RECT.left, MESSAGE_Y - 8, PLAY_RECT.width, 70)
#: The strip at the bottom of the play area where notices show.
NOTICE_STRIP = pygame.Rect(PLAY_RECT.left, PLAY_RECT.bottom - 90, PLAY_RECT.width, 90)


def post(kind: int, **attrs) -> None:
    pygame.event.post(pygame.event.Event(kind, **attrs))


def frames(app: App, n: int = 1) -> None:
    for _ in range(n):
        app.frame(None)


def key(app: App, k: int, times: int = 1, *, text: str = "") -> None:
    """Press and release key k, `times` times, one frame after each press.

    With text, the press is sent as SDL sends it while text input is on: KEYDOWN, then
    TEXTINPUT, then KEYUP.
    """
    for _ in range(times):
        post(pygame.KEYDOWN, key=k, mod=0, unicode=text, scancode=0)
        if text:
            post(pygame.TEXTINPUT, text=text)
        post(pygame.KEYUP, key=k, mod=0, unicode=text, scancode=0)
        frames(app)


def click(app: App, xy: tuple[int, int], *, move: bool = True) -> None:
    """A left click at xy (window pixels): button down, a frame, button up, a frame.

    move: first move the pointer there (a MOUSEMOTION event), as a real mouse would.
    """
    if move:
        post(pygame.MOUSEMOTION, pos=xy, rel=(0, 0), buttons=(0, 0, 0))
    post(pygame.MOUSEBUTTONDOWN, pos=xy, button=1)
    frames(app)
    post(pygame.MOUSEBUTTONUP, pos=xy, button=1)
    frames(app)


def play_ramp(app: App, budget: int = 1500) -> None:
    """A scripted player: Space, then the Down key whenever the trap is a step above a
    ramp from 400 to 80 px over 500 frames, until the gas condenses."""
    key(app, pygame.K_SPACE)
    for k in range(budget):
        wanted = max(80.0, 400.0 - 320.0 * k / 500.0)
        if app.game.trap_height - wanted >= HEIGHT_STEP:
            post(pygame.KEYDOWN, key=pygame.K_DOWN, mod=0, unicode="", scancode=0)
        frames(app)
        if app.game.won:
            return
    raise AssertionError("the scripted game did not win")


def pixels(app: App) -> np.ndarray:
    """The window as an (x, y, rgb) int array."""
    return pygame.surfarray.array3d(app.window.surface).astype(int)


def count(app: App, box: pygame.Rect, test) -> int:
    """Pixels in box (window pixels) for which test(r, g, b) holds."""
    px = pixels(app)[box.left : box.right, box.top : box.bottom]
    return int(np.count_nonzero(test(px[..., 0], px[..., 1], px[..., 2])))


def white(r, g, b):
    return (r >= 250) & (g >= 250) & (b >= 250)


def blends(px: np.ndarray, background: tuple, inks: list[tuple], tolerance: int = 3) -> np.ndarray:
    """Which pixels are a blend of the background and one of the inks (antialiased text)."""
    px = px.astype(float)
    ok = np.zeros(px.shape[:2], dtype=bool)
    bg = np.array(background, dtype=float)
    for ink in inks:
        d = np.array(ink, dtype=float) - bg
        t = np.clip(((px - bg) @ d) / max(1.0, d @ d), 0.0, 1.0)
        ok |= np.abs(px - (bg + t[..., None] * d)).max(axis=-1) <= tolerance
    return ok
