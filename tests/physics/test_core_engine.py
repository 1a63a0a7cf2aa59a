"""The compiled core (engine 'fast', issue 32): the reference engine's events exactly, sound at
10 000 atoms, built without contraction."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from evapcool import Simulation
from evapcool.physics.world import TRAPPED


def _grid_errors(sim: Simulation) -> int:
    """Trapped atoms beyond their cell and its skin in the compiled core's grid (0 if sound)."""
    return int(sim._engine.core.grid_errors())


def _pair_run(
    n: int,
    seed: int,
    frames: int,
    changes: dict[int, float] | None = None,
    force_win_at: int | None = None,
    **kw: object,
) -> tuple[Simulation, Simulation]:
    """Both engines from the same start, driven alike frame by frame."""
    sims = [
        Simulation(n_atoms=n, seed=seed, engine=e, record_events=True, **kw)
        for e in ("reference", "fast")
    ]
    for f in range(frames):
        for sim in sims:
            if changes and f in changes:
                sim.trap_height = changes[f]
            if f == force_win_at:
                sim.force_win()
            sim.advance(1.0)
    return sims[0], sims[1]


def _assert_same(ref: Simulation, fast: Simulation) -> None:
    """The same events (atoms, order and times, to the last bit) and the same end state."""
    assert fast.event_log == ref.event_log
    wa, wb = ref._world, fast._world
    for name in ("status", "pos", "vel", "t_atom"):
        np.testing.assert_array_equal(getattr(wb, name), getattr(wa, name), err_msg=name)
    np.testing.assert_array_equal(fast.positions, ref.positions)
    assert (fast.pair_collision_count, fast.wall_collision_count, fast.n_trapped, fast.won) == (
        ref.pair_collision_count,
        ref.wall_collision_count,
        ref.n_trapped,
        ref.won,
    )
    assert wb.energy_sum == wa.energy_sum
    assert _grid_errors(fast) == 0


def test_engine_is_fast() -> None:
    assert Simulation(n_atoms=5, radius=2.0, seed=0, engine="fast").engine == "fast"


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_same_events_classic_1000_frames(seed: int) -> None:
    ref, fast = _pair_run(49, seed, 1000)
    assert ref.pair_collision_count > 5000  # a real, chaotic gas
    _assert_same(ref, fast)


def test_same_events_trap_lowered_mid_run() -> None:
    # The slider moves between frames: the rim alone decides bounce vs escape.
    ref, fast = _pair_run(50, 7, 1000, changes={200: 250.0, 500: 120.0, 800: 200.0}, radius=8.0)
    assert ref.n_trapped < 50
    _assert_same(ref, fast)


def test_same_events_escape_heavy() -> None:
    ref, fast = _pair_run(50, 4, 600, trap_height=60.0, radius=6.0)
    kinds = {e[0] for e in ref.event_log}
    assert {"escape", "gone"} <= kinds
    assert ref.n_trapped < 25
    _assert_same(ref, fast)


def test_same_events_knife() -> None:
    ref, fast = _pair_run(
        50, 5, 800, changes={100: 300.0, 400: 150.0}, trap_height=400.0, escape="knife", radius=6.0
    )
    assert sum(e[0] == "knife" for e in ref.event_log) > 3
    _assert_same(ref, fast)


def test_same_events_after_forced_win() -> None:
    # Pairs stop, wall bounces lose 20 % of speed, the energy sum follows.
    ref, fast = _pair_run(49, 9, 400, force_win_at=150)
    assert ref.won
    _assert_same(ref, fast)
    assert fast._world.energy_sum == ref._world.energy_sum


