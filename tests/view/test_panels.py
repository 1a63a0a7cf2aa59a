"""Energy and path panels, and the condensate drawing, checked headless against numpy."""

from __future__ import annotations

import math

import numpy as np
import pygame
import pytest
from apphelp import blends

from evapcool import Simulation, i18n
from evapcool.view import panels
from evapcool.view.condensate import Condensate, draw_condensate, packet_size
from evapcool.view.panels import EnergyPanel, PathPanel
from evapcool.view.pen import Pen
from evapcool.view.screen import ScreenMap

RECT = pygame.Rect(40, 30, 520, 340)
MAGENTA = (255, 0, 255)


@pytest.fixture(scope="module", autouse=True)
def _pygame() -> None:
    pygame.init()
    yield
    pygame.quit()


def _sim(**kw: object) -> Simulation:
    return Simulation.classic(seed=7, engine="reference", **kw)


def _surface() -> pygame.Surface:
    surf = pygame.Surface((640, 420))
    surf.fill(MAGENTA)
    return surf


# -- energy panel ---------------------------------------------------------------------
def test_single_frame_bars_equal_numpys_histogram() -> None:
    sim = _sim()
    panel = EnergyPanel(window_frames=1)
    for _ in range(5):
        sim.advance(1.0)
        panel.record(sim)
        expect, _ = np.histogram(sim.energies(), bins=panel.bin_edges)
        np.testing.assert_array_equal(panel.heights, expect)
        assert panel.heights.sum() == sim.n_trapped  # every trapped atom is in a bin


def test_smoothed_bars_are_the_mean_of_numpys_histograms_over_the_window() -> None:
    sim = _sim()
    sim.trap_height = 150.0  # atoms leave, so counts change from frame to frame
    panel = EnergyPanel(window_frames=6)
    per_frame = []
    edges0 = None
    for _ in range(20):
        sim.advance(1.0)
        panel.record(sim)
        if edges0 is None:
            edges0 = panel.bin_edges.copy()
        np.testing.assert_array_equal(panel.bin_edges, edges0)  # bins fixed for the run
        per_frame.append(np.histogram(sim.energies(), bins=panel.bin_edges)[0])
        expect = np.mean(per_frame[-6:], axis=0)
        np.testing.assert_allclose(panel.heights, expect, rtol=0, atol=1e-12)
    assert panel.frames_in_window == 6
    assert sim.n_trapped < sim.n_atoms  # the window really saw different frames


def test_bins_cover_the_starting_gas_and_the_cut() -> None:
    sim = _sim()
    panel = EnergyPanel()
    panel.record(sim)
    edges = panel.bin_edges
    assert edges[0] == 0.0
    assert edges[-1] >= sim.energies().max()
    assert edges[-1] >= sim.gravity * sim.trap_height
    np.testing.assert_allclose(np.diff(edges), np.diff(edges)[0])  # equal widths


def test_equilibrium_curve_holds_n_atoms() -> None:
    sim = _sim()
    panel = EnergyPanel()
    panel.record(sim)
    kt = 0.4 * sim.temperature
    assert panel.kt == pytest.approx(kt)
    es = np.linspace(0.0, 60.0 * kt, 200_001)
    area = np.trapezoid(panel.equilibrium_density(es), es)
    assert area == pytest.approx(sim.n_trapped, rel=1e-6)
    # Mean energy of the curve is 5/2 kT, i.e. the temperature (the seed's T).
    mean = np.trapezoid(es * panel.equilibrium_density(es), es) / area
    assert mean == pytest.approx(sim.temperature, rel=1e-6)
    # Per-bin expectation is N P(E) w at the bin centres, same bins as the bars.
    centres = 0.5 * (panel.bin_edges[1:] + panel.bin_edges[:-1])
    w = panel.bin_width
    expect = sim.n_trapped * centres**1.5 * np.exp(-centres / kt) / (0.75 * math.sqrt(math.pi))
    np.testing.assert_allclose(panel.equilibrium_counts(), expect * w / kt**2.5)


