"""The win, the name entry and the high-score table in the applet (headless, posted events)."""

from __future__ import annotations

import json
from datetime import datetime

import numpy as np
import pygame
import pytest
from apphelp import NOTICE_STRIP, SCORE_BOX, count, frames, key, pixels, post, white

from evapcool import Simulation
from evapcool.app.applet import NOTICE_SECONDS, App
from evapcool.app.input import Mode
from evapcool.game.highscores import HighScoreTable
from evapcool.physics.simulation import FPS
from evapcool.view.scene import PLAY_RECT

CUP_BOTTOM = pygame.Rect(PLAY_RECT.left, PLAY_RECT.bottom - 140, PLAY_RECT.width, 140)


@pytest.fixture
def data(tmp_path):
    return tmp_path / "data"


def type_text(app: App, text: str) -> None:
    for ch in text:
        post(pygame.TEXTINPUT, text=ch)
    frames(app)


def cyan(r, g, b):
    return (b - r > 60) & (g - r > 60)


def glow(r, g, b):
    return (r > 230) & (g > 90) & (b < 200) & (r - b > 60)


def notice_red(r, g, b):
    return (r > 90) & (g < 60) & (b < 60)


def stored(data) -> list[dict]:
    return json.loads((data / "highscores.json").read_text(encoding="utf-8"))["entries"]


def win_with(app: App, n_atoms: int, seed: int = 0) -> None:
    """Play a game of n atoms to a forced win (score n): a quick stand-in for skill."""
    app.game.sim = Simulation(n_atoms=n_atoms, seed=seed)
    app.game.paused = False
    frames(app, 2)
    app.game.sim.force_win()
    frames(app)


# -- the win -------------------------------------------------------------------------------------


def test_forced_win_shows_the_condensate_and_the_score_and_asks_a_name(app, monkeypatch):
    started = []
    monkeypatch.setattr(pygame.key, "start_text_input", lambda: started.append(True))
    # (the name box and the table sit below the score, which stays in view)
    app.game.paused = False
    frames(app, 5)
    assert count(app, CUP_BOTTOM, cyan) > 500 and count(app, CUP_BOTTOM, glow) == 0
    assert (
        app.scores.name_box is None
        and count(app, SCORE_BOX, lambda r, g, b: (r > 250) & (g > 250)) == 0
    )
    app.game.sim.force_win()
    app.game.set_speed(4.0)
    frames(app, 150)  # the atoms settle and merge into the packet
    assert app.scene.fade == 1.0
    assert count(app, CUP_BOTTOM, cyan) == 0  # atoms fully faded under the condensate
    assert count(app, CUP_BOTTOM, glow) > 300  # the glowing packet at the bottom of the cup
    assert count(app, SCORE_BOX, lambda r, g, b: (r > 250) & (g > 250) & (b > 250)) > 300
    assert app.game.score == 49
    assert app.scores.name_box is not None and started == [True]


def test_a_typed_name_is_stored_and_enter_then_restarts(app, data):
    win_with(app, 12)
    assert app.scores.name_box is not None
    sim = app.game.sim
    paused = app.game.paused
    type_text(app, "Ada")
    # Keys typed into the box are letters, not controls: no pause, restart or chart.
    key(app, pygame.K_SPACE, text=" ")
    key(app, pygame.K_r, text="R")
    key(app, pygame.K_e, text="e")
    assert app.game.sim is sim and app.game.paused == paused and not app.charts.show_energy
    key(app, pygame.K_BACKSPACE)
    key(app, pygame.K_RETURN)
    rows = stored(data)
    assert [(r["name"], r["score"]) for r in rows] == [("Ada R", 12)]
    assert rows[0]["seconds"] == pytest.approx(app.game.won_at, abs=0.01)
    assert rows[0]["seconds"] == pytest.approx(3 / FPS, abs=0.01)
    assert datetime.strptime(rows[0]["date"], "%Y-%m-%d %H:%M:%S").date() == datetime.now().date()
    assert app.scores.name_box is None and app.overlay == "table" and app.scores.stored_rank == 1
    assert app.game.sim is sim  # the table shows; the next player presses Enter
    key(app, pygame.K_RETURN)
    new = app.game.sim
    assert new is not sim and (new.n_trapped, new.time, app.game.paused) == (49, 0.0, True)
    assert app.overlay is None and not app.scores.ready_for_next


def test_table_order_and_top_10_through_the_ui(app, data):
    scores = [5, 9, 3, 12, 7, 2, 10, 4, 8, 11, 6]
    for k, score in enumerate(scores):
        win_with(app, score, seed=k)
        assert app.scores.name_box is not None, score
        type_text(app, f"P{k}")
        key(app, pygame.K_RETURN)
        key(app, pygame.K_RETURN)
    rows = stored(data)
    assert [r["score"] for r in rows] == sorted(scores, reverse=True)[:10]
    assert [r["name"] for r in rows][:3] == ["P3", "P9", "P6"]
    # A score below the whole table is not asked for; Enter still starts the next game.
    win_with(app, 1, seed=99)
    assert app.scores.name_box is None and app.scores.ready_for_next
    assert any("not in the top 10" in n for n in app.visible_notices)
    old = app.game.sim
    key(app, pygame.K_RETURN)
    assert app.game.sim is not old
    assert len(stored(data)) == 10


def test_escape_skips_the_name(app, data):
    win_with(app, 7)
    type_text(app, "Bo")
    key(app, pygame.K_ESCAPE)
    assert app.scores.name_box is None and app.running  # Esc left the box, not the applet
    assert not (data / "highscores.json").exists()
    key(app, pygame.K_RETURN)
    assert app.game.sim.n_atoms == 49


