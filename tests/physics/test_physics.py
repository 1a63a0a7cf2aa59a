"""Physics core: analytic cases, invariants, lifecycle and validation, on both engines."""

from __future__ import annotations

import math

import numpy as np
import pytest

from evapcool import Simulation
from evapcool.physics.room import Room
from evapcool.physics.simulation import GRAVITY

G = GRAVITY
A = 0.01


def make(engine: str, pos, vel, **kw) -> Simulation:
    """A simulation with exactly these atoms (trap coordinates)."""
    pos = np.asarray(pos, dtype=float)
    kw.setdefault("trap_height", math.inf)
    kw.setdefault("record_events", True)
    return Simulation(len(pos), positions=pos, velocities=vel, engine=engine, **kw)


def kinds(sim: Simulation) -> list[str]:
    return [e[0] for e in sim.event_log]


# -- atom-atom collisions (seed Eqs. 10-19) ---------------------------------------


def test_head_on_unequal_masses(engine: str) -> None:
    # m1 = 1 at -50 moving +2, m2 = 3 at +50 moving -1, same height: contact after 76/3 frames.
    sim = make(engine, [(-50, 200), (50, 200)], [(2, 0), (-1, 0)], mass=[1.0, 3.0])
    e0 = sim.total_energy()
    sim.advance(30.0)
    assert kinds(sim) == ["pair"]
    assert sim.event_log[0][3] == pytest.approx(76 / 3, rel=1e-12)
    v = sim.velocities
    # 1D elastic: v1' = ((m1 - m2) v1 + 2 m2 v2) / (m1 + m2) = -2.5, v2' = 0.5
    assert v[0, 0] == pytest.approx(-2.5, abs=1e-12)
    assert v[1, 0] == pytest.approx(0.5, abs=1e-12)
    assert v[0, 1] == pytest.approx(-G * 30, abs=1e-12)
    assert v[1, 1] == pytest.approx(-G * 30, abs=1e-12)
    assert 1 * v[0, 0] + 3 * v[1, 0] == pytest.approx(1 * 2 + 3 * -1, abs=1e-12)
    assert sim.total_energy() == pytest.approx(e0, rel=1e-14)


def test_glancing_collision_unequal_masses(engine: str) -> None:
    # Impact parameter 12 = sigma / 2: the line of centres is 30 degrees below horizontal.
    sim = make(engine, [(-60, 300), (0, 288)], [(3, 0), (0, 0)], mass=[2.0, 1.0])
    p0 = 2 * 3.0
    e0 = sim.total_energy()
    sim.advance(14.0)
    assert kinds(sim) == ["pair"]
    tc = (60 - math.sqrt(24**2 - 12**2)) / 3
    assert sim.event_log[0][3] == pytest.approx(tc, rel=1e-12)
    v = sim.velocities
    s3 = math.sqrt(3.0)
    # Hand-computed: n = (sqrt3/2, -1/2), n.(v1 - v2) = 3 sqrt3 / 2,
    # v1' = v1 - (2 m2 / M) dv n, v2' = v2 + (2 m1 / M) dv n.
    assert v[0, 0] == pytest.approx(1.5, abs=1e-12)
    assert v[0, 1] == pytest.approx(s3 / 2 - G * 14, abs=1e-12)
    assert v[1, 0] == pytest.approx(3.0, abs=1e-12)
    assert v[1, 1] == pytest.approx(-s3 - G * 14, abs=1e-12)
    assert 2 * v[0, 0] + v[1, 0] == pytest.approx(p0, abs=1e-12)
    assert sim.total_energy() == pytest.approx(e0, rel=1e-14)


#: Exactly touching (24 px apart): a valid start, "at least r_i + r_j apart".
TOUCHING = 12.0


def test_touching_approaching_pair_collides_at_once_and_does_not_stick(engine: str) -> None:
    sim = make(engine, [(-TOUCHING, 300), (TOUCHING, 300)], [(1, 0), (-1, 0)])
    sim.advance(0.0)
    sim.advance(40.0)
    pair_events = [e for e in sim.event_log if e[0] == "pair"]
    assert len(pair_events) == 1
    assert pair_events[0][3] == 0.0
    p = sim.positions
    assert abs(p[1, 0] - p[0, 0]) > 24.0


def test_touching_receding_pair_is_ignored(engine: str) -> None:
    sim = make(engine, [(-TOUCHING, 300), (TOUCHING, 300)], [(-1, 0), (1, 0)])
    sim.advance(20.0)
    assert sim.pair_collision_count == 0
    v = sim.velocities
    assert v[0, 0] == -1.0 and v[1, 0] == 1.0


# -- atom-wall collisions (SPEC 2.1) ---------------------------------------------