@pytest.mark.parametrize("height", [400.0, 180.0, 60.0])
def test_cut_line_sits_at_the_pixel_of_mgh(height: float) -> None:
    sim = _sim()
    sim.trap_height = height
    panel = EnergyPanel()
    panel.record(sim)
    surf = _surface()
    panel.draw(surf, RECT)
    plot = panel.plot_rect(RECT)
    e_max = panel.bin_edges[-1]
    mgh = float(sim.masses.mean()) * sim.gravity * height
    expect_x = round(plot.x + plot.w * mgh / e_max)
    assert panel.cut_x(RECT) == expect_x
    # The red line covers that column from top to bottom of the plot, below the label.
    fs = panels._font_size(RECT)
    for y in range(plot.y + 3 * fs, plot.bottom - 3, 7):
        assert tuple(surf.get_at((expect_x, y)))[:3] == panels.CUT, (expect_x, y)
    # ...and is 3 px wide, no more.
    y = plot.centery
    assert tuple(surf.get_at((expect_x - 2, y)))[:3] != panels.CUT
    assert tuple(surf.get_at((expect_x + 2, y)))[:3] != panels.CUT


def test_cut_line_follows_the_rim_between_frames() -> None:
    sim = _sim()
    panel = EnergyPanel()
    panel.record(sim)
    x400 = panel.cut_x(RECT)
    sim.trap_height = 200.0
    sim.advance(1.0)
    panel.record(sim)
    x200 = panel.cut_x(RECT)
    plot = panel.plot_rect(RECT)
    assert x200 - plot.x == pytest.approx((x400 - plot.x) / 2, abs=1)


def test_panels_draw_only_inside_their_rectangle() -> None:
    sim = _sim()
    ep, pp = EnergyPanel(), PathPanel()
    for _ in range(3):
        sim.advance(1.0)
        ep.record(sim)
        pp.record(sim)
    for panel in (ep, pp):
        surf = _surface()
        panel.draw(surf, RECT)
        arr = pygame.surfarray.array3d(surf)
        outside = np.ones(arr.shape[:2], dtype=bool)
        outside[RECT.left : RECT.right, RECT.top : RECT.bottom] = False
        assert np.all(arr[outside] == MAGENTA)
        inside = arr[RECT.left : RECT.right, RECT.top : RECT.bottom]
        assert not np.any(np.all(inside == MAGENTA, axis=-1))  # and fill all of it


def test_empty_panels_draw_without_data() -> None:
    surf = _surface()
    EnergyPanel().draw(surf, RECT)
    PathPanel().draw(surf, RECT)


def test_a_new_simulation_resets_the_energy_panel() -> None:
    panel = EnergyPanel(window_frames=10)
    sim = _sim()
    for _ in range(4):
        sim.advance(1.0)
        panel.record(sim)
    other = Simulation(n_atoms=20, radius=8.0, seed=3, engine="reference")
    panel.record(other)
    assert panel.frames_in_window == 1
    np.testing.assert_array_equal(
        panel.heights, np.histogram(other.energies(), bins=panel.bin_edges)[0]
    )


# -- path panel -----------------------------------------------------------------------
def test_one_point_per_recorded_frame() -> None:
    sim = _sim()
    sim.trap_height = 150.0
    panel = PathPanel()
    seen = []
    for k in range(1, 16):
        sim.advance(1.0)
        assert panel.record(sim)
        seen.append((sim.n_trapped, sim.temperature))
        assert len(panel.points) == k
    np.testing.assert_allclose(panel.points, np.array(seen))


def _tc_law(sim: Simulation):
    """Seed Eq. (46), written out independently of the panel."""
    tc0 = 0.75 * sim.initial_temperature
    return lambda n: tc0 * (n / sim.n_atoms) ** sim.tc_exponent


