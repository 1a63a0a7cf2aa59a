"""No state stalls the engines: grazing and resting atoms advance with bounded events.

Exact elastic dynamics of an atom on the wall is an endless run of ever shorter hops, so
a bounce leaves the wall at least WALL_MIN_NORMAL_SPEED along the normal
(kernels.bounce_wall). These states used to hang both engines (issue 13, bug 1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from evapcool import Simulation
from evapcool.physics.kernels import bounce_wall
from evapcool.physics.world import WALL_MIN_NORMAL_SPEED

A = 0.01
G = 10.0 / 30.0
V_MIN = WALL_MIN_NORMAL_SPEED


def one_atom(engine: str, x: float, y: float, vx: float, vy: float) -> Simulation:
    return Simulation(
        n_atoms=1, radius=12.0, positions=[[x, y]], velocities=[[vx, vy]], engine=engine,
        trap_height=450.0,
    )  # fmt: skip


def hop_bound(sim: Simulation, frames: float) -> float:
    """Most wall events a lone atom can have in `frames`: every hop lasts at least
    v_min / (g/2 + a v^2), v^2 at most 2 E / m."""
    v2 = 2.0 * sim.total_energy()
    return 2.0 + frames * (0.5 * G + A * v2) / V_MIN


def run(sim: Simulation, frames: int) -> list[int]:
    counts = []
    for _ in range(frames):
        before = sim.wall_collision_count
        sim.advance(1.0)
        counts.append(sim.wall_collision_count - before)
    return counts


def test_atom_at_rest_on_the_vertex_rests(engine):
    sim = one_atom(engine, 0.0, 1e-300, 0.0, 0.0)
    counts = run(sim, 30)
    # hops of 2 v_min / g = 0.006 frames: about 167 bounces a frame, never more than 170
    assert max(counts) <= 170
    x, y = sim.positions[0]
    assert x == 0.0
    assert 0.0 <= y <= V_MIN**2 / (2 * G) * (1 + 1e-9)  # 1.5e-6 px: at rest to the eye
    # it gained at most the energy of the floor speed, once
    assert sim.total_energy() <= 0.5 * V_MIN**2 * (1 + 1e-9)


def test_grazing_atom_slides_with_energy_conserved(engine):
    x = 50.0
    t = np.array([1.0, 2 * A * x]) / math.hypot(1.0, 2 * A * x)
    sim = one_atom(engine, x, A * x * x + 1e-9, 3 * t[0], 3 * t[1])
    e0 = sim.total_energy()
    counts = run(sim, 30)
    assert sum(counts) <= hop_bound(sim, 30)
    assert abs(sim.total_energy() - e0) <= 1e-12 * e0


@pytest.mark.parametrize("y_above", [0.0, "ulp", 1e-12])
def test_atom_at_rest_on_the_slope_rolls_down_and_back(engine, y_above):
    x = 50.0
    wall = A * x * x
    y = np.nextafter(wall, 1e9) if y_above == "ulp" else wall + y_above
    sim = one_atom(engine, x, y, 0.0, 0.0)
    e0 = sim.total_energy()
    xs = []
    for _ in range(120):
        sim.advance(1.0)
        xs.append(sim.positions[0, 0])
    assert sim.wall_collision_count <= hop_bound(sim, 120)
    # frictionless sliding: down through the vertex to the other side, nearly as high
    assert min(xs) < -49.0
    # the floor speed added at most m v_min^2 / 2, the rest is exact
    assert abs(sim.total_energy() - e0) <= 0.5 * V_MIN**2 * (1 + 1e-6) + 1e-12 * e0


def test_tangent_on_the_wall_exactly(engine):
    """C == 0 and B == 0: the contact is now, and the bounce must leave the wall."""
    sim = one_atom(engine, 0.0, 0.0, 2.0, 0.0)
    e0 = sim.total_energy()
    counts = run(sim, 10)
    assert sum(counts) <= hop_bound(sim, 10)
    assert abs(sim.total_energy() - e0) <= 1e-12 * e0


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    x=st.floats(-150.0, 150.0),
    above=st.sampled_from([0.0, 1e-300, 1e-15, 1e-9, 1e-3]),
    speed=st.one_of(st.just(0.0), st.floats(0.0, 1e-3), st.floats(0.0, 8.0)),
    angle=st.floats(0.0, 2 * math.pi),
    engine=st.sampled_from(["reference", "fast"]),
)
def test_any_state_near_the_wall_advances_with_bounded_events(x, above, speed, angle, engine):
    y = A * x * x
    y = y + above if above else np.nextafter(y, math.inf)
    sim = one_atom(engine, x, y, speed * math.cos(angle), speed * math.sin(angle))
    e0 = sim.total_energy()
    run(sim, 3)
    assert sim.wall_collision_count <= hop_bound(sim, 3)
    assert abs(sim.total_energy() - e0) <= 0.5 * V_MIN**2 * (1 + 1e-6) + 1e-12 * e0
    px, py = sim.positions[0]
    assert py >= A * px * px - 1e-9 * (1 + py)


@settings(max_examples=300, deadline=None)
@given(
    x=st.floats(-200.0, 200.0),
    vx=st.floats(-20.0, 20.0),
    vy=st.floats(-20.0, 20.0),
)
def test_bounce_leaves_inwards_at_least_v_min_with_the_same_speed(x, vx, vy):
    ux, uy = bounce_wall(x, vx, vy, A, V_MIN)
    nn = math.hypot(-2 * A * x, 1.0)
    un = (ux * (-2 * A * x) + uy) / nn
    assert un >= V_MIN * (1 - 1e-9)
    v2 = vx * vx + vy * vy
    if v2 >= V_MIN * V_MIN:
        assert math.isclose(ux * ux + uy * uy, v2, rel_tol=1e-12, abs_tol=1e-300)
    else:
        assert math.isclose(math.hypot(ux, uy), V_MIN, rel_tol=1e-12)


def test_without_the_win_rule_the_gas_goes_on_below_tc(engine):
    """win=False (issue 13, item 5): T < Tc(N) ends nothing, collisions go on."""
    sims = [Simulation.classic(seed=2, engine=engine, win=w) for w in (True, False)]
    for sim in sims:
        for frame in range(1800):  # the best linear ramp of the game, 400 -> 140 px
            sim.trap_height = 400.0 - 260.0 * frame / 1800
            sim.advance(1.0)
    won, free = sims
    assert won.won and won.temperature < won.critical_temperature
    assert not free.won and free.temperature < free.critical_temperature
    pairs = free.pair_collision_count
    free.advance(100.0)
    assert free.pair_collision_count > pairs  # still a gas


def test_win_must_be_a_bool():
    with pytest.raises(ValueError, match="win"):
        Simulation.classic(seed=1, win="no")