def test_dropped_on_vertex_returns_to_start_height(engine: str) -> None:
    sim = make(engine, [(0, 100)], [(0, 0)])
    t_fall = math.sqrt(2 * 100 / G)
    sim.advance(2 * t_fall)
    assert kinds(sim) == ["wall"]
    assert sim.event_log[0][3] == pytest.approx(t_fall, rel=1e-12)
    (_x, y), (vx, vy) = sim.positions[0], sim.velocities[0]
    assert y == pytest.approx(100.0, abs=1e-9)
    assert vx == 0.0 and abs(vy) < 1e-9


def test_steep_wall_reflects_about_tangent(engine: str) -> None:
    sim = make(engine, [(0, 200)], [(8, 0)])
    t_hit = math.sqrt(200 / (G / 2 + A * 64))
    sim.advance(t_hit - 1e-9)
    assert sim.wall_collision_count == 0
    v_in = sim.velocities[0].copy()
    sim.advance(2e-9)
    assert sim.wall_collision_count == 1
    t_ev = sim.event_log[0][3]
    assert t_ev == pytest.approx(t_hit, rel=1e-12)
    x_c = 8 * t_ev
    v_in = np.array([8.0, -G * t_ev])
    m = 2 * A * x_c  # tangent slope, about 2.5: a steep part of the wall
    assert m > 2
    reflect = np.array([[1 - m * m, 2 * m], [2 * m, m * m - 1]]) / (1 + m * m)
    expected = reflect @ v_in
    v_out = sim.velocities[0] - np.array([0.0, -G * (sim.time - t_ev)])
    assert v_out == pytest.approx(expected, abs=1e-12)
    assert np.linalg.norm(v_out) == pytest.approx(np.linalg.norm(v_in), rel=1e-14)


@pytest.mark.parametrize("delta, escapes", [(1e-6, True), (-1e-6, False)])
def test_rim_decides_escape_or_bounce(engine: str, delta: float, escapes: bool) -> None:
    # A throw from (0, 50) that meets the wall at x_c = x_rim + delta after 20 frames.
    height = 100.0
    x_c = math.sqrt(height / A) + delta
    t_c = 20.0
    vy = (A * x_c * x_c - 50 + G / 2 * t_c * t_c) / t_c
    sim = make(engine, [(0, 50)], [(x_c / t_c, vy)], trap_height=height)
    sim.advance(t_c + 1.0)
    assert kinds(sim) == (["escape"] if escapes else ["wall"])
    assert sim.event_log[0][3] == pytest.approx(t_c, rel=1e-12)
    assert sim.n_trapped == (0 if escapes else 1)
    assert sim.wall_collision_count == (0 if escapes else 1)


def test_escaped_atom_falls_out_and_is_gone(engine: str) -> None:
    sim = make(engine, [(0, 50)], [(5, 6)], trap_height=30.0)
    sim.advance(25.0)  # meets the wall at t = 20.3, x = 101 > x_rim = 54.8
    assert sim.n_trapped == 0
    sim.advance(200.0)
    assert kinds(sim) == ["escape", "gone"]
    assert sim.n_escaped == 0
    assert sim.temperature == 0.0


def test_trapped_atom_is_never_removed_however_high(engine: str) -> None:
    # Thrown far above the window top: still trapped, comes back and bounces.
    sim = make(engine, [(0, 10)], [(0, 40)])
    sim.advance(100.0)
    assert sim.positions[0, 1] > 544
    assert sim.n_trapped == 1
    sim.advance(200.0)
    assert sim.n_trapped == 1 and sim.wall_collision_count >= 1


def test_lowering_rim_lets_high_atoms_escape_only_at_the_wall(engine: str) -> None:
    # An atom high in the cup stays trapped until it crosses the wall outside the new rim.
    sim = make(engine, [(0, 300)], [(0, 0)], trap_height=400.0)
    sim.advance(1.0)
    sim.trap_height = 100.0
    assert sim.n_trapped == 1
    sim.advance(100.0)  # falls straight down the axis: bounces at the vertex
    assert sim.n_trapped == 1
    side = make(engine, [(0, 300)], [(3, 0)], trap_height=400.0)
    side.trap_height = 100.0
    side.advance(100.0)
    assert side.n_trapped == 0 and kinds(side)[0] == "escape"


def test_knife_removes_atoms_above_mgh(engine: str) -> None:
    pos = [(-100, 150), (0, 20), (100, 150)]
    vel = [(0, 0), (0, 0), (0, 0)]
    sim = make(engine, pos, vel, escape="knife", trap_height=400.0)
    assert sim.n_trapped == 3
    sim.trap_height = 100.0  # energies m g y: 150 g > 100 g > 20 g
    assert sim.n_trapped == 1
    assert sim.positions[0] == pytest.approx([0, 20])


