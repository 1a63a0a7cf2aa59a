"""The energy and path charts inside the applet, driven by posted events, checked by pixels."""

from __future__ import annotations

import numpy as np
import pygame
import pytest
from apphelp import click, frames, key

from evapcool.app.applet import App
from evapcool.app.charts import CHART_BUTTON_RECT
from evapcool.physics.simulation import GRAVITY
from evapcool.view.panels import BAR, CONDENSATE, CUT, PLOT_BG
from evapcool.view.scene import SCENE_SIZE


def window_size(app: App) -> tuple[int, int]:
    return app.window.surface.get_size()


def chart_pixels(app: App, name: str) -> tuple[np.ndarray, pygame.Rect]:
    """(x, y, rgb) pixels of the window, and one chart's rectangle in them."""
    return pygame.surfarray.array3d(app.window.surface), app.charts.rects[name]


def is_color(px: np.ndarray, color: tuple[int, int, int]) -> np.ndarray:
    return np.all(px == np.array(color), axis=-1)


# -- toggling ----------------------------------------------------------------------------------


def test_e_and_the_button_toggle_the_energy_chart(app):
    frames(app)
    assert window_size(app) == SCENE_SIZE
    key(app, pygame.K_e)
    assert window_size(app) == (SCENE_SIZE[0] + 520, SCENE_SIZE[1])
    px, rect = chart_pixels(app, "energy")
    assert rect == pygame.Rect(SCENE_SIZE[0], 0, 520, SCENE_SIZE[1])  # alone: the whole column
    plot = app.charts.energy.plot_rect(rect)
    area = px[plot.left : plot.right, plot.top : plot.bottom]
    assert np.count_nonzero(is_color(area, BAR)) > 500  # the start's histogram is drawn
    key(app, pygame.K_e)
    assert window_size(app) == SCENE_SIZE and not app.charts.show_energy

    click(app, CHART_BUTTON_RECT.center, move=False)
    assert app.charts.show_energy and window_size(app)[0] == SCENE_SIZE[0] + 520
    click(app, CHART_BUTTON_RECT.center, move=False)
    assert not app.charts.show_energy and window_size(app) == SCENE_SIZE


def test_g_toggles_the_path_chart_and_both_share_the_column(app):
    key(app, pygame.K_g)
    assert app.charts.show_path and window_size(app)[0] == SCENE_SIZE[0] + 520
    px, rect = chart_pixels(app, "path")
    plot = app.charts.path.plot_rect(rect)
    area = px[plot.left : plot.right, plot.top : plot.bottom]
    assert np.count_nonzero(is_color(area, CONDENSATE)) > 1000  # the shaded region
    key(app, pygame.K_e)
    energy, path = app.charts.rects["energy"], app.charts.rects["path"]
    assert energy.bottom <= path.top and energy.h == path.h == SCENE_SIZE[1] // 2
    key(app, pygame.K_g)
    assert "path" not in app.charts.rects and window_size(app)[0] > SCENE_SIZE[0]
    key(app, pygame.K_e)
    assert window_size(app) == SCENE_SIZE and app.charts.shown == []


# -- the energy histogram ------------------------------------------------------------------


def test_bars_equal_numpys_histogram_of_the_energies_after_real_frames(app):
    key(app, pygame.K_e)
    key(app, pygame.K_SPACE)
    panel = app.charts.energy
    edges = panel.bin_edges.copy()
    counts = []
    for _ in range(45):
        frames(app)
        counts.append(np.histogram(app.game.sim.energies(), bins=edges)[0])
    assert app.game.sim.time >= 45
    expected = np.mean(counts[-panel.window_frames :], axis=0)
    np.testing.assert_allclose(panel.heights, expected)
    assert expected.sum() == pytest.approx(app.game.sim.n_trapped, abs=3)

    # Each bar is drawn from the axis up to the row of its height.
    px, rect = chart_pixels(app, "energy")
    plot = panel.plot_rect(rect)
    xs = plot.x + plot.w * edges / edges[-1]
    cut = panel.cut_x(rect)
    checked = 0
    for i, h in enumerate(expected):
        xc = (round(xs[i]) + round(xs[i + 1])) // 2
        if abs(xc - cut) <= 3:
            continue  # the cut line is drawn over the bars
        column = is_color(px[xc, plot.top + 2 : plot.bottom], BAR)
        rows = np.flatnonzero(column) + plot.top + 2
        top = round(plot.bottom - plot.h * h / panel._y_max)
        if top >= plot.bottom:
            assert rows.size == 0
            continue
        assert rows.min() >= top, (i, h)
        assert rows.size >= 0.6 * (plot.bottom - top), (i, h)  # the curve may cross it
        checked += 1
    assert checked >= 5