def test_same_events_win_by_cooling() -> None:
    # Lowering the rim far evaporates the hot atoms until T < Tc(N) is reached.
    ref, fast = _pair_run(40, 11, 900, changes={100: 60.0, 400: 40.0}, radius=10.0)
    _assert_same(ref, fast)


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    seed=st.integers(0, 2**31 - 1),
    n=st.integers(2, 60),
    hot=st.floats(1.0, 8.0),
    rule=st.sampled_from(["rim", "knife"]),
    fall=st.floats(0.3, 0.95),
)
def test_same_events_random_states(seed: int, n: int, hot: float, rule: str, fall: float) -> None:
    """Mixed radii and masses, a few hot atoms, either escape rule, a rim falling in steps:
    the reference engine and the core agree to the last bit (issue 32)."""
    rng = np.random.default_rng(seed)
    start = Simulation(n_atoms=n, radius=8.0, seed=seed % 1000, engine="reference")
    radii = rng.uniform(2.0, 8.0, n)  # placed for radius 8: no overlaps
    masses = rng.uniform(0.5, 3.0, n)
    vel = start._world.vel.copy()
    vel[rng.random(n) < 0.1] *= hot
    sims = [
        Simulation(n, radius=radii, mass=masses, positions=start._world.pos, velocities=vel,
                   engine=e, escape=rule, record_events=True, trap_height=450.0)
        for e in ("reference", "fast")
    ]  # fmt: skip
    height = 450.0
    for frame in range(120):
        if frame % 20 == 19:
            height = max(25.0, height * fall)
        for sim in sims:
            if frame % 20 == 19:
                sim.trap_height = height
            sim.advance(1.0)
    _assert_same(*sims)


def test_the_core_is_built_without_contraction() -> None:
    """0.1 * 10 - 1 is 0 with two roundings and 2^-54 fused: a build that contracts a * b + c
    into a multiply-add (and so changes events) fails here."""
    from evapcool.physics.core import compiled

    module = compiled()
    assert module is not None, "the compiled core is not built"
    assert 0.1 * 10.0 - 1.0 == 0.0
    assert module.contraction_probe(0.1, 10.0, -1.0) == 0.0


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    seed=st.integers(0, 10_000),
    n=st.integers(2, 50),
    radius=st.sampled_from([3.0, 6.0, 12.0]),
    height=st.floats(30.0, 450.0),
    rule=st.sampled_from(["rim", "knife"]),
)
def test_same_events_random_systems(
    seed: int, n: int, radius: float, height: float, rule: str
) -> None:
    ref, fast = _pair_run(
        n, seed, 150, changes={60: height * 0.6}, trap_height=height, radius=radius, escape=rule
    )
    _assert_same(ref, fast)


def test_atoms_far_above_the_grid_still_collide() -> None:
    # Two trapped atoms thrown far above the rim (H = 60) fly in the top row of cells, which
    # reaches up to infinity, meet there and bounce apart, exactly as in the reference engine.
    pos = [(-30.0, 100.0), (30.0, 100.0), (0.0, 5.0), (10.0, 5.0), (-10.0, 5.0)]
    vel = [(1.0, 20.0), (-1.0, 20.0), (0.5, 0.0), (-0.5, 0.0), (0.1, 0.0)]
    sims = [
        Simulation(
            5,
            radius=2.0,
            positions=pos,
            velocities=vel,
            engine=e,
            trap_height=60.0,
            record_events=True,
        )
        for e in ("reference", "fast")
    ]
    for sim in sims:
        sim.advance(80.0)
    ref, fast = sims
    assert ("pair", 0, 1) in {e[:3] for e in ref.event_log}
    _assert_same(ref, fast)


def test_raising_the_rim_keeps_the_same_events() -> None:
    ref, fast = _pair_run(50, 3, 700, changes={150: 120.0, 300: 350.0}, radius=6.0,
                          trap_height=60.0)  # fmt: skip
    _assert_same(ref, fast)