# -- the win (seed Eq. 46 and Eq. 34) ----------------------------------------------


def test_win_stops_pair_collisions_and_damps_bounces(engine: str) -> None:
    sim = Simulation.classic(seed=3, engine=engine)
    sim.advance(20.0)
    assert not sim.won
    sim.force_win()
    pairs = sim.pair_collision_count
    e0 = sim.total_energy()
    sim.advance(600.0)
    assert sim.pair_collision_count == pairs
    assert sim.total_energy() < 0.5 * e0
    # Settled: every atom slow and low in the cup.
    assert np.all(np.linalg.norm(sim.velocities, axis=1) < 2.0)


@pytest.mark.parametrize("seed, escape", [(1, "rim"), (2, "rim"), (4, "knife"), (5, "knife")])
def test_settled_condensate_bounces_at_a_bounded_rate(engine: str, seed: int, escape: str) -> None:
    # Damped bounces must not collapse (ever faster bounces of atoms sliding in the bowl).
    sim = Simulation.classic(seed=seed, engine=engine, escape=escape)
    sim.advance(30.0)
    sim.force_win()
    sim.advance(600.0)
    before = sim.wall_collision_count
    sim.advance(300.0)
    per_atom_frame = (sim.wall_collision_count - before) / (300.0 * sim.n_trapped)
    assert per_atom_frame < 2.0
    assert np.all(np.linalg.norm(sim.velocities, axis=1) < 1.0)
    assert np.all(sim.positions[:, 1] < 3.0)  # settled at the bottom


def test_damped_bounce_keeps_a_floor_on_the_normal_speed() -> None:
    from evapcool.physics.kernels import settle_wall

    # A grazing hit: after damping the inward normal speed is lifted to the floor.
    x, a = 30.0, 0.01
    n = np.array([-2 * a * x, 1.0]) / math.hypot(2 * a * x, 1.0)
    t = np.array([n[1], -n[0]])
    v = 3.0 * t - 0.01 * n
    u = np.array(settle_wall(x, v[0], v[1], a, 0.8, 0.25))
    assert u @ n == pytest.approx(0.25, rel=1e-12)
    assert u @ t == pytest.approx(0.8 * 3.0, rel=1e-12)
    assert u @ u < v @ v


def test_low_rim_cools_the_gas(engine: str) -> None:
    sim = Simulation.classic(seed=2, engine=engine)
    t0 = sim.temperature
    sim.trap_height = 60.0
    sim.advance(600.0)
    assert sim.n_trapped < 49
    assert sim.temperature < t0


def test_win_when_temperature_falls_below_tc() -> None:
    # A gentle ramp from the classic start reaches T < Tc(N) and latches the win.
    sim = Simulation.classic(seed=1)
    heights = np.linspace(400, 40, 1800)
    for h in heights:
        sim.trap_height = float(h)
        sim.advance(1.0)
        if sim.won:
            break
    assert sim.won
    assert sim.n_trapped > 0
    assert sim.temperature < Simulation.classic(seed=1).initial_temperature


def test_critical_temperature_law() -> None:
    sim = Simulation.classic(seed=5)
    assert sim.critical_temperature == pytest.approx(0.75 * sim.initial_temperature)
    sim2 = Simulation.classic(seed=5, tc_exponent=0.4)
    assert sim2.tc_exponent == 0.4


# -- loading (SPEC 1) ------------------------------------------------------------------


def test_classic_start_is_reproducible_and_valid() -> None:
    a, b = Simulation.classic(seed=7), Simulation.classic(seed=7)
    assert np.array_equal(a.positions, b.positions)
    assert np.array_equal(a.velocities, b.velocities)
    assert not np.array_equal(a.positions, Simulation.classic(seed=8).positions)
    p, v = a.positions, a.velocities
    assert len(p) == 49 and a.n_trapped == 49
    d = np.linalg.norm(p[:, None] - p[None], axis=-1) + np.eye(49) * 1e9
    assert d.min() >= 24.0
    assert np.all(p[:, 1] > A * p[:, 0] ** 2)
    # Row 0: one atom near the centre; speeds rise with height (v0 = 100/30, dv = 10/30 per 40 px).
    assert abs(p[0, 0]) <= 8.0 and p[0, 1] <= 17.0
    speed = np.linalg.norm(v, axis=1)
    level = (p[:, 1] - p[0, 1]) / 40.0
    assert np.all(speed >= 100 / 30 + (level - 0.5) * 10 / 30)
    assert np.all(speed <= 100 / 30 + (level + 1.5) * 10 / 30)


