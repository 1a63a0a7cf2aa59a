"""The applet driven through real pygame events (headless), checked by state and pixels."""

from __future__ import annotations

import numpy as np
import pygame
import pytest
from apphelp import SCORE_BOX, click, count, frames, key, pixels, post, white

from evapcool import Simulation, i18n
from evapcool.app.applet import HELP_ARGS, App
from evapcool.app.input import Mode
from evapcool.game import rules
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN
from evapcool.view.fonts import text_image
from evapcool.view.scene import (
    BORDER,
    PAUSE_RECT,
    PLAY_RECT,
    RESTART_RECT,
    SCALE_FULL,
    SCALE_ZERO,
    SLIDER_RECT,
    THERMO_X,
)
from evapcool.view.screen import ScreenMap

pytestmark = pytest.mark.usefixtures("own_folders")


def window_size(app: App) -> tuple[int, int]:
    return app.window.surface.get_size()


# -- the window ------------------------------------------------------------------------------


def test_window_is_the_original_layout(app):
    frames(app)
    assert app.window.win.title == "Evaporation cooling"
    assert window_size(app) == (640, 672)
    px = pixels(app)
    assert tuple(px[20, 300]) == BORDER  # left border
    assert tuple(px[600, 40]) != (159, 159, 159)
    assert tuple(px[PLAY_RECT.left + 3, PLAY_RECT.bottom - 3]) == (159, 159, 159)
    # Yellow buttons with black outline, at the original positions.
    for rect in (PAUSE_RECT, RESTART_RECT):
        r, g, b = px[rect.left + 10, rect.top + 10]
        assert r > 200 and g > 170 and b < 100
        assert tuple(px[rect.left + 2, rect.centery]) == (0, 0, 0)


def test_starts_paused_and_stays_still(app):
    assert app.game.paused
    frames(app, 5)
    assert app.game.sim.time == 0.0


