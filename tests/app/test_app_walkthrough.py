"""What a walk through the desktop under a real X server found, each through real events:
A at the paused start, C in the name box, numbers and options in Arabic, Latin key names
on the baseline of a Japanese or Arabic help, the help fitted once, a class server that is
down said in words, and notices that end with their moment and are coloured by kind.
(The window that a chart moves near the screen's edge is in test_app_wm.py.)"""

from __future__ import annotations

import time

import numpy as np
import pygame
import pytest
from apphelp import NOTICE_STRIP, click, frames, key, pixels, play_ramp
from classhelp import free_port

from evapcool import i18n
from evapcool.app.applet import App
from evapcool.app.classlink import ClassLink
from evapcool.app.input import Mode
from evapcool.app.words import choose
from evapcool.game.autopilot import Autopilot, parse_strategy
from evapcool.game.rules import Game, GameConfig
from evapcool.view import fonts, scene
from evapcool.view.pen import Pen
from evapcool.view.scene import NEWS_SHADE, NOTICE_SHADE, REPLAY_RECT, Scene

pytestmark = pytest.mark.usefixtures("own_folders")


@pytest.fixture
def make_app(tmp_path):
    """make_app(seed=1, **options): an App on a fresh game, closed after the test."""
    apps: list[App] = []

    def build(seed: int = 1, **options: object) -> App:
        a = App(
            Game(GameConfig(seed=seed)),
            data_dir=tmp_path / "data",
            config_dir=tmp_path / "config",
            screen=(1600, 1000),
            **options,  # type: ignore[arg-type]
        )
        apps.append(a)
        return a

    yield build
    for a in apps:
        a.close()


def window_rect(app: App, rect: pygame.Rect) -> pygame.Rect:
    """A scene (logical) rectangle in window pixels."""
    lay = app.layout
    s = lay.scale
    return pygame.Rect(lay.scene.x + rect.x * s, lay.scene.y + rect.y * s, rect.w * s, rect.h * s)


_MIRROR = str.maketrans("()<>[]", ")(><][")


def seen(text: str, rtl: bool) -> str:
    """The characters of a line left to right as the screen shows them (a right-to-left
    run turned round, its brackets mirrored, as HarfBuzz draws it)."""
    return "".join(s[::-1].translate(_MIRROR) if r else s for r, s in fonts.bidi_runs(text, rtl))


# -- A at the paused start -----------------------------------------------------------------------


def test_a_at_the_paused_start_plays_the_autopilot_at_once(make_app):
    app = make_app()
    frames(app)
    assert app.game.paused and app.game.sim.time == 0.0
    key(app, pygame.K_a)
    frames(app, 5)
    assert not app.game.paused and app.game.sim.time > 0.0  # "plays" is what happens
    assert app.autopilot is not None and app.autopilot.engaged and app.autopilot.flew
    assert app.visible_notices[-1].startswith("Autopilot (demo) plays")


def test_autopilot_from_the_command_line_waits_for_space_and_says_so(make_app):
    app = make_app(autopilot=Autopilot(parse_strategy("300@0,100@400"), name="quick"))
    frames(app, 3)
    assert app.game.paused and app.game.sim.time == 0.0
    assert "Space starts the game" in app.visible_notices[-1]
    key(app, pygame.K_SPACE)
    frames(app, 3)
    assert app.game.sim.time > 0.0 and app.autopilot.flew


# -- C while the name box is open ----------------------------------------------------------------


