"""Make the README's screenshots: the classic start, a win with its score, a small screen.

    python docs/make_screenshots.py [FOLDER]     # default: the folder of this script

Headless (SDL's dummy driver), from fixed seeds, so the pictures come out the same every
time. Scores and settings go to a temporary folder, never the user's.
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")

import pygame

from evapcool.app.applet import App
from evapcool.game.rules import Game, GameConfig

#: A desktop with room for the scene and both charts at scale 1.
WIDE = (1920, 1080)
#: A netbook or a low-resolution projector.
SMALL = (1024, 600)


def _app(folder: str, screen: tuple[int, int], seed: int) -> App:
    return App(Game(GameConfig(seed=seed)), data_dir=folder, config_dir=folder, screen=screen)


def _type(app: App, text: str, key: int | None = None) -> None:
    for ch in text:
        pygame.event.post(pygame.event.Event(pygame.TEXTINPUT, text=ch))
    if key is not None:
        pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=key, mod=0, unicode=""))
    app.frame(None)


def classic_start(folder: str, out: Path) -> None:
    app = _app(folder, WIDE, seed=1)
    app.run_frames(0)
    app.game.paused = True
    app.frame(None)
    app.screenshot(out / "classic-start.png")
    app.close()


def win(folder: str, out: Path) -> None:
    """Lower the rim 3 px a second until the gas condenses, store a name, let it settle."""
    app = _app(folder, WIDE, seed=1)
    app.game.paused = False
    while not app.game.won and app.game.sim.time < 6000:
        app.game.set_trap_height(app.game.trap_height - 0.1)
        app.frame(None)
    if not app.game.won:
        raise SystemExit("make_screenshots: the scripted run did not win")
    _type(app, "Ada", pygame.K_RETURN)
    app.game.set_speed(4.0)
    for _ in range(120):  # the atoms settle into the condensate
        app.frame(None)
    app.screenshot(out / "win.png")
    app.close()


def small_screen(folder: str, out: Path) -> None:
    app = _app(folder, SMALL, seed=2)
    app.toggle_chart("energy")
    app.toggle_chart("path")
    app.game.paused = False
    for _ in range(450):
        app.game.set_trap_height(app.game.trap_height - 0.3)
        app.frame(None)
    app.screenshot(out / "small-screen.png")
    app.close()


def main(argv: list[str]) -> int:
    out = Path(argv[0]) if argv else Path(__file__).resolve().parent
    out.mkdir(parents=True, exist_ok=True)
    for make in (classic_start, win, small_screen):
        with tempfile.TemporaryDirectory() as folder:
            make(folder, out)
    print(f"make_screenshots: wrote classic-start.png, win.png, small-screen.png in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
