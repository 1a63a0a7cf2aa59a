"""Helpers for driving the pygame applet headless in tests: posted events and whole frames.

Imported by the app test modules as `from apphelp import ...` (pytest puts tests/ on sys.path).
The fixtures that go with them (`make_app`, `app`, `own_folders`) live in conftest.py.
"""

from __future__ import annotations

import pygame

from evapcool.app.applet import App
from evapcool.view.scene import PLAY_RECT

#: Where the large "Score: N" text appears in the play area.
SCORE_BOX = pygame.Rect(PLAY_RECT.left, PLAY_RECT.top + 100, PLAY_RECT.width, 140)
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
    """A left click at xy: button down, a frame, button up, a frame.

    move: first move the pointer there (a MOUSEMOTION event), as a real mouse would.
    """
    if move:
        post(pygame.MOUSEMOTION, pos=xy, rel=(0, 0), buttons=(0, 0, 0))
    post(pygame.MOUSEBUTTONDOWN, pos=xy, button=1)
    frames(app)
    post(pygame.MOUSEBUTTONUP, pos=xy, button=1)
    frames(app)