@pytest.mark.parametrize("tc_exponent", [2.0 / 3.0, 2.0 / 5.0])
def test_condensate_shading_is_exactly_where_t_is_below_tc(tc_exponent: float) -> None:
    sim = _sim(tc_exponent=tc_exponent)
    tc = _tc_law(sim)
    panel = PathPanel()
    panel.record(sim)
    surf = _surface()
    panel.draw(surf, RECT)
    plot = panel.plot_rect(RECT)
    arr = pygame.surfarray.array3d(surf)

    # Pixels drawn over the shading: text, the path marker, the T = Tc line (3 px).
    skip = np.zeros(arr.shape[:2], dtype=bool)
    for r in panel.overlay_rects:
        r = r.inflate(4, 4)
        skip[r.left : r.right, r.top : r.bottom] = True
    px, py = panel.pixel_of(*panel.points[-1], RECT)
    skip[px - 12 : px + 13, py - 12 : py + 13] = True

    shaded = unshaded = 0
    for x in range(plot.left + 3, plot.right - 3):
        # Screen y of the boundary T = Tc(N) in this column and its neighbours.
        ys = []
        for dx in (-1.0, 0.0, 1.0):
            n, _ = panel.from_pixel(x, plot.y, RECT)
            n_dx = n * (panel.n_range[1] / panel.n_range[0]) ** (dx / plot.w)
            ys.append(panel.to_pixel(n_dx, tc(n_dx), RECT)[1])
        for y in range(plot.top + 3, plot.bottom - 3):
            if skip[x, y]:
                continue
            n, t = panel.from_pixel(x, y, RECT)
            colour = tuple(arr[x, y])
            below = t < tc(n)
            allowed = {panels.CONDENSATE if below else panels.PLOT_BG}
            if min(ys) - 3 <= y <= max(ys) + 3:  # the line may cover these
                allowed.add(panels.TC_LINE)
            assert colour in allowed, (x, y, n, t, colour)
            shaded += below
            unshaded += not below
    assert shaded > 5000 and unshaded > 5000


def test_pixel_membership_matches_the_law_everywhere() -> None:
    sim = _sim()
    tc = _tc_law(sim)
    panel = PathPanel()
    panel.record(sim)
    plot = panel.plot_rect(RECT)
    for x in range(plot.left, plot.right, 3):
        for y in range(plot.top, plot.bottom, 3):
            n, t = panel.from_pixel(x, y, RECT)
            assert panel.pixel_in_condensate(x, y, RECT) == (t < tc(n))
    assert not panel.pixel_in_condensate(plot.left - 1, plot.bottom - 2, RECT)


def test_point_to_pixel_mapping_is_log_log() -> None:
    sim = _sim()
    panel = PathPanel()
    panel.record(sim)
    plot = panel.plot_rect(RECT)
    (n_lo, n_hi), (t_lo, t_hi) = panel.n_range, panel.t_range
    assert panel.to_pixel(n_lo, t_lo, RECT) == pytest.approx((plot.left, plot.bottom))
    assert panel.to_pixel(n_hi, t_hi, RECT) == pytest.approx((plot.right, plot.top))
    mid = panel.to_pixel(math.sqrt(n_lo * n_hi), math.sqrt(t_lo * t_hi), RECT)
    assert mid == pytest.approx(plot.center, abs=0.51)
    x, y = panel.to_pixel(*panel.from_pixel(123, 200, RECT), RECT)
    assert (x, y) == pytest.approx((123.5, 200.5))
    # The start point lies inside the frame, above the Tc line.
    n0, t0 = panel.points[0]
    assert plot.collidepoint(panel.pixel_of(n0, t0, RECT))
    assert not panel.in_condensate(n0, t0)
    assert panel.in_condensate(n0, 0.5 * sim.critical_temperature)


def test_recording_stops_after_the_win() -> None:
    sim = _sim()
    panel = PathPanel()
    sim.advance(1.0)
    assert panel.record(sim)
    sim.force_win()
    assert panel.record(sim)  # the winning frame is the path's last point
    sim.advance(1.0)
    assert not panel.record(sim)
    assert len(panel.points) == 2
    restarted = _sim()
    assert panel.record(restarted)  # a new run starts a new path
    assert len(panel.points) == 1