# -- the table overlay and its reset --------------------------------------------------------


def test_t_shows_the_table_and_a_reset_needs_confirmation(make_app, data):
    table = HighScoreTable(data / "highscores.json")
    table.add("Ada", 30, 40.0)
    table.add("Bo", 20, 50.0)
    app = make_app()
    frames(app)
    dark = lambda r, g, b: (r < 60) & (g < 60) & (b < 80)  # noqa: E731
    box = PLAY_RECT.inflate(-60, -300)
    before = count(app, box, dark)
    key(app, pygame.K_t)
    assert app.overlay == "table" and count(app, box, dark) > before + 0.5 * box.w * box.h
    key(app, pygame.K_x)
    assert app.input.mode is Mode.CONFIRM_CLEAR
    key(app, pygame.K_SPACE)  # only Y or N/Esc answer the question
    assert app.input.mode is Mode.CONFIRM_CLEAR and app.game.paused
    key(app, pygame.K_n)
    assert app.input.mode is not Mode.CONFIRM_CLEAR and len(stored(data)) == 2
    key(app, pygame.K_DELETE)
    key(app, pygame.K_ESCAPE)
    assert (
        app.input.mode is not Mode.CONFIRM_CLEAR
        and app.overlay == "table"
        and len(stored(data)) == 2
    )
    key(app, pygame.K_DELETE)
    key(app, pygame.K_y)
    assert stored(data) == [] and app.scores.table.entries == []
    assert any("cleared" in n for n in app.visible_notices)
    key(app, pygame.K_t)
    assert app.overlay is None


# -- damaged files and unusable folders ------------------------------------------------------


def test_a_corrupt_score_file_is_set_aside_and_the_app_starts_with_a_notice(make_app, data):
    data.mkdir()
    (data / "highscores.json").write_text("{not json", encoding="utf-8")
    app = make_app()
    frames(app)
    aside = list(data.glob("highscores.json.corrupt-*"))
    assert len(aside) == 1 and aside[0].read_text(encoding="utf-8") == "{not json"
    assert any("damaged" in n for n in app.visible_notices)
    assert count(app, NOTICE_STRIP, notice_red) > 2000  # the notice is on screen
    frames(app, round(NOTICE_SECONDS * FPS) + 5)  # ...for a few seconds
    assert app.visible_notices == [] and count(app, NOTICE_STRIP, notice_red) == 0
    win_with(app, 5)  # a new table is started
    type_text(app, "Cy")
    key(app, pygame.K_RETURN)
    assert [r["name"] for r in stored(data)] == ["Cy"]


def test_an_unusable_data_folder_gives_a_notice_not_a_crash(make_app, tmp_path):
    blocker = tmp_path / "not-a-folder"  # as root nothing is read-only: a file in the way
    blocker.write_text("", encoding="utf-8")
    app = make_app(data_dir=blocker)
    frames(app)
    assert any("cannot be saved" in n for n in app.visible_notices)
    assert count(app, NOTICE_STRIP, notice_red) > 2000
    win_with(app, 8)
    type_text(app, "Di")
    key(app, pygame.K_RETURN)
    assert any("could not be saved" in n for n in app.visible_notices)
    assert [e.name for e in app.scores.table.entries] == ["Di"]  # kept for this session
    assert app.overlay == "table" and app.running
    key(app, pygame.K_RETURN)
    assert app.game.sim.time == 0.0


# -- the score stays in view; the name's limit shows (issue 14, items 5 and 10) ---------------


def _score_text(app: App) -> np.ndarray:
    """Where the score box is pure white: the letters of "Score: N" (atoms are never white)."""
    px = pixels(app)[SCORE_BOX.left : SCORE_BOX.right, SCORE_BOX.top : SCORE_BOX.bottom]
    return white(px[..., 0], px[..., 1], px[..., 2])


def test_the_score_stays_visible_over_the_name_box_and_the_table(app):
    win_with(app, 12)
    letters = _score_text(app)
    assert app.scores.name_box is not None and letters.sum() > 300
    type_text(app, "Ada")
    key(app, pygame.K_RETURN)
    assert app.overlay == "table"
    # The table opened below the score: "Score: 12" is untouched, pixel for pixel.
    np.testing.assert_array_equal(_score_text(app), letters)
    # ...and with a full table too.
    for k in range(10):
        app.scores.table.add(f"P{k}", 20 + k, 10.0)
    frames(app)
    np.testing.assert_array_equal(_score_text(app), letters)


def test_the_name_box_shows_the_length_and_the_limit(app):
    win_with(app, 12)
    box = app.scores.name_box
    counter = pygame.Rect(PLAY_RECT.right - 160, PLAY_RECT.top + 230, 110, 30)
    type_text(app, "Ada")
    assert box.text == "Ada"
    few = count(app, counter, lambda r, g, b: (r > 240) & (g > 240) & (b > 240))
    assert few > 20  # "3/16" in white
    type_text(app, "abcdefghijklmnopqrstu")  # 24 letters offered, 16 kept
    assert box.text == "Adaabcdefghijklm" and len(box.text) == box.max_length
    full = count(app, counter, lambda r, g, b: (r > 230) & (g > 190) & (b < 90))
    assert full > 40  # "16/16 (full)" in the accent colour
    key(app, pygame.K_BACKSPACE)
    assert count(app, counter, lambda r, g, b: (r > 230) & (g > 190) & (b < 90)) == 0
