"""Every desktop game is recorded (issue 22): the win's replay code verifies, and the win
screen offers it (key C or its button copies it; a file in the data folder keeps it)."""

from __future__ import annotations

import pygame
import pytest
from apphelp import click, count, frames, key, post

from evapcool.app import replays
from evapcool.app.applet import HEIGHT_STEP, App
from evapcool.app.input import Mode
from evapcool.game.autopilot import Autopilot, parse_strategy
from evapcool.game.replay import decode, verify
from evapcool.game.rules import Game, GameConfig
from evapcool.view.scene import REPLAY_RECT

pytestmark = pytest.mark.usefixtures("own_folders")

#: The autopilot wins this at frame 431 with 18 atoms from seed 3 (test_app_autopilot.py).
QUICK = "400@0,80@500"


@pytest.fixture
def make(tmp_path):
    """make(seed=None, autopilot=None): an App on a fresh game, closed after the test."""
    apps: list[App] = []

    def build(seed: int | None = None, autopilot: str | None = None) -> App:
        pilot = Autopilot(parse_strategy(autopilot), name="quick") if autopilot else None
        a = App(
            Game(GameConfig(seed=seed)),
            data_dir=tmp_path / "data",
            config_dir=tmp_path / "config",
            screen=(1600, 1000),
            autopilot=pilot,
        )
        apps.append(a)
        return a

    yield build
    for a in apps:
        a.close()


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


def test_a_players_win_gives_a_code_that_verifies(make, tmp_path):
    app = make()  # the simulation draws the seed, and records it
    play_ramp(app)
    assert app.replays.code is not None
    rec = decode(app.replays.code)
    assert rec.seed == app.game.sim.seed and rec.edition == "desktop"
    assert (rec.won, rec.score) == (True, app.game.score)
    assert verify(rec).frames == rec.frames == app.game.sim.time
    saved = list((tmp_path / "data" / "replays").iterdir())
    assert [p.read_text().strip() for p in saved] == [app.replays.code]


def test_an_autopilot_win_and_a_restart_are_recorded_too(make):
    app = make(seed=3, autopilot=QUICK)
    for _ in range(2):  # the second game, after R, is recorded afresh
        key(app, pygame.K_SPACE)
        frames(app, 440)
        assert app.game.won
        rec = decode(app.replays.code)
        assert (rec.seed, rec.score, rec.frames) == (3, 18, 431)
        assert verify(rec).score == 18
        key(app, pygame.K_r)
        assert app.replays.code is None and not app.replay_offered