class _Fake:
    """Just enough of a Simulation to place points anywhere."""

    def __init__(self, n: int, t: float) -> None:
        self.n_atoms, self.n_trapped, self.temperature = 49, n, t
        self.initial_temperature, self.tc_exponent, self.won = 80.0, 2.0 / 3.0, False
        self.critical_temperature = 60.0 * (n / 49) ** (2.0 / 3.0) if n else 0.0


def test_empty_cup_adds_no_point_and_far_points_are_clamped() -> None:
    fake = _Fake(49, 80.0)
    panel = PathPanel()
    assert panel.record(fake)
    assert panel.tc(49) == pytest.approx(60.0)
    fake.n_trapped, fake.temperature = 0, 0.0
    assert not panel.record(fake)
    fake.n_trapped, fake.temperature = 3, 1e6  # far above the axis
    assert panel.record(fake)
    surf = _surface()
    panel.draw(surf, RECT)  # clamped into the frame, no error
    assert len(panel.points) == 2


# -- condensate -----------------------------------------------------------------------
def test_packet_grows_with_the_number_of_atoms() -> None:
    sizes = [packet_size(n, 12.0, 0.01) for n in (1, 10, 49)]
    assert sizes[0][0] < sizes[1][0] < sizes[2][0]
    assert sizes[0][1] < sizes[1][1] < sizes[2][1]
    assert packet_size(0, 12.0, 0.01) == (0.0, 0.0)


def test_condensate_appears_only_after_the_win_and_fades_in() -> None:
    sim = _sim()
    effect = Condensate(fade_seconds=1.0)
    surf = pygame.Surface((640, 672))
    surf.fill((159, 159, 159))
    before = pygame.surfarray.array3d(surf).copy()
    assert effect.draw(surf, sim, ScreenMap.of(sim).to_screen, 0.0) == 0.0
    np.testing.assert_array_equal(pygame.surfarray.array3d(surf), before)

    sim.force_win()
    levels = []
    for k in range(400):
        sim.advance(1.0)
        levels.append(effect.update(sim, k / 30.0))
    assert levels[0] == 0.0
    assert np.all(np.diff(levels) >= 0)  # never fades out
    assert levels[-1] == 1.0  # settled: speeds are down where the damping stops

    rect = draw_condensate(surf, sim, ScreenMap.of(sim).to_screen, 3.0)
    assert rect is not None
    bottom = ScreenMap.of(sim).to_screen(np.array([[0.0, -float(sim.radii.mean())]]))[0]
    assert rect.collidepoint(bottom)  # it sits at the bottom of the cup
    arr = pygame.surfarray.array3d(surf)
    cx, cy = rect.center
    assert tuple(arr[cx, cy]) != (159, 159, 159)
    assert arr[cx, cy, 0] > 200  # warm glow, unlike the cyan atoms
    assert draw_condensate(surf, sim, ScreenMap.of(sim).to_screen, 3.0, strength=0.0) is None


def test_panels_and_scene_text_survive_pygame_quit_and_init() -> None:
    # Fonts die with pygame's font module; an applet reopened in one process (a
    # notebook) must not draw with dead fonts.
    from evapcool.view import scene

    sim = _sim()
    for _ in range(2):
        energy, path = EnergyPanel(), PathPanel()
        energy.record(sim)
        path.record(sim)
        surface = _surface()
        energy.draw(surface, RECT)
        path.draw(surface, RECT)
        pen = Pen(pygame.Surface((640, 672)))
        scene.Scene().draw_too_few(pen, "All the atoms escaped.")
        pen.text("Ada 名字 علي", 24, (255, 255, 255))  # the fallback fonts too
        pygame.quit()
        pygame.init()


# -- labels never crossed by data (issue 14, item 11) ---------------------------------------------
DATA_COLOURS = (panels.BAR, panels.CUT, panels.PATH, panels.CONDENSATE, panels.TC_LINE)


