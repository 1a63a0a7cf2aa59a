"""Every desktop game is recorded (issue 22): the win's replay code verifies, and the win
screen offers it (key C or its button copies it; a file in the data folder keeps it)."""

from __future__ import annotations

import pygame
import pytest
from apphelp import click, count, frames, key, play_ramp

from evapcool.app.applet import App
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


def test_a_players_win_gives_a_code_that_verifies(make, tmp_path, monkeypatch):
    # The simulation draws the seed and records it; the draw is pinned to one the scripted
    # ramp wins (a random one may leave too few atoms to condense).
    monkeypatch.setattr("evapcool.physics.simulation.random_seed", lambda: 12345)
    app = make()
    play_ramp(app)
    assert app.replays.code is not None
    rec = decode(app.replays.code)
    assert rec.seed == app.game.sim.seed == 12345 and rec.edition == "desktop"
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


def window_rect(app: App, rect: pygame.Rect) -> pygame.Rect:
    """A scene (logical) rectangle in window pixels."""
    lay = app.layout
    s = lay.scale
    return pygame.Rect(lay.scene.x + rect.x * s, lay.scene.y + rect.y * s, rect.w * s, rect.h * s)


def accent(r, g, b):
    return (r > 230) & (g > 190) & (b < 90)


def test_the_win_screen_offers_the_code_beside_the_name_entry_and_the_table(make, monkeypatch):
    app = make(seed=3)
    button = window_rect(app, REPLAY_RECT)
    play_ramp(app)
    frames(app)
    assert app.input.mode is Mode.NAME and app.scores.name_box is not None  # as before
    assert app.replay_offered and count(app, button, accent) > 100  # the button's words
    click(app, button.center)  # the name box is modal: the button waits for it
    assert app.visible_notices == []
    key(app, pygame.K_a, text="a")
    key(app, pygame.K_c, text="c")  # C types into the name while it is asked
    key(app, pygame.K_RETURN)
    assert app.scores.table.entries[0].name == "ac" and app.overlay == "table"
    assert count(app, button, accent) > 100  # the table ends above the button
    key(app, pygame.K_c)
    assert pygame.scrap.get_text() == app.replays.code
    assert app.visible_notices[-1].startswith("Replay code copied;")
    assert str(app.replays.path) in app.visible_notices[-1]


def test_without_a_clipboard_the_button_says_where_the_file_is(make, monkeypatch):
    app = make(seed=3)
    play_ramp(app)
    key(app, pygame.K_ESCAPE)  # no name: the score is not stored
    monkeypatch.setattr(pygame.scrap, "put_text", _no_clipboard)
    click(app, window_rect(app, REPLAY_RECT).center)
    assert app.visible_notices[-1].startswith("No clipboard:")
    assert app.replays.path.read_text().strip() == app.replays.code
    assert str(app.replays.path) in app.visible_notices[-1]


def _no_clipboard(text: str) -> None:
    raise pygame.error("no clipboard on this system")


def test_an_unwritable_data_folder_is_one_notice_and_the_code_is_still_offered(
    make, tmp_path, monkeypatch
):
    app = make(seed=3)
    (tmp_path / "data").mkdir(exist_ok=True)
    (tmp_path / "data" / "replays").write_text("a file in the folder's place")
    play_ramp(app)
    assert app.replays.path is None and app.replay_offered
    assert any(n.startswith("The replay code could not be saved") for n in app.visible_notices)
    key(app, pygame.K_ESCAPE)
    key(app, pygame.K_c)
    assert pygame.scrap.get_text() == app.replays.code
    assert app.visible_notices[-1] == "Replay code copied to the clipboard."
    monkeypatch.setattr(pygame.scrap, "put_text", _no_clipboard)
    key(app, pygame.K_c)  # neither file nor clipboard: the code itself, to copy by hand
    assert app.visible_notices[-1] == app.replays.code


def test_a_wall_clock_game_won_within_a_frame_verifies(make):
    # At 45 display frames a second the gas condenses between whole frames (t = 430.67):
    # the win counts at that frame's end, which the recording holds, as the replay checks.
    app = make(seed=3, autopilot=QUICK)
    app.game.paused = False
    while not app.game.won:
        assert app.game.sim.time < 600
        app.frame(1 / 45)
    assert not float(app.game.sim.time).is_integer()  # condensed mid-frame...
    assert app.game.won_at is None and app.replays.code is None  # ...counted at its end
    while app.game.won_at is None:
        app.frame(1 / 45)
    rec = decode(app.replays.code)
    assert verify(rec).frames == rec.frames == round(app.game.won_at * 30)
    assert rec.score == app.game.score


def test_a_replay_watched_in_the_applet_plays_its_heights_to_the_claimed_win(tmp_path):
    """`evapcool --replay CODE`: the recording's settings, seed and heights; R plays it again;
    its win is not a player's (no name asked); the player's keys do not move the trap."""
    from evapcool.game.replay import Settings, encode, record_autopilot

    rec = record_autopilot(QUICK, Settings(), 3)
    app = App(
        Game(rec.settings.game_config(rec.seed)),
        data_dir=tmp_path / "data",
        config_dir=tmp_path / "config",
        screen=(1600, 1000),
        replay=decode(encode(rec)),
    )
    try:
        for _ in range(2):  # the second time after R
            assert app.game.trap_height == rec.heights()[0]
            key(app, pygame.K_DOWN)  # the recording holds the trap
            assert app.game.trap_height == rec.heights()[0]
            key(app, pygame.K_SPACE)
            frames(app, rec.frames + 2)
            assert (app.game.won, app.game.score) == (True, rec.score)
            assert app.input.mode is not Mode.NAME
            assert any("replay reached the win" in n for n in app.notices.visible)
            key(app, pygame.K_r)
    finally:
        app.close()


def test_the_command_line_refuses_a_bad_replay_in_one_line(capsys):
    from evapcool.app.cli import main

    assert main(["--replay", "EC1.nonsense.00000000", "--frames", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--replay: not a replay code to watch (damaged" in err[0]