def test_the_strip_promises_c_only_when_c_copies(make_app, monkeypatch):
    monkeypatch.setattr("evapcool.app.replays.put_on_clipboard", lambda text: True)
    app = make_app(seed=3)
    strip = window_rect(app, REPLAY_RECT)
    play_ramp(app)
    frames(app)
    assert app.input.mode is Mode.NAME and app.replay_offered
    while_named = pygame.surfarray.array3d(app.window.surface.subsurface(strip)).copy()
    assert app.win_screen.strip_label() == "Replay code: C copies it after the name"
    key(app, pygame.K_c, text="c")  # a letter of the name: no copy, no promise broken
    assert app.scores.name_box.text == "c" and app.visible_notices == []
    key(app, pygame.K_RETURN)
    assert app.win_screen.strip_label() == "Replay code: C copies it"
    after = pygame.surfarray.array3d(app.window.surface.subsurface(strip))
    assert (after != while_named).any()  # the strip's words changed with the box
    key(app, pygame.K_c)
    assert app.visible_notices[-1].startswith("Replay code copied;")


# -- Arabic: numbers, ranges, options, names -----------------------------------------------------


def test_the_atoms_row_reads_right_in_arabic(make_app):
    app = make_app()
    choose(None, "ar")
    key(app, pygame.K_o)
    _, value = app.options.rows()[0]
    assert value == "49  (1 إلى 62)"
    # As the settings screen draws the selected row: brackets round the value.
    # (An Arabic word's letters go right to left on the screen: written here as seen.)
    assert seen(f"< {value} >", True) == "< (62 " + "إلى"[::-1] + " 1)  49 >"


def test_an_option_in_the_arabic_help_stays_whole(make_app):
    app = make_app()
    choose(None, "ar")
    key(app, pygame.K_h)
    [what] = [w for _, w in app.help_rows() if "autopilot" in w]
    shown = seen(what, fonts._rtl_paragraph(what))
    assert "--autopilot" in shown and "autopilot--" not in shown


def test_a_name_with_a_number_is_drawn_alike_in_every_language():
    name = "سارة 7"
    images = []
    for tag in ("en", "ar", "de"):
        choose(None, tag)
        image = fonts.text_image(name, 24, (255, 255, 255))
        images.append(pygame.surfarray.array3d(image).copy())
        assert seen(name, fonts._rtl_paragraph(name)) == "7 " + "سارة"[::-1]
    for other in images[1:]:
        np.testing.assert_array_equal(other, images[0])


# -- Latin key names on the baseline of the description ------------------------------------------


def _ink_bottom(px: np.ndarray, color: tuple[int, int, int], columns: slice) -> int:
    """The lowest row where a pixel is near this colour, within the columns."""
    near = (np.abs(px[columns].astype(int) - color).max(axis=-1) < 60).any(axis=0)
    return int(np.nonzero(near)[0].max())


@pytest.mark.parametrize(
    ("tag", "row"), [("ja", ("S", "1 フレーム進める")), ("ar", ("R", "خفض 1"))]
)
def test_latin_key_names_sit_on_the_descriptions_baseline(make_app, tag, row):
    make_app()  # the display and fonts, as the applet has them
    choose(None, tag)
    surface = pygame.Surface((640, 672))
    surface.fill((0, 0, 0))
    panel = Scene().draw_help(Pen(surface), [row], [])
    # The row, inside the panel's frame and under its title.
    rows = pygame.Rect(panel.left + 6, panel.top + 45, panel.width - 12, panel.height - 50)
    px = pygame.surfarray.array3d(surface.subsurface(rows)).astype(int)
    is_key = (np.abs(px - scene.ACCENT).max(axis=-1) < 60).any(axis=1)
    is_text = (px.min(axis=-1) > 200).any(axis=1)
    keys, text = np.nonzero(is_key)[0], np.nonzero(is_text)[0]
    key_bottom = _ink_bottom(px, scene.ACCENT, slice(keys.min(), keys.max() + 1))
    # The digit 1 is the description's leftmost letter in both (right to left: its end).
    digit = _ink_bottom(px, (255, 255, 255), slice(text.min(), text.min() + 6))
    assert abs(key_bottom - digit) <= 1, (key_bottom, digit)


# -- the help is fitted once ---------------------------------------------------------------------