def _runs(tc_exponent: float) -> list:
    """Energy and path charts in states where data reach every edge of their plots."""
    hot = _sim(tc_exponent=tc_exponent)
    hot.trap_height = 450.0  # the cut at the right edge
    low = _sim(tc_exponent=tc_exponent)
    low.trap_height = 25.0  # the cut at the left edge; the gas then cools along the path
    states = []
    for sim, frames in ((hot, 3), (low, 400)):
        energy, path = EnergyPanel(window_frames=1), PathPanel()
        for _ in range(frames):
            sim.advance(1.0)
            energy.record(sim)
            path.record(sim)
        states += [energy, path]
    far = PathPanel()  # a path running along the top and through the corner
    fake = _Fake(49, 80.0)
    for n, t in ((49, 1e6), (30, 1e6), (1, 1e6), (1, 1e-6)):
        fake.n_trapped, fake.temperature = n, t
        far.record(fake)
    return [*states, far]


@pytest.mark.parametrize("scale", [1.0, 1.5])
@pytest.mark.parametrize("tc_exponent", [2 / 3])
def test_no_label_is_crossed_by_data(scale: float, tc_exponent: float) -> None:
    rect = pygame.Rect(10, 10, round(520 * scale), round(336 * scale))
    for panel in _runs(tc_exponent):
        surf = pygame.Surface((rect.right + 10, rect.bottom + 10))
        panel.draw(surf, rect, scale)
        plot = panel.plot_rect(rect)
        px = pygame.surfarray.array3d(surf).astype(float)
        assert len(panel.label_rects) >= 5
        for r in panel.label_rects:
            assert not r.colliderect(plot), (type(panel).__name__, r, plot)
            cells = px[r.left : r.right, r.top : r.bottom]
            # Text is ink (or the cut's red, for nothing but the legend swatch's words) on
            # the panel's background: no bar, path or line colour anywhere in a label.
            clean = blends(cells, panels.BG, [panels.INK])
            assert clean.all(), (type(panel).__name__, r, int((~clean).sum()))
        # ...and the data stay inside the plot: none of their colours outside it, but
        # in the legend's swatches.
        outside = np.ones(px.shape[:2], dtype=bool)
        outside[plot.left : plot.right, plot.top : plot.bottom] = False
        for _, sw in panel.layout(rect).legend:
            outside[sw.left : sw.right, sw.top : sw.bottom] = False
        for colour in DATA_COLOURS:
            stray = np.all(px[outside] == np.array(colour), axis=-1)
            assert not stray.any(), (type(panel).__name__, colour)


def test_one_symbol_for_the_temperature() -> None:
    """The game's temperature is T everywhere: no 'kT' in the charts' words."""
    sim = _sim()
    for panel in (EnergyPanel(), PathPanel()):
        panel.record(sim)
        keys = [panel.title, panel.readout_template, *(i.text for i in panel.legend_items)]
        words = [i18n.t(k, n=1, t="1", tc="1") for k in keys]  # catalog keys, shown in English
        assert not any("kT" in w for w in words)
    energy = EnergyPanel()
    assert "T = " in i18n.t(energy.readout_template, n=1, t="1")
    assert "T" in i18n.t(energy.legend_items[1].text)


def test_after_the_win_both_charts_show_the_wins_temperature() -> None:
    """The energy chart holds the win's frame as the path chart does: while the atoms
    settle (T of the settling gas falls to ~0.4) both say the T of the win (issue 49.7)."""
    sim = _sim()
    energy, path = EnergyPanel(), PathPanel()
    sim.advance(1.0)
    energy.record(sim), path.record(sim)
    sim.force_win()
    energy.record(sim), path.record(sim)
    t_win, heights = sim.temperature, energy.heights.copy()
    for _ in range(240):
        sim.advance(1.0)
        energy.record(sim), path.record(sim)
    assert sim.temperature < 0.5 * t_win  # the atoms did settle
    assert energy.temperature == path.points[-1][1] == t_win
    np.testing.assert_array_equal(energy.heights, heights)
    energy.record(_sim())  # a new game records again
    assert energy.temperature == _sim().temperature