def test_hot_atoms_do_not_widen_the_cells() -> None:
    """Issue 13: the cells' size depends on the atoms' size, never on their energies."""
    cold = Simulation(n_atoms=2000, radius=2.0, seed=4, trap_height=450.0, engine="fast")
    vel = cold._world.vel.copy()
    vel[::20] *= 10.0  # 5 % of the atoms 100 times hotter (under the speed limit of a start)
    hot = Simulation(
        n_atoms=2000, radius=2.0, positions=cold._world.pos, velocities=vel,
        trap_height=450.0, engine="fast",
    )  # fmt: skip
    assert hot._engine.grid_shape[2] == cold._engine.grid_shape[2] == pytest.approx(1.12 * 2 * 2.0)
    hot.advance(5.0)
    assert _grid_errors(hot) == 0  # every atom filed where it is


@settings(max_examples=25, deadline=None)
@given(
    n=st.integers(1, 3000),
    radius=st.floats(0.01, 2.0),
    speed=st.floats(0.0, 3.0),
)
def test_grid_memory_is_bounded(n, radius, speed) -> None:
    """At most 8 cells per atom (plus 64) whatever the gas; cells at least a contact wide."""
    start = Simulation(n_atoms=n, radius=radius, seed=n, engine="reference" if n < 9 else "fast")
    vel = start._world.vel * (1.0 + speed)  # hotter: the grid must not grow with the energy
    sim = Simulation(n_atoms=n, radius=radius, positions=start._world.pos, velocities=vel,
                     engine="fast", trap_height=450.0)  # fmt: skip
    nx, ny, cell, _ = sim._engine.grid_shape
    assert nx * ny <= 8 * n + 64
    assert cell >= 2.0 * radius


def _min_gap(pos: np.ndarray, radius: float) -> float:
    """Smallest centre distance minus 2R over all pairs (binned, so O(N))."""
    cell = 2.0 * radius
    keys = np.floor(pos / cell).astype(np.int64)
    order = np.lexsort((keys[:, 1], keys[:, 0]))
    buckets: dict[tuple[int, int], list[int]] = {}
    for i in order:
        buckets.setdefault((int(keys[i, 0]), int(keys[i, 1])), []).append(int(i))
    best = math.inf
    for (kx, ky), members in buckets.items():
        near = [
            j for dx in (-1, 0, 1) for dy in (-1, 0, 1) for j in buckets.get((kx + dx, ky + dy), ())
        ]
        a = pos[members]
        b = pos[near]
        d = np.hypot(a[:, None, 0] - b[None, :, 0], a[:, None, 1] - b[None, :, 1])
        d[np.asarray(members)[:, None] == np.asarray(near)[None, :]] = math.inf
        best = min(best, float(d.min()) - 2.0 * radius)
    return best


def test_ten_thousand_atoms_sound() -> None:
    sim = Simulation(n_atoms=10_000, radius=1.0, seed=1, trap_height=450.0, engine="fast")
    w = sim._world
    e0 = float(np.sum(w.energies()))  # all atoms: escaped ones keep their energy in flight
    for _ in range(4):
        sim.advance(1.0)
        pos = sim.positions
        assert _min_gap(pos, 1.0) > -1e-9
        assert np.all(pos[:, 1] - sim.curvature * pos[:, 0] ** 2 > -1e-9)  # no wall penetration
        assert _grid_errors(sim) == 0
    assert sim.collision_count > 50_000
    assert sim.n_trapped > 9_000
    e1 = float(np.sum(w.energies()))
    assert abs(e1 - e0) / e0 < 1e-9
    # The running sum over trapped atoms agrees with a fresh one.
    trapped = w.energies()[w.status == TRAPPED]
    assert w.energy_sum == pytest.approx(float(np.sum(trapped)), rel=1e-9)


# -- cell crossings cannot stall (issue 17) ----------------------------------------------
A = 0.01
G = 10.0 / 30.0
CELL = 1.12 * 2 * 12.0