def test_an_open_help_is_fitted_once_not_every_frame(make_app, monkeypatch):
    app = make_app()
    choose(None, "ja")
    fitted = []
    real = scene._help_rows
    monkeypatch.setattr(scene, "_help_rows", lambda *a: fitted.append(1) or real(*a))
    key(app, pygame.K_h)
    frames(app, 30)
    assert app.overlay == "help" and len(fitted) == 1
    choose(None, "de")  # another language: its own words, fitted again
    frames(app, 5)
    assert len(fitted) == 2


# -- a class server that is down ------------------------------------------------------------------


def test_a_class_server_that_is_down_is_said_in_words(make_app):
    choose(None, "de")
    app = make_app(classroom=ClassLink(f"http://127.0.0.1:{free_port()}/", "Ada", timeout=10))
    deadline = time.monotonic() + 30
    while not any("antwortet nicht" in n for n in app.visible_notices):
        assert time.monotonic() < deadline, app.visible_notices
        frames(app)
        time.sleep(0.01)
    [said] = [n for n in app.visible_notices if "antwortet nicht" in n]
    assert "Errno" not in said and "refused" not in said
    assert i18n.t("desk.class.why.refused") in said


# -- notices end with their moment, coloured by kind ---------------------------------------------


def _notice_pixels(app, shade: tuple[int, int, int, int]) -> int:
    """Pixels of the lower play area in this notice shade (over the grey background)."""
    a = shade[3] / 255
    over = [round(c * a + b * (1 - a)) for c, b in zip(shade[:3], scene.BACKGROUND, strict=True)]
    px = pixels(app)[NOTICE_STRIP.left : NOTICE_STRIP.right, NOTICE_STRIP.top - 60 :]
    return int((np.abs(px - over).max(axis=-1) <= 3).sum())


def test_a_copied_code_is_gone_at_the_next_players_start_and_was_not_red(make_app, monkeypatch):
    monkeypatch.setattr("evapcool.app.replays.put_on_clipboard", lambda text: True)
    app = make_app(seed=3)
    play_ramp(app)
    frames(app)
    key(app, pygame.K_ESCAPE)  # skip the name
    click(app, window_rect(app, REPLAY_RECT).center)
    assert any(n.startswith("Replay code copied") for n in app.visible_notices)
    frames(app)
    assert _notice_pixels(app, NEWS_SHADE) > 2000 and _notice_pixels(app, NOTICE_SHADE) == 0
    key(app, pygame.K_RETURN)  # the next player's game
    assert app.game.score is None and app.visible_notices == []


def test_settings_saved_is_gone_after_r_and_a_problem_stays(make_app, tmp_path):
    app = make_app()
    key(app, pygame.K_o)
    key(app, pygame.K_LEFT)  # one atom fewer
    key(app, pygame.K_RETURN)
    assert app.visible_notices == ["Settings saved. Press R (restart) to play with them."]
    app.notices.problem("The high-score file was damaged.")
    key(app, pygame.K_r)
    assert app.game.config.n_atoms == app.options.settings.n_atoms < 49
    assert app.visible_notices == ["The high-score file was damaged."]
    frames(app)
    assert _notice_pixels(app, NOTICE_SHADE) > 2000 and _notice_pixels(app, NEWS_SHADE) == 0


# -- the house: the App's parts never hold it ------------------------------------------------------


def _reaches(value: object, target: object) -> bool:
    """Whether value is target, or a function whose closure or bound self is it."""
    if value is target:
        return True
    cells = getattr(value, "__closure__", None) or ()
    owner = getattr(value, "__self__", None)
    return owner is target or any(c.cell_contents is target for c in cells)


def test_no_part_of_the_app_holds_the_app(make_app):
    app = make_app()
    parts = (
        app.input,
        app.commands,
        app.rounds,
        app.framing,
        app.overlays,
        app.win_screen,
        app.pilot,
        app.classroom,
        app.time,
        app.notices,
        app.scores,
        app.options,
        app.replays,
        app.controls,
        app.slider,
    )
    for part in parts:
        for name, value in vars(part).items():
            assert not _reaches(value, app), (type(part).__name__, name)
    assert app.input.controls is app.commands