def test_cut_line_sits_at_the_pixel_of_m_g_h(app):
    key(app, pygame.K_e)
    key(app, pygame.K_SPACE)
    frames(app, 3)
    panel = app.charts.energy
    for presses in (0, 20):  # as built, then with the trap 100 px lower
        for _ in range(presses):
            key(app, pygame.K_DOWN)
        h = app.game.trap_height
        e_cut = 1.0 * GRAVITY * h  # atoms of mass 1
        px, rect = chart_pixels(app, "energy")
        plot = panel.plot_rect(rect)
        x = round(plot.x + plot.w * e_cut / panel.bin_edges[-1])
        y = plot.bottom - 6
        assert all(tuple(px[x + dx, y]) == CUT for dx in (-1, 0, 1)), (h, x)
        assert tuple(px[x + 3, y]) != CUT and tuple(px[x - 3, y]) != CUT
    assert app.game.trap_height == 300.0


# -- the path in the (N, T) plane ----------------------------------------------------------------


def test_path_adds_a_point_per_recorded_frame_and_none_while_paused(app):
    key(app, pygame.K_g)
    panel = app.charts.path
    assert len(panel.points) == 1  # the start, recorded once
    frames(app, 5)
    assert len(panel.points) == 1  # paused: nothing new
    key(app, pygame.K_SPACE)  # unpauses within this frame, which then advances
    frames(app, 7)
    assert len(panel.points) == 1 + 8
    sim = app.game.sim
    assert tuple(panel.points[-1]) == (sim.n_trapped, pytest.approx(sim.temperature))
    key(app, pygame.K_SPACE)
    frames(app, 3)
    assert len(panel.points) == 9
    key(app, pygame.K_s)  # one frame forward while paused is a recorded frame
    assert len(panel.points) == 10
    key(app, pygame.K_r)  # a restart starts a new path (and a new histogram)
    assert len(panel.points) == 1 and app.charts.energy.frames_in_window == 1


@pytest.mark.parametrize("p", [2 / 3, 2 / 5])
def test_path_shading_is_where_t_is_below_tc_of_n(make_app, p):
    app = make_app(tc_exponent=p)
    key(app, pygame.K_g)
    key(app, pygame.K_SPACE)
    frames(app, 10)
    panel = app.charts.path
    px, rect = chart_pixels(app, "path")
    plot = panel.plot_rect(rect).inflate(-6, -6)
    sim = app.game.sim
    tc0, n0 = 0.75 * sim.initial_temperature, sim.n_atoms
    (n_lo, n_hi), (t_lo, t_hi) = panel.n_range, panel.t_range
    full = panel.plot_rect(rect)
    skip = [r.inflate(4, 4) for r in panel.overlay_rects]
    agree = shaded = clear = 0
    for x in range(plot.left, plot.right, 3):
        n = n_lo * (n_hi / n_lo) ** ((x + 0.5 - full.x) / full.w)
        for y in range(plot.top, plot.bottom, 3):
            if any(r.collidepoint(x, y) for r in skip):
                continue
            colour = tuple(px[x, y])
            if colour not in (CONDENSATE, PLOT_BG):
                continue  # the Tc line, the path, the marker
            t = t_lo * (t_hi / t_lo) ** ((full.bottom - (y + 0.5)) / full.h)
            below = t < tc0 * (n / n0) ** p
            agree += below == (colour == CONDENSATE)
            shaded += colour == CONDENSATE
            clear += colour == PLOT_BG
    assert shaded > 500 and clear > 500
    assert agree == shaded + clear
