"""The applet in a real window under a window manager (Xvfb + openbox), driven by xdotool.

Each test runs in a child pytest of its own with a time limit (conftest, ownprocess.py) and
starts its own X servers: a 1024 x 768 screen (a classroom laptop or projector) and a large
2560 x 1600 one. Skipped, saying why, where Xvfb, openbox or xdotool are missing (CI has them).
"""

from __future__ import annotations

import time

import numpy as np
import pygame
import pytest
from apphelp import SCORE_BOX, blends, key, white
from xserver import XServer, missing_tools

from evapcool import Simulation
from evapcool.app.applet import App
from evapcool.app.charts import CHART_BUTTON_RECT
from evapcool.app.input import Mode
from evapcool.game.rules import Game, GameConfig
from evapcool.view import panels
from evapcool.view.fonts import text_image
from evapcool.view.scene import BORDER, SLIDER_RECT

# Each test in a fresh process with a time limit (ownprocess.py): SDL waits for the window
# manager's answers without a timeout, and a lost one must fail a test, not hang the suite.
pytestmark = [pytest.mark.usefixtures("own_folders"), pytest.mark.own_process(timeout=120)]


def _server(width: int, height: int):
    missing = missing_tools()
    if missing:
        pytest.skip(f"needs {', '.join(missing)} for a real window manager (apt install them)")
    server = XServer(width, height)
    yield server
    server.stop()


@pytest.fixture(scope="module")
def small_screen():
    yield from _server(1024, 768)


@pytest.fixture(scope="module")
def big_screen():
    yield from _server(2560, 1600)


@pytest.fixture
def on(monkeypatch, tmp_path):
    """on(server): an App in a real window on that X server (closed after the test)."""
    apps: list[App] = []

    def make(server: XServer) -> App:
        pygame.display.quit()
        monkeypatch.setenv("SDL_VIDEODRIVER", "x11")
        monkeypatch.setenv("DISPLAY", server.display)
        app = App(Game(GameConfig(seed=1)), data_dir=tmp_path / "d", config_dir=tmp_path / "c")
        apps.append(app)
        settle(app)
        return app

    yield make
    for app in apps:
        app.close()


