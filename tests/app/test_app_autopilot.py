"""The autopilot in the applet, driven by real events: `--autopilot FILE`, the slider follows
the strategy, the player takes over by touching it, key A hands back, and autopilot wins go
to a table of their own, marked, never among the players' scores."""

from __future__ import annotations

import json

import pygame
import pytest
from apphelp import frames, key, post

from evapcool.app.applet import App
from evapcool.app.input import Mode
from evapcool.game.autopilot import Autopilot, GameSetup, parse_strategy, play
from evapcool.game.rules import Game, GameConfig
from evapcool.view.scene import SLIDER_RECT

pytestmark = pytest.mark.usefixtures("own_folders")

#: Wins at frame 415 with 25 atoms from seed 1 (test_autopilot_wins_the_headless_game).
QUICK = "400@0,80@500"


@pytest.fixture
def pilot_app(tmp_path):
    apps = []

    def make(strategy: str = QUICK, seed: int = 1) -> App:
        a = App(
            Game(GameConfig(seed=seed)),
            data_dir=tmp_path / "data",
            config_dir=tmp_path / "config",
            screen=(1600, 1000),
            autopilot=Autopilot(parse_strategy(strategy), name="quick"),
        )
        apps.append(a)
        return a

    yield make
    for a in apps:
        a.close()


def knob_x(app: App) -> float:
    return app.slider.knob_xy()[0]


def test_the_slider_moves_as_the_strategy_says(pilot_app):
    app = pilot_app("300@0,100@400")
    frames(app)
    assert app.game.paused and app.game.trap_height == 300.0  # its start, before Space
    assert app.slider.value == pytest.approx(300.0)
    x0 = knob_x(app)
    key(app, pygame.K_SPACE)
    frames(app, 199)
    t = app.game.sim.time
    assert t == 200.0
    assert app.game.trap_height == pytest.approx(300 - 200 * (t - 1) / 400)
    assert app.slider.value == pytest.approx(app.game.trap_height)
    assert knob_x(app) < x0  # the knob is drawn where the trap is


def test_touching_the_slider_takes_over_and_a_hands_back(pilot_app):
    app = pilot_app("300@0,100@400")
    key(app, pygame.K_SPACE)
    frames(app, 20)
    x = SLIDER_RECT.left + SLIDER_RECT.width * (420 - 25) / 425
    post(pygame.MOUSEBUTTONDOWN, pos=(round(x), SLIDER_RECT.centery), button=1)
    frames(app)
    post(pygame.MOUSEBUTTONUP, pos=(round(x), SLIDER_RECT.centery), button=1)
    frames(app, 30)
    assert not app.autopilot.engaged
    assert app.game.trap_height == pytest.approx(420.0, abs=1.0)  # the player's, held
    assert any("You have the trap" in n for n in app.visible_notices)
    key(app, pygame.K_a)
    assert app.autopilot.engaged
    t = app.game.sim.time
    assert app.game.trap_height == pytest.approx(300 - 200 * (t - 1) / 400)
    key(app, pygame.K_DOWN)  # the arrow keys are the slider's too
    assert not app.autopilot.engaged
    h = app.game.trap_height
    frames(app, 10)
    assert app.game.trap_height == h


def test_key_a_without_autopilot_plays_the_demo(make_app):
    app = make_app()
    assert app.autopilot is None
    key(app, pygame.K_a)
    assert app.autopilot is not None and app.autopilot.name == "demo" and app.autopilot.engaged
    assert any("Autopilot (demo)" in n for n in app.visible_notices)
    labels = [label for label, _ in app.help_rows()]
    assert "A" in labels


def test_autopilot_wins_the_headless_game_and_its_score_is_kept_apart(pilot_app, tmp_path):
    # Seed 3's start (the shared start generator, issue 22.1): the quick ramp wins at frame 431.
    o = play(parse_strategy(QUICK), 3, 1800, GameSetup(engine="reference"))
    assert (o.won_frame, o.score) == (431, 18)
    app = pilot_app(seed=3)
    key(app, pygame.K_SPACE)
    frames(app, 440)
    assert app.game.won and app.game.score == o.score
    assert round(app.game.won_at * 30) == o.won_frame
    assert app.scores.name_box is None and app.input.mode is not Mode.NAME  # no name asked
    players = tmp_path / "data" / "highscores.json"
    assert not players.exists() or json.loads(players.read_text()).get("entries") in ([], None)
    pilots = json.loads((tmp_path / "data" / "autopilot-scores.json").read_text())
    assert [(e["name"], e["score"]) for e in pilots["entries"]] == [("Autopilot quick", 18)]
    key(app, pygame.K_t)
    footer = app.scores.footer(False)
    assert footer[0].startswith("Autopilot quick, not ranked: 18 atoms")
    assert app.scores.table.entries == []
    key(app, pygame.K_RETURN)  # next round, as after a player's win
    assert not app.game.won and not app.autopilot.flew


def test_a_win_after_the_player_took_over_at_the_start_is_the_players(pilot_app):
    app = pilot_app()
    x = SLIDER_RECT.left + 200
    post(pygame.MOUSEBUTTONDOWN, pos=(x, SLIDER_RECT.centery), button=1)
    post(pygame.MOUSEBUTTONUP, pos=(x, SLIDER_RECT.centery), button=1)
    frames(app)
    assert not app.autopilot.engaged and not app.autopilot.flew
    key(app, pygame.K_SPACE)
    frames(app, 10)
    app.game.sim.force_win()  # the player's win (how is not the point here)
    frames(app)
    assert app.scores.name_box is not None  # a person's win: the name box, the players' table


def test_autopilot_option(tmp_path, monkeypatch):
    from evapcool.app.cli import main

    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    shot = tmp_path / "a.png"
    args = ["--data-dir", str(tmp_path / "d"), "--config-dir", str(tmp_path / "c"), "--seed", "1"]
    assert main([*args, "--autopilot", "demo", "--frames", "30", "--screenshot", str(shot)]) == 0
    assert shot.is_file()


@pytest.mark.parametrize("bad", ["nowhere.json", "sideways", "feedback:eta0=x"])
def test_bad_autopilot_is_one_line_and_exit_2(tmp_path, capsys, bad):
    from evapcool.app.cli import main

    assert main(["--autopilot", bad, "--frames", "1", "--data-dir", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("evapcool: error: --autopilot:")