def _on_core_edges(x: float, lift: float, side: int = 0) -> tuple[float, float]:
    """A point near (x, a x^2 + lift) on a column edge and a row edge of the core's grid for
    one atom resting there (the core sizes its grid from the atom's height: settle it).
    side -1 or 1: a skin to the left or right of the column edge and above the row edge,
    where an atom moving across them is refiled."""
    y = A * x * x + lift
    for _ in range(4):
        nx, _, cell, skin = _one_atom("fast", x, y, 0.0, 0.0)._engine.grid_shape
        x0, y0 = -0.5 * nx * cell, -0.5 * cell
        x = x0 + round((x - x0) / cell) * cell + side * skin
        y = y0 + math.ceil((A * x * x + lift - y0) / cell) * cell + abs(side) * skin
    return x, y


def _one_atom(engine: str, x: float, y: float, vx: float, vy: float) -> Simulation:
    return Simulation(
        n_atoms=1, radius=12.0, positions=[[x, y]], velocities=[[vx, vy]], engine=engine,
        trap_height=450.0, record_events=True,
    )  # fmt: skip


def _events_per_frame(sim: Simulation, frames: int) -> list[int]:
    eng = sim._engine
    counts = []
    for _ in range(frames):
        before = sim.wall_collision_count + eng.crossing_count
        sim.advance(1.0)
        counts.append(sim.wall_collision_count + eng.crossing_count - before)
        assert _grid_errors(sim) == 0
    return counts


def _bound(sim: Simulation) -> float:
    """Most wall bounces plus crossings a lone atom can have in a frame.

    A hop lasts at least v_min / (g/2 + a v^2) (test_stalls.py), an arc crosses a row
    edge at most twice, and the atom travels at most v_max px in a frame."""
    v2 = 2.0 * sim.total_energy()
    hops = 2.0 + (0.5 * G + A * v2) / 1e-3
    return hops * 3 + 2 * math.sqrt(v2) / CELL + 4


@pytest.mark.parametrize(
    ("x", "lift", "vx", "vy"),
    [
        (0.0, 0.0, 0.0, 0.0),  # at rest near the vertex, on a column and a row edge
        (50.0, 0.0, 0.0, 0.0),  # at rest on the slope, on both edges: rolls
        (0.0, 40.0, 0.0, 0.0),  # dropped along a column edge
        (0.0, 40.0, 0.0, 3.0),  # thrown up along it
        (-30.0, 40.0, 2.0, 0.0),  # at the top of its arc on a row edge, moving along it
        (20.0, 0.0, 1e-9, 0.0),  # hopping on the wall across a row edge
    ],
)
@pytest.mark.parametrize("side", [-1, 0, 1])
def test_atom_on_cell_edges_advances_with_bounded_events(x, lift, vx, vy, side) -> None:
    x, y = _on_core_edges(x, lift, side)
    ref = _one_atom("reference", x, y, vx, vy)
    fast = _one_atom("fast", x, y, vx, vy)
    counts = _events_per_frame(fast, 30)
    ref.advance(30.0)
    assert max(counts) <= _bound(fast)
    assert fast.event_log == ref.event_log  # the crossings changed nothing


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    x=st.floats(-150.0, 150.0),
    lift=st.sampled_from([0.0, 1e-300, 1e-12, 1e-6, 5.0]),
    speed=st.one_of(st.just(0.0), st.floats(0.0, 1e-3), st.floats(0.0, 6.0)),
    angle=st.sampled_from([0.0, 0.5 * math.pi, math.pi, 1.5 * math.pi, 0.3]),
    side=st.sampled_from([-1, 0, 1]),
)
def test_any_state_on_cell_edges_advances_with_bounded_events(x, lift, speed, angle, side) -> None:
    x, y = _on_core_edges(x, lift, side)
    sim = _one_atom("fast", x, y, speed * math.cos(angle), speed * math.sin(angle))
    counts = _events_per_frame(sim, 3)
    assert max(counts) <= _bound(sim)