def settle(app: App, seconds: float = 0.4) -> None:
    """Run frames on the wall clock for a while: the window manager's answers arrive."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        app.frame(1 / 60)
        time.sleep(0.015)


def where(server: XServer, app: App) -> tuple[int, int, int, int]:
    settle(app)
    return server.geometry(app.window.win.handle)


# -- item 1: one window, never creeping -------------------------------------------------------


def test_panels_and_full_screen_never_move_or_remake_the_window(small_screen, on):
    app = on(small_screen)
    wid = app.window.win.handle
    x0, y0, w0, h0 = where(small_screen, app)
    assert (w0, h0) == (640, 672)
    windowed = []
    for k in (pygame.K_e, pygame.K_g, pygame.K_e, pygame.K_g, pygame.K_e):
        key(app, k)
        windowed.append(where(small_screen, app))
        key(app, k)
        windowed.append(where(small_screen, app))
    for _ in range(5):
        key(app, pygame.K_F11)
        assert where(small_screen, app) == (0, 0, 1024, 768)
        key(app, pygame.K_F11)
        windowed.append(where(small_screen, app))
    assert app.window.win.handle == wid  # the same window all along
    # A chart that needs the room moves the window onto the screen, always to the same
    # place; closed, the window is back where it was; it never creeps down.
    with_chart = {(x, y) for x, y, _, _ in windowed[0:10:2]}
    alone = {(x, y) for x, y, _, _ in windowed[1:10:2] + windowed[10:]}
    assert len(with_chart) == 1 and alone == {(x0, y0)}, windowed
    assert all(y <= y0 for _, y, _, _ in windowed)
    assert windowed[-1][2:] == (640, 672)
    for x, y, w, h in windowed[0:10:2]:  # a widened window is wholly on the screen
        assert x >= 0 and y >= 0 and x + w <= 1024 and y + h <= 768


def test_a_chart_opened_near_the_right_edge_puts_the_window_back_when_closed(small_screen, on):
    app = on(small_screen)
    wid = str(app.window.win.handle)
    small_screen.xdotool("windowmove", "--sync", wid, "300", "40")
    x0, y0, w0, _ = where(small_screen, app)
    assert x0 >= 300 and x0 + w0 <= 1024  # the scene alone fits there
    key(app, pygame.K_e)
    x1, _, w1, _ = where(small_screen, app)
    assert x1 < x0 and x1 + w1 <= 1024  # the chart needed the room: on the screen, whole
    key(app, pygame.K_e)
    assert where(small_screen, app)[:2] == (x0, y0)  # closed: back where the user had it
    # Moved by the user while the chart is open: that is where it stays.
    key(app, pygame.K_e)
    small_screen.xdotool("windowmove", "--sync", wid, "100", "30")
    moved = where(small_screen, app)[:2]
    key(app, pygame.K_e)
    assert where(small_screen, app)[:2] == moved


# -- item 2: a chart on a small screen fits it ------------------------------------------------


def test_charts_on_a_1024_screen_fit_it_with_the_whole_scene(small_screen, on):
    app = on(small_screen)
    key(app, pygame.K_e)
    key(app, pygame.K_g)
    x, y, w, h = where(small_screen, app)
    assert x >= 0 and x + w <= 1024 and y + h <= 768
    lay = app.layout
    assert lay.arrangement == "beside" and lay.scale < 1.0
    assert pygame.Rect(0, 0, w, h).contains(lay.scene)
    px = pygame.surfarray.array3d(app.window.surface)
    s = lay.scene
    for cx, cy in ((s.left + 3, s.top + 3), (s.right - 4, s.bottom - 4)):
        assert tuple(px[cx, cy]) == BORDER  # both corners of the scene are on screen
    for r in lay.charts:
        assert tuple(px[r.x + 3, r.y + 3]) == panels.BG and r.right <= w


# -- item 3: crisp at 1.5x and 2x ----------------------------------------------------------------


@pytest.mark.parametrize("scale", [1.5, 2.0])
def test_a_scaled_window_is_drawn_at_its_size(big_screen, on, scale):
    app = on(big_screen)
    app.window.resize((round(640 * scale), round(672 * scale)))
    assert where(big_screen, app)[2:] == (round(640 * scale), round(672 * scale))
    assert app.layout.scale == pytest.approx(scale)
    image = text_image("Evaporation cooling", round(40 * scale), (255, 255, 255))
    reference = pygame.Surface(image.get_size())
    reference.fill(BORDER)
    reference.blit(image, (0, 0))
    spot = image.get_rect(center=(round(320 * scale), round(25 * scale)))
    shown = pygame.surfarray.array3d(app.window.surface.subsurface(spot))
    np.testing.assert_array_equal(shown, pygame.surfarray.array3d(reference))
    # The border meets the play area in one step: no blurred in-between greys.
    row = pygame.surfarray.array3d(app.window.surface)[: round(60 * scale), 300, 0]
    assert set(row.tolist()) == {79, 159}


# -- item 5: the score stays in view over the table ------------------------------------------------


def test_the_score_stays_visible_when_the_table_opens(big_screen, on):
    app = on(big_screen)
    app.game.sim = Simulation(n_atoms=9, seed=0)
    app.game.paused = False
    settle(app, 0.1)
    app.game.sim.force_win()
    settle(app, 0.3)
    assert app.input.mode is Mode.NAME

    def letters():
        px = pygame.surfarray.array3d(app.window.surface).astype(int)
        box = px[SCORE_BOX.left : SCORE_BOX.right, SCORE_BOX.top : SCORE_BOX.bottom]
        return white(box[..., 0], box[..., 1], box[..., 2])

    before = letters()
    assert before.sum() > 300
    big_screen.xdotool("type", "--delay", "30", "Ada")
    big_screen.xdotool("key", "Return")
    settle(app)
    assert app.overlay == "table" and app.scores.stored_rank == 1
    np.testing.assert_array_equal(letters(), before)


# -- item 8: real mouse and keys, interleaved ------------------------------------------------------


def _mouse(server: XServer, app: App, *steps: str, until=None) -> None:
    """xdotool steps, then frames for 0.3 s; with until, on until it holds (at most 10 s):
    on a loaded machine the X server's events can take longer than 0.3 s to arrive."""
    server.xdotool(*steps)
    settle(app, 0.3)
    end = time.monotonic() + 10.0
    while until is not None and not until() and time.monotonic() < end:
        settle(app, 0.05)