def test_loading_scales_with_radius() -> None:
    sim = Simulation(n_atoms=3000, radius=2.0, seed=1, engine="reference")
    p = sim.positions
    assert np.all(p[:, 1] > A * p[:, 0] ** 2)
    from evapcool.physics.loading import cell_centres

    c = cell_centres(3000, 2.0, A, 540.0)
    assert np.diff(np.unique(c[:, 1])).min() == pytest.approx(2 * 2.0 * 20 / 12)


# -- long runs: exact to round-off --------------------------------------------------------


def _check_invariants(sim: Simulation, e0: float, size: float) -> None:
    p = sim.positions
    r = sim.radii
    assert np.all(np.isfinite(p)) and np.all(np.isfinite(sim.velocities))
    diff = p[:, None, :] - p[None, :, :]
    dist = np.sqrt((diff**2).sum(-1))
    sigma = r[:, None] + r[None, :]
    np.fill_diagonal(dist, np.inf)
    assert np.min(dist - sigma) > -1e-9 * r.min(), "pair overlap"
    below = A * p[:, 0] ** 2 - p[:, 1]
    assert np.max(below) < 1e-9 * size, "wall penetration"
    assert abs(sim.total_energy() - e0) / e0 < 1e-9, "energy drift"


# The core on three starts; the reference (a minute a start) on one: the golden traces
# already hold the core to the reference event for event.
@pytest.mark.slow
@pytest.mark.parametrize(
    ("engine", "seed"),
    [("reference", 1), ("fast", 1), ("fast", 2), ("fast", 3)],
    indirect=["engine"],
)
def test_long_run_is_exact(engine: str, seed: int) -> None:
    sim = Simulation.classic(seed=seed, engine=engine, trap_height=math.inf)
    e0 = sim.total_energy()
    size = 1.0 / A
    for _ in range(30):
        sim.advance(1000.0)
        _check_invariants(sim, e0, size)
    assert sim.n_trapped == 49
    assert sim.pair_collision_count > 10_000


def test_mixed_radii_and_masses_stay_exact(engine: str) -> None:
    # Per-atom radius and mass: the classic start with smaller, unequal atoms.
    start = Simulation.classic(seed=11)
    rng = np.random.default_rng(11)
    radii = rng.uniform(5.0, 12.0, 49)
    masses = rng.uniform(0.5, 3.0, 49)
    sim = Simulation(
        49,
        radius=radii,
        mass=masses,
        positions=start.positions,
        velocities=start.velocities,
        trap_height=math.inf,
        engine=engine,
    )
    e0 = sim.total_energy()
    for _ in range(4):
        sim.advance(500.0)
        _check_invariants(sim, e0, 1.0 / A)
    assert sim.pair_collision_count > 1000
    assert np.array_equal(sim.radii, radii) and np.array_equal(sim.masses, masses)


# -- validation -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"n_atoms": -3}, "n_atoms"),
        ({"n_atoms": 2.5}, "n_atoms"),
        ({"radius": 0}, "radius"),
        ({"radius": float("nan")}, "radius"),
        ({"radius": 40.0}, "n_atoms"),
        ({"mass": -1}, "mass"),
        ({"curvature": float("inf")}, "curvature"),
        ({"gravity": 0}, "gravity"),
        ({"trap_height": float("nan")}, "trap_height"),
        ({"trap_height": -5}, "trap_height"),
        ({"engine": "warp"}, "engine"),
        ({"escape": "teleport"}, "escape"),
        ({"seed": -1}, "seed"),
        ({"room": (640, 672)}, "room"),
        ({"room": Room(296.0, 344.0, 128.0, -5.0)}, "room"),
        ({"tc_exponent": 0}, "tc_exponent"),
    ],
)
def test_bad_input_names_the_parameter(kwargs: dict, name: str) -> None:
    with pytest.raises(ValueError, match=name):
        Simulation(**kwargs)


def test_positions_must_start_inside_the_cup() -> None:
    with pytest.raises(ValueError, match=r"positions .*atom 0"):
        Simulation(1, positions=[(0.0, -1e-9)], velocities=[(0.0, 0.0)])
    with pytest.raises(ValueError, match=r"positions .*atom 1 "):
        Simulation(2, positions=[(0.0, 300.0), (100.0, 50.0)], velocities=[(0, 0), (0, 0)])
    # On the wall is inside (the lead's change of issue 13).
    assert Simulation(1, positions=[(0.0, 0.0)], velocities=[(0.0, 0.0)]).n_trapped == 1


def test_bad_advance_and_height() -> None:
    sim = Simulation.classic(seed=1)
    with pytest.raises(ValueError, match="dt"):
        sim.advance(-1.0)
    with pytest.raises(ValueError, match="dt"):
        sim.advance(float("nan"))
    with pytest.raises(ValueError, match="trap_height"):
        sim.trap_height = float("nan")
