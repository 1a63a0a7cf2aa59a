"""Issue 13, item 2: a starting state is checked (no overlap, centres in the cup), fast."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from evapcool import Simulation
from evapcool.limits import POSITION_MAX, VELOCITY_MAX
from evapcool.physics.loading import load_cup
from evapcool.physics.validation import check_world, first_outside, first_overlap
from evapcool.physics.world import ESCAPED, World

A = 0.01


def brute_first_overlap(pos: np.ndarray, radii: np.ndarray) -> tuple[int, int] | None:
    d = pos[:, None, :] - pos[None, :, :]
    d2 = d[..., 0] ** 2 + d[..., 1] ** 2
    sigma = radii[:, None] + radii[None, :]
    close = np.triu(d2 < sigma * sigma, k=1)
    pairs = np.argwhere(close)
    return (int(pairs[0, 0]), int(pairs[0, 1])) if len(pairs) else None


_states = st.integers(2, 40).flatmap(
    lambda n: st.tuples(
        hnp.arrays(float, (n, 2), elements=st.floats(-60, 60)),
        hnp.arrays(
            float,
            (n,),
            elements=st.one_of(st.floats(0.01, 0.1), st.floats(0.5, 3), st.floats(5, 30)),
        ),
    )
)


@settings(max_examples=300, deadline=None)
@given(_states)
def test_grid_finds_the_same_first_pair_as_all_pairs(state) -> None:
    pos, radii = state
    assert first_overlap(pos, radii) == brute_first_overlap(pos, radii)


def test_touching_is_allowed_and_a_hair_closer_is_not() -> None:
    radii = np.array([1.0, 1.0])
    assert first_overlap(np.array([[0.0, 5.0], [2.0, 5.0]]), radii) is None
    assert first_overlap(np.array([[0.0, 5.0], [2.0 - 1e-6, 5.0]]), radii) == (0, 1)


def test_the_first_offending_pair_is_named() -> None:
    pos = [(-100, 300), (0, 300), (100, 300), (5, 300)]  # 1 and 3 overlap
    with pytest.raises(ValueError, match=r"positions must not overlap.*atoms 1 and 3 are"):
        Simulation(4, positions=pos, velocities=np.zeros((4, 2)))
    pos = [(-100, 300), (-95, 300), (0, 300), (5, 300)]  # 0-1 and 2-3: 0 and 1 first
    with pytest.raises(ValueError, match="atoms 0 and 1 are"):
        Simulation(4, positions=pos, velocities=np.zeros((4, 2)))


def test_centres_below_the_wall_are_named_and_on_it_accepted() -> None:
    x = np.array([-50.0, 0.0, 30.0])
    on_wall = np.column_stack((x, A * x * x))
    assert first_outside(on_wall, A) is None
    Simulation(3, radius=5.0, positions=on_wall, velocities=np.zeros((3, 2)))
    below = on_wall.copy()
    below[2, 1] -= 1e-3
    assert first_outside(below, A) == 2
    with pytest.raises(ValueError, match="atom 2 at"):
        Simulation(3, radius=5.0, positions=below, velocities=np.zeros((3, 2)))


def test_far_positions_and_fast_atoms_are_refused() -> None:
    with pytest.raises(ValueError, match="positions must be within"):
        Simulation(1, positions=[(0.0, 2 * POSITION_MAX)], velocities=[(0.0, 0.0)])
    with pytest.raises(ValueError, match=r"velocities must be at most .*atom 1 has"):
        Simulation(
            2,
            positions=[(-50, 300), (50, 300)],
            velocities=[(0.0, 0.0), (VELOCITY_MAX, 1.0)],
        )


@pytest.mark.parametrize(
    ("positions", "velocities", "word"),
    [
        ([(0, 1)], None, "velocities"),
        (None, [(0, 1)], "positions"),
        ([(0, float("nan"))], [(0, 0)], "positions"),
        ([(0, 100)], [(0, float("inf"))], "velocities"),
        ([(0, 100), (1, 2)], [(0, 0)], "positions"),
        ("lots", [(0, 0)], "positions"),
        ([(0, 100)], {"a": 1}, "velocities"),
    ],
)
def test_malformed_states_name_the_array(positions, velocities, word) -> None:
    with pytest.raises(ValueError, match=word):
        Simulation(1, positions=positions, velocities=velocities)


def test_a_hundred_thousand_atoms_are_checked() -> None:
    # The loader's start is valid; moving one atom onto another is found (a grid, not N^2).
    pos, _vel = load_cup(100_000, 0.35, A, 543.0, seed=3)
    radii = np.full(len(pos), 0.35)
    assert first_overlap(pos, radii) is None
    pos[77_777] = pos[12_345] + (0.1, 0.0)
    assert first_overlap(pos, radii) == (12_345, 77_777)


def test_a_heap_of_atoms_on_one_point_is_answered() -> None:
    # Work stays bounded for the worst input: every atom on the same spot.
    pos = np.tile([0.0, 10.0], (20_000, 1))
    assert first_overlap(pos, np.full(20_000, 1.0)) == (0, 1)


def test_wide_radius_mixtures_use_levels() -> None:
    # One huge atom among many small ones: found without comparing everything to everything.
    small = np.column_stack((np.arange(20_000) * 0.05 - 500.0, np.full(20_000, 5000.0)))
    pos = np.vstack((small, [[0.0, 2000.0]]))
    radii = np.append(np.full(20_000, 0.02), 500.0)
    assert first_overlap(pos, radii) is None
    pos[-1] = (0.0, 4600.0)  # now it reaches the row of small atoms
    d = np.hypot(*(small - pos[-1]).T)
    first_small = int(np.flatnonzero(d < 500.02)[0])
    assert first_overlap(pos, radii) == (first_small, 20_000)


def _world(pos, **overrides) -> World:
    n = len(pos)
    fields = dict(
        pos=np.array(pos, dtype=float),
        vel=np.zeros((n, 2)),
        radius=np.full(n, 5.0),
        mass=np.ones(n),
        curvature=A,
        gravity=1 / 3,
        trap_height=400.0,
        x_left=-300.0,
        x_right=300.0,
        y_bottom=-100.0,
    )
    return World(**{**fields, **overrides})


def test_a_world_from_elsewhere_gets_the_same_checks() -> None:
    # For states read from files: ranges, and the trapped atoms now, named by their index.
    w = _world([(0, 100), (200, 50), (3, 100)])
    w.status[1] = ESCAPED  # an escaped atom may be anywhere
    with pytest.raises(ValueError, match="atoms 0 and 2 are"):
        check_world(w)
    w.status[2] = ESCAPED
    check_world(w)
    with pytest.raises(ValueError, match=r"^gravity"):
        check_world(_world([(0, 100)], gravity=1e300))
    with pytest.raises(ValueError, match=r"^mass .*atom 1 has 2000.0"):
        check_world(_world([(0, 100), (50, 100)], mass=np.array([1.0, 2e3])))


def test_a_state_from_a_file_gets_the_same_ranges_and_check() -> None:
    from evapcool.physics.simulation import Simulation
    from evapcool.physics.state import check_placement

    atoms = {"x": [0.0], "y": [100.0], "vx": [0.0], "vy": [0.0]}
    with pytest.raises(ValueError, match=r"^gravity must be a number from"):
        Simulation.from_state({"gravity": 1e300, "atoms": atoms})
    with pytest.raises(ValueError, match=r"^velocities must be at most"):
        Simulation.from_state({"atoms": {**atoms, "vx": [500.0]}})
    # A column of atoms (one x): the grid finds the first overlap; a sweep along x was O(N^2).
    n = 50_000
    y = 10.0 + 2.0 * np.arange(n)
    y[-1] = y[-2] + 1.5
    ones = np.ones(n)
    with pytest.raises(ValueError, match=f"atoms {n - 2} and {n - 1} overlap"):
        check_placement("state.atoms", np.zeros(n), y, ones, ones > 0, A, 1e-9)