def _at(app: App, logical: tuple[float, float]) -> list[str]:
    x, y = app.layout.scene.x + logical[0] * app.layout.scale, logical[1] * app.layout.scale
    move = ["mousemove", "--window", str(app.window.win.handle), str(round(x)), str(round(y))]
    return [*move, "sleep", "0.05"]  # so the pointer is there before what follows


def test_r_during_a_real_drag_and_a_chart_click_after_it(big_screen, on):
    app = on(big_screen)
    big_screen.xdotool("windowactivate", "--sync", str(app.window.win.handle))
    y = SLIDER_RECT.centery
    grabbed = lambda: app.input.mode is Mode.DRAG  # noqa: E731
    _mouse(big_screen, app, *_at(app, (SLIDER_RECT.left + 68, y)), "mousedown", "1", until=grabbed)
    assert app.input.mode is Mode.DRAG
    assert app.game.trap_height == pytest.approx(25 + 0.25 * 425, abs=2)
    _mouse(big_screen, app, "key", "r")
    assert app.game.trap_height == 400.0 and app.input.mode is Mode.PLAY
    _mouse(big_screen, app, *_at(app, (SLIDER_RECT.left, 300)))  # button still held
    assert app.game.trap_height == 400.0
    _mouse(big_screen, app, "mouseup", "1")
    assert app.game.trap_height == 400.0
    # A drag, its release and a click on the chart button, all before the next frame
    # (a few ms apart, as the X server's mouse and SDL's motion events keep order then).
    pause = ["sleep", "0.05"]
    steps = [*_at(app, (SLIDER_RECT.left + 136, y)), *pause, "mousedown", "1", *pause]
    steps += [*_at(app, (SLIDER_RECT.left + 68, 200)), *pause, "mouseup", "1", *pause]
    steps += [*_at(app, CHART_BUTTON_RECT.center), *pause, "click", "1"]
    _mouse(big_screen, app, *steps)
    assert app.charts.show_energy
    assert app.game.trap_height == pytest.approx(25 + 0.25 * 425, abs=2)


def test_keys_typed_into_the_name_box_are_letters(big_screen, on):
    app = on(big_screen)
    big_screen.xdotool("windowactivate", "--sync", str(app.window.win.handle))
    app.game.paused = False
    settle(app, 0.1)
    app.game.sim.force_win()
    settle(app, 0.2)
    sim = app.game.sim
    big_screen.xdotool("type", "--delay", "30", "r e+h")
    settle(app)
    assert app.scores.name_box is not None and app.scores.name_box.text == "r e+h"
    assert app.game.sim is sim and app.game.speed == 1.0 and app.overlay is None


# -- item 11: chart labels never crossed by data ---------------------------------------------------


def test_chart_labels_are_clear_of_data_in_a_real_window(big_screen, on):
    app = on(big_screen)
    key(app, pygame.K_e)
    key(app, pygame.K_g)
    app.game.paused = False
    app.game.set_trap_height(60.0)
    for _ in range(200):
        app.frame(None)
    settle(app, 0.2)
    px = pygame.surfarray.array3d(app.window.surface)
    for name in ("energy", "path"):
        panel = app.charts.panels[name]
        plot = panel.plot_rect(app.charts.rects[name])
        assert panel.label_rects
        for r in panel.label_rects:
            assert not r.colliderect(plot)
            cells = px[r.left : r.right, r.top : r.bottom]
            assert blends(cells, panels.BG, [panels.INK]).all(), (name, r)


# -- item 15: `evapcool bench` measures a real window when a display is there ------------------


def test_bench_measures_frames_in_a_real_window(small_screen, monkeypatch):
    from evapcool.bench import applet as bench

    pygame.display.quit()
    monkeypatch.setenv("DISPLAY", small_screen.display)
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    assert not bench.display_available()  # a forced dummy driver is no display
    monkeypatch.delenv("SDL_VIDEODRIVER")
    assert bench.display_available()
    drivers = []
    real = bench._time_frames

    def spy(app, pygame_, frames, window, out):
        drivers.append(pygame.display.get_driver())
        real(app, pygame_, frames, window, out)

    monkeypatch.setattr(bench, "_time_frames", spy)
    t = bench.measure(15, 1, window=True)
    assert drivers == ["x11"] and len(t["total"]) == 15
    assert np.all(t["drawing"] > 0) and np.all(t["total"] >= t["drawing"])
    assert "SDL_VIDEODRIVER" not in __import__("os").environ  # restored as it was