def test_a_small_screen_gets_a_smaller_window_with_the_whole_scene(make_app):
    app = make_app(screen=(1024, 600))  # a netbook: 600 px minus the title and task bars
    frames(app)
    w, h = window_size(app)
    assert h <= 600 - 80 and (w, h) == (round(640 * h / 672), h)
    scene = app.layout.scene  # all of it, scaled down to the window (rounding: 1 px)
    assert scene.topleft == (0, 0) and scene.w == w and h - 1 <= scene.h <= h
    assert tuple(pixels(app)[5, h // 2]) == BORDER and tuple(pixels(app)[w - 5, 5]) == BORDER


# -- the mouse -------------------------------------------------------------------------------


def test_clicking_the_pause_button_toggles_pause(app):
    click(app, PAUSE_RECT.center)
    assert not app.game.paused
    t = app.game.sim.time
    frames(app, 3)
    assert app.game.sim.time == pytest.approx(t + 3.0)
    click(app, PAUSE_RECT.center)
    assert app.game.paused
    t = app.game.sim.time
    frames(app, 3)
    assert app.game.sim.time == t
    click(app, (PAUSE_RECT.right + 4, PAUSE_RECT.centery))  # just beside it: nothing
    assert app.game.paused


def test_dragging_the_slider_knob_sets_the_trap_height(app):
    y = SLIDER_RECT.centery
    knob_x = round(SLIDER_RECT.left + SLIDER_RECT.width * (400 - 25) / 425)
    post(pygame.MOUSEBUTTONDOWN, pos=(knob_x, y), button=1)
    frames(app)
    assert app.game.sim.trap_height == pytest.approx(400.0, abs=1.0)
    assert app.input.mode is Mode.DRAG
    post(pygame.MOUSEMOTION, pos=(SLIDER_RECT.left + 68, y), rel=(0, 0), buttons=(1, 0, 0))
    frames(app)
    assert app.game.sim.trap_height == pytest.approx(25 + 0.25 * 425)
    # The drag goes on off the bar while the button is held.
    post(pygame.MOUSEMOTION, pos=(SLIDER_RECT.left + 136, 300), rel=(0, 0), buttons=(1, 0, 0))
    frames(app)
    assert app.game.sim.trap_height == pytest.approx(25 + 0.5 * 425)
    post(pygame.MOUSEBUTTONUP, pos=(SLIDER_RECT.left + 136, 300), button=1)
    post(pygame.MOUSEMOTION, pos=(SLIDER_RECT.left, y), rel=(0, 0), buttons=(0, 0, 0))
    frames(app, 2)
    assert app.game.sim.trap_height == pytest.approx(25 + 0.5 * 425)
    assert app.input.mode is Mode.PLAY
    # The rim the atoms see moved: x_rim = sqrt(H / a).
    assert app.game.sim.rim_half_width == pytest.approx(np.sqrt(237.5 / 0.01))


def test_press_drag_and_release_within_one_frame_are_three_steps(app):
    y = SLIDER_RECT.centery
    post(pygame.MOUSEBUTTONDOWN, pos=(SLIDER_RECT.left, y), button=1)
    post(pygame.MOUSEMOTION, pos=(SLIDER_RECT.left + 68, y), rel=(0, 0), buttons=(1, 0, 0))
    post(pygame.MOUSEBUTTONUP, pos=(SLIDER_RECT.left + 68, y), button=1)
    post(pygame.MOUSEMOTION, pos=(SLIDER_RECT.right, y), rel=(0, 0), buttons=(0, 0, 0))
    frames(app)  # all four in one frame
    assert app.game.trap_height == pytest.approx(25 + 0.25 * 425)
    assert app.input.mode is Mode.PLAY and not app.slider.sliding


def test_clicking_restart_restores_49_atoms_height_400_paused(app):
    click(app, PAUSE_RECT.center)
    post(pygame.MOUSEBUTTONDOWN, pos=(SLIDER_RECT.left, SLIDER_RECT.centery), button=1)
    post(pygame.MOUSEBUTTONUP, pos=(SLIDER_RECT.left, SLIDER_RECT.centery), button=1)
    frames(app, 120)
    sim = app.game.sim
    assert sim.trap_height == HEIGHT_MIN and sim.n_trapped < 49 and sim.time > 0
    click(app, RESTART_RECT.center)
    new = app.game.sim
    assert new is not sim
    assert (new.n_trapped, new.trap_height, new.time) == (49, 400.0, 0.0)
    assert app.game.paused
    assert app.slider.value == pytest.approx(400.0)
    frames(app, 3)
    assert new.time == 0.0  # really paused


# -- the keyboard: every key does what the help overlay says ------------------------------------


def _toggle_pause(app, k):
    before = app.game.paused
    key(app, k)
    assert app.game.paused is (not before)
    key(app, k)
    assert app.game.paused is before


def _restart(app, k):
    app.game.paused = False
    app.game.set_trap_height(100)
    frames(app, 30)
    old = app.game.sim
    key(app, k)
    assert app.game.sim is not old
    assert (app.game.sim.n_trapped, app.game.trap_height, app.game.paused) == (49, 400.0, True)


def _height(delta):
    def check(app, k):
        h = app.game.trap_height
        key(app, k)
        assert app.game.trap_height == pytest.approx(h + delta)
        assert app.slider.value == pytest.approx(h + delta)
        app.game.set_trap_height(HEIGHT_MAX if delta > 0 else HEIGHT_MIN)
        key(app, k)  # clamped at the end of the range
        assert app.game.trap_height == (HEIGHT_MAX if delta > 0 else HEIGHT_MIN)

    return check


def _step(app, k):
    assert app.game.paused
    key(app, k)
    assert app.game.sim.time == pytest.approx(1.0)
    app.game.paused = False
    t = app.game.sim.time
    key(app, k)  # while playing S adds nothing beyond the frame itself
    assert app.game.sim.time == pytest.approx(t + 1.0)


def _speed(factor):
    def check(app, k):
        key(app, k)
        assert app.game.speed == pytest.approx(factor)
        for _ in range(5):
            key(app, k)
        assert app.game.speed == (4.0 if factor > 1 else 0.25)
        app.game.paused = False
        t = app.game.sim.time
        frames(app)
        assert app.game.sim.time == pytest.approx(t + app.game.speed)

    return check


def _fullscreen(app, k):
    key(app, k)
    assert app.fullscreen
    assert window_size(app) == pygame.display.get_desktop_sizes()[0]
    key(app, k)
    assert not app.fullscreen
    assert window_size(app) == (640, 672)


def _help(app, k):
    box = PLAY_RECT.inflate(-40, -200)
    key(app, k)
    assert app.overlay == "help"
    px = pixels(app)[box.left : box.right, box.top : box.bottom]
    dark = np.count_nonzero(np.all(px < 60, axis=-1))
    assert dark > 0.5 * px.shape[0] * px.shape[1]  # the panel covers the play area
    key(app, k)
    assert app.overlay is None


def _escape(app, k):
    key(app, pygame.K_h)
    key(app, k)
    assert app.overlay is None and app.running
    app.toggle_fullscreen()
    key(app, k)
    assert not app.fullscreen and app.running  # leaves full screen first
    key(app, k)
    assert not app.running


def _chart(attr):
    def check(app, k):
        key(app, k)
        assert getattr(app.charts, attr)
        assert window_size(app) == (640 + 520, 672)  # beside the scene at the same scale
        key(app, k)
        assert not getattr(app.charts, attr)
        assert window_size(app) == (640, 672)

    return check


def _table(app, k):
    key(app, k)
    assert app.overlay == "table"
    key(app, k)
    assert app.overlay is None


def _ask_reset(app, k):
    key(app, k)
    assert app.overlay == "table" and app.input.mode is Mode.CONFIRM_CLEAR
    key(app, pygame.K_n)
    assert app.input.mode is Mode.TABLE and app.overlay == "table"


def _next_player(app, k):
    old = app.game.sim
    key(app, k)  # nothing to do before a score was stored
    assert app.game.sim is old
    app.scores.ready_for_next = True
    key(app, k)
    assert app.game.sim is not old and not app.scores.ready_for_next


def _settings(app, k):
    key(app, k)
    assert app.overlay == "settings"
    key(app, k)  # O closes it again; nothing changed, so nothing is written
    assert app.overlay is None and not app.options.path.exists()


def _copy_replay(app, k):
    key(app, k)  # before a win there is no code: nothing happens
    assert app.visible_notices == [] and not app.replay_offered
    app.game.sim.force_win()
    frames(app)
    app.replays.code = "EC1.test.00000000"  # as after a win (tests/app/test_app_replay.py)
    key(app, k)
    assert pygame.scrap.get_text() == "EC1.test.00000000"


def _save_run(app, k):
    key(app, k)
    assert app.teaching.saved is not None and app.teaching.saved.suffix == ".csv"
    assert app.visible_notices[-1].startswith("Run saved: ")


def _describe(app, k):
    key(app, k)
    assert app.visible_notices[-1].startswith("Atoms in the cup: 49;")


def _mute(app, k):
    heard = app.teaching.sound.audible
    key(app, k)
    assert app.teaching.sound.audible is not heard or not app.teaching.sound.available


def _autopilot(app, k):
    key(app, k)  # the demo takes the trap...
    assert app.autopilot.engaged and app.autopilot.name == "demo"
    key(app, k)  # ...and hands it back
    assert not app.autopilot.engaged


KEY_CHECKS = {
    pygame.K_SPACE: _toggle_pause,
    pygame.K_r: _restart,
    pygame.K_LEFT: _height(-5.0),
    pygame.K_DOWN: _height(-5.0),
    pygame.K_RIGHT: _height(5.0),
    pygame.K_UP: _height(5.0),
    pygame.K_s: _step,
    pygame.K_PLUS: _speed(2.0),
    pygame.K_EQUALS: _speed(2.0),
    pygame.K_KP_PLUS: _speed(2.0),
    pygame.K_MINUS: _speed(0.5),
    pygame.K_KP_MINUS: _speed(0.5),
    pygame.K_F11: _fullscreen,
    pygame.K_h: _help,
    pygame.K_F1: _help,
    pygame.K_ESCAPE: _escape,
    pygame.K_e: _chart("show_energy"),
    pygame.K_g: _chart("show_path"),
    pygame.K_t: _table,
    pygame.K_DELETE: _ask_reset,
    pygame.K_x: _ask_reset,
    pygame.K_RETURN: _next_player,
    pygame.K_KP_ENTER: _next_player,
    pygame.K_o: _settings,
    pygame.K_a: _autopilot,
    pygame.K_c: _copy_replay,
    pygame.K_w: _save_run,
    pygame.K_d: _describe,
    pygame.K_m: _mute,
}


@pytest.mark.parametrize("k", list(KEY_CHECKS), ids=pygame.key.name)
def test_key_does_what_the_help_says(app, k):
    KEY_CHECKS[k](app, k)


def test_every_bound_key_is_checked_and_listed_in_the_help(app):
    bound = {k for b in app.bindings for k in b.keys}
    assert bound == set(KEY_CHECKS)
    rows = app.help_rows()
    for b in app.bindings:  # labels and help are catalog keys, shown translated
        assert any(what == i18n.t(b.help, **HELP_ARGS) for _, what in rows), b.help
    labels = " ".join(label for label, _ in rows)
    names = ("Space", "R", "Left", "Right", "Up", "Down", "S", "+", "-", "F11", "H", "F1")
    for name in (*names, "E", "G", "T", "O", "Delete", "X", "Enter", "A", "C", "W", "D", "M"):
        assert name in labels
    assert "Esc" in labels and "Mouse" in labels
    # The reset confirmation and the settings keys are spelled out too.
    text = " ".join(what for _, what in rows)
    assert "Y clears" in text and "N or Esc" in text
    assert "Left/Right change" in text


def test_shifted_plus_on_any_layout_speeds_up(app):
    post(pygame.KEYDOWN, key=pygame.K_8, mod=pygame.KMOD_SHIFT, unicode="+", scancode=0)
    frames(app)
    assert app.game.speed == 2.0


# -- what the screen shows ----------------------------------------------------------------------


def test_screenshot_shows_cup_atoms_and_mercury_at_t_over_1_2_t0(app, tmp_path):
    app.run_frames(40)
    path = tmp_path / "shot.png"
    app.screenshot(path)
    img = pygame.image.load(str(path))
    assert img.get_size() == (640, 672)
    px = pygame.surfarray.array3d(img).astype(int)
    sim = app.game.sim

    # The cup: a black band below the lowest point, and at the rim.
    assert all(tuple(px[296, y]) == (0, 0, 0) for y in range(545, 549))
    assert tuple(px[296, 538]) != (0, 0, 0)
    x_rim = sim.rim_half_width
    rim_sx, rim_sy = ScreenMap.of(sim).to_screen(np.array([x_rim, sim.trap_height]))
    n = np.array([-2 * 0.01 * x_rim, 1.0]) / np.hypot(2 * 0.01 * x_rim, 1.0)
    band = (rim_sx - 15 * n[0] * 1.0, rim_sy + 15 * n[1])  # R + 3 px outside the wall
    assert tuple(px[round(band[0] - 1), round(band[1])]) == (0, 0, 0)

    # Every trapped atom: cyan at its centre.
    centres = ScreenMap.of(sim).to_screen(sim.positions)
    inside = [c for c in centres if PLAY_RECT.collidepoint(c)]
    assert len(inside) >= 40
    for cx, cy in inside:
        r, g, b = px[int(cx), int(cy)]
        assert b > 150 and g > 150 and r < 160, (cx, cy, (r, g, b))

    # The mercury top at the row T / (1.2 T0) predicts.
    f = sim.temperature / (1.2 * sim.initial_temperature)
    assert 0.3 < f < 1.0
    expected = round(SCALE_ZERO - f * (SCALE_ZERO - SCALE_FULL))
    column = px[THERMO_X]
    red = [y for y in range(672) if column[y][0] > 180 and column[y][1] < 80]
    assert min(red) == expected
    # ...and the Tc line at its own row, labelled.
    tc_row = round(
        SCALE_ZERO - sim.critical_temperature / (1.2 * sim.initial_temperature) * (SCALE_ZERO - 88)
    )
    assert tuple(px[THERMO_X - 14, tc_row]) == (0, 0, 0)


def test_forced_win_stops_collisions_and_shows_the_score(app):
    app.run_frames(20)
    assert count(app, SCORE_BOX, white) == 0
    before = app.game.sim.pair_collision_count
    frames(app, 10)
    assert app.game.sim.pair_collision_count > before  # collisions happen while playing
    app.game.sim.force_win()
    frames(app)
    won_with = app.game.sim.n_trapped
    pairs = app.game.sim.pair_collision_count
    energy = app.game.sim.total_energy()
    app.game.set_speed(4.0)
    frames(app, 150)
    sim = app.game.sim
    assert sim.pair_collision_count == pairs
    assert sim.total_energy() < 0.5 * energy  # damped bounces: the atoms settle
    assert app.game.score == won_with > 0  # fixed when the gas condensed
    assert count(app, SCORE_BOX, white) > 300  # "Score: N" in large text
    # The trap is frozen once the gas has condensed.
    post(pygame.MOUSEBUTTONDOWN, pos=(SLIDER_RECT.left, SLIDER_RECT.centery), button=1)
    post(pygame.MOUSEBUTTONUP, pos=(SLIDER_RECT.left, SLIDER_RECT.centery), button=1)
    frames(app)
    assert sim.trap_height == 400.0


# -- too few atoms (issue 14, item 6) --------------------------------------------------------------


def _one_escaping_atom() -> Simulation:
    # Thrown up and out: it meets the wall line at x ~ 88 px, beyond a rim at 50 px.
    return Simulation(n_atoms=1, radius=12.0, positions=[[0.0, 10.0]], velocities=[[8.0, 8.0]])


def test_empty_cup_says_too_few_atoms_and_r_restarts(app):
    app.game.sim = _one_escaping_atom()
    app.game.set_trap_height(25.0)
    app.game.paused = False
    frames(app, 2)
    assert app.game.too_few_atoms == "One atom alone cannot cool below Tc."
    for _ in range(200):
        frames(app)
        if app.game.sim.n_trapped == 0:
            break
    frames(app)
    assert app.game.all_escaped and app.game.too_few_atoms == "All the atoms escaped."
    assert count(app, SCORE_BOX, white) > 300  # "Too few atoms left" in large text
    key(app, pygame.K_r)
    assert app.game.sim.n_trapped == 49 and app.game.too_few_atoms is None
    frames(app)
    assert count(app, SCORE_BOX, white) == 0


def test_two_cold_atoms_that_cannot_leave_are_too_few(app):
    # Both far below the lowest rim's energy, and hotter than Tc(2): nothing can change.
    sim = Simulation(
        n_atoms=2,
        radius=12.0,
        positions=[[-30.0, 9.5], [30.0, 9.5]],
        velocities=[[0.3, 0.0], [-0.3, 0.0]],
    )
    app.game.sim = sim
    assert sim.temperature > sim.critical_temperature
    assert sim.total_energy() < 1.0 * sim.gravity * rules.HEIGHT_MIN
    frames(app)
    assert app.game.too_few_atoms == "No atom can leave any more: T stays above Tc."
    assert count(app, SCORE_BOX, white) > 300


# -- the window scales, drawn at its size ---------------------------------------------------------


def test_resized_window_scales_the_scene_and_the_mouse(app):
    frames(app)
    small = pixels(app).copy()
    app.window.win.size = (1280, 1344)  # what a user's resize does
    frames(app)
    big = pixels(app)
    assert big.shape[:2] == (1280, 1344)
    for x, y in ((20, 300), (600, 300), (PAUSE_RECT.left + 10, PAUSE_RECT.top + 10)):
        assert np.abs(big[2 * x, 2 * y] - small[x, y]).max() < 40
    click(app, (2 * PAUSE_RECT.centerx, 2 * PAUSE_RECT.centery))
    assert not app.game.paused


def test_wide_window_keeps_the_aspect_with_bars(app):
    app.window.win.size = (1000, 672)
    frames(app)
    px = pixels(app)
    assert tuple(px[50, 300]) == (0, 0, 0)  # bar at the side
    assert tuple(px[180 + 20, 300]) == BORDER  # scene starts at (1000 - 640) / 2


def _ramp_pixels(profile: np.ndarray) -> int:
    """Pixels of a 1-D profile unlike both neighbours: the in-between shades of a blur."""
    p = profile.astype(int)
    return int(np.count_nonzero((p[1:-1] != p[:-2]) & (p[1:-1] != p[2:])))


@pytest.mark.parametrize("scale", [1.5, 2.0])
def test_a_scaled_scene_is_drawn_at_its_size_with_sharp_edges(app, scale):
    """Borders and the slider bar: one-pixel edges at 1.5x and 2x, not a blurred bitmap."""
    app.window.win.size = (round(640 * scale), round(672 * scale))
    frames(app)
    px = pixels(app).sum(axis=-1)
    assert app.layout.scale == pytest.approx(scale)
    # Left border to play area: grey 79 to grey 159 in at most one pixel's step.
    row = px[round(40 * scale) : round(56 * scale), round(300 * scale)]
    assert _ramp_pixels(row) == 0 and len(set(row.tolist())) == 2
    # The slider bar's top edge (white on the dark border), along a column.
    x = round((SLIDER_RECT.left + 30) * scale)
    col = px[x, round((SLIDER_RECT.top - 6) * scale) : round((SLIDER_RECT.top + 3) * scale)]
    assert _ramp_pixels(col) == 0 and set(col.tolist()) == {3 * 79, 0, 3 * 255}
    # The title is the text drawn at 40 x scale px, pixel for pixel, not a scaled 40 px one.
    image = text_image("Evaporation cooling", round(40 * scale), (255, 255, 255))
    reference = pygame.Surface(image.get_size())
    reference.fill(BORDER)
    reference.blit(image, (0, 0))
    where = image.get_rect(center=(round(320 * scale), round(25 * scale)))
    shown = pygame.surfarray.array3d(app.window.surface.subsurface(where))
    np.testing.assert_array_equal(shown, pygame.surfarray.array3d(reference))


def test_closing_the_window_quits(app):
    post(pygame.QUIT)
    frames(app)
    assert not app.running


def test_interactive_loop_runs_on_the_wall_clock_and_quits_on_escape(app):
    app.game.paused = False
    post(pygame.KEYDOWN, key=pygame.K_ESCAPE, mod=0, unicode="", scancode=0)
    app.run()  # returns once Esc is handled
    assert not app.running


# -- frame rate and bounded physics (issue 14, item 15) -------------------------------------------


def test_a_slow_frame_advances_the_physics_by_the_bounded_step_only(app):
    app.game.paused = False
    app.game.set_speed(2.0)
    t = app.game.sim.time
    app.frame(0.5)  # a frame that took half a second
    step = rules.MAX_WALL_STEP * 30 * 2.0
    assert app.game.sim.time == pytest.approx(t + step)
    app.frame(0.01)  # a quick one advances by its own time
    assert app.game.sim.time == pytest.approx(t + step + 0.01 * 30 * 2.0)
    assert app.stats.pace is not None and app.stats.pace < 0.3


def test_the_loop_slows_the_game_when_frames_fall_behind(app, monkeypatch):
    class SlowClock:
        def tick(self, fps=0):
            return 400  # every frame took 0.4 s

    app.clock = SlowClock()
    app.game.paused = False
    calls = []
    real = app.frame

    def counted(seconds):
        calls.append(seconds)
        if len(calls) == 4:
            app.running = False
        real(seconds)

    monkeypatch.setattr(app, "frame", counted)
    app.run()
    assert calls == [0.4, 0.4, 0.4, 0.4]
    assert app.game.sim.time == pytest.approx(3 * rules.MAX_WALL_STEP * 30)  # the 4th quit
    assert any("falls behind" in line or "fall behind" in line for line in app.stats.lines())


def test_help_shows_the_frame_rate_and_times(app):
    app.game.paused = False
    frames(app, 5)
    key(app, pygame.K_h)
    lines = app.stats.lines()
    assert lines[0].startswith("Frame rate") and "physics" in lines[0] and "drawing" in lines[0]
    assert app.stats.fps > 0 and app.stats.drawing_ms > 0
    # The readout is drawn: the help panel's light-blue footer text is on screen.
    blue = count(app, PLAY_RECT, lambda r, g, b: (b > 230) & (g > 200) & (r > 170) & (r < 215))
    assert blue > 100
