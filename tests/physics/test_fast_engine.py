"""The fast engine (issue 4): the reference engine's events exactly, and sound at 10 000 atoms."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from evapcool import Simulation
from evapcool.physics.world import TRAPPED



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
    """Same events (atoms, order, times to 1e-9 relative) and the same end state to 1e-6 px."""
    a, b = ref.event_log, fast.event_log
    assert len(a) == len(b)
    for k, (ea, eb) in enumerate(zip(a, b, strict=True)):
        assert ea[:3] == eb[:3], f"event {k}: {ea} != {eb}"
        assert eb[3] == pytest.approx(ea[3], rel=1e-9, abs=1e-12), f"event {k}"
    wa, wb = ref._world, fast._world
    np.testing.assert_array_equal(wa.status, wb.status)
    np.testing.assert_allclose(wb.pos, wa.pos, rtol=0, atol=1e-6)
    np.testing.assert_allclose(wb.vel, wa.vel, rtol=0, atol=1e-6)
    np.testing.assert_allclose(fast.positions, ref.positions, rtol=0, atol=1e-6)
    assert (fast.pair_collision_count, fast.wall_collision_count, fast.n_trapped, fast.won) == (
        ref.pair_collision_count,
        ref.wall_collision_count,
        ref.n_trapped,
        ref.won,
    )
    assert fast.total_energy() == pytest.approx(ref.total_energy(), rel=1e-12)
    assert fast._engine.grid_errors() == 0


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
    # Two trapped atoms thrown far above the rim (H = 60) fly in the attic, the grid's
    # top row, meet there and bounce apart, exactly as in the reference engine.
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
    assert fast._engine.grid.top < 100.0  # the meeting point, about 600 px up, is far above
    assert ("pair", 0, 1) in {e[:3] for e in ref.event_log}
    _assert_same(ref, fast)


def test_raising_the_rim_rebuilds_the_grid_with_the_same_events() -> None:
    ref, fast = _pair_run(50, 3, 700, changes={150: 120.0, 300: 350.0}, radius=6.0,
                          trap_height=60.0)  # fmt: skip
    assert fast._engine.grid.reach >= 350.0
    _assert_same(ref, fast)


def test_hot_atoms_do_not_widen_the_cells() -> None:
    """Issue 13: the grid depends on the atoms' size and the trap, never on their energies."""
    cold = Simulation(n_atoms=2000, radius=2.0, seed=4, trap_height=450.0, engine="fast")
    vel = cold._world.vel.copy()
    vel[::20] *= 10.0  # 5 % of the atoms 100 times hotter (under the speed limit of a start)
    hot = Simulation(
        n_atoms=2000, radius=2.0, positions=cold._world.pos, velocities=vel,
        trap_height=450.0, engine="fast",
    )  # fmt: skip
    assert hot._engine.grid_shape == cold._engine.grid_shape
    assert hot._engine.grid_shape[2] == pytest.approx(1.1 * 2 * 2.0)
    hot.advance(5.0)
    assert hot._engine.off_grid_count > 0  # some of them fly in the attic ...
    assert hot._engine.grid_errors() == 0  # ... filed where they are


@settings(max_examples=200, deadline=None)
@given(
    n=st.integers(1, 300_000),
    radius=st.floats(1e-3, 30.0),
    height=st.one_of(st.floats(1.0, 1e6), st.just(math.inf)),
    curvature=st.floats(1e-5, 1.0),
    width=st.integers(160, 100_000),
)
def test_grid_memory_is_bounded(n, radius, height, curvature, width) -> None:
    """At most 16 cells per atom (or 4096) for any input; cells at least a contact wide."""
    from types import SimpleNamespace

    from evapcool.physics.fast import grid

    world = SimpleNamespace(
        radius=np.array([radius]), curvature=curvature, x_left=-0.4 * width,
        x_right=0.6 * width,
    )  # fmt: skip
    g = grid.geometry(world, height)
    assert g.nx * g.ny <= max(grid.MAX_CELLS_PER_ATOM * n, grid.MIN_CELLS)
    assert g.cell >= 2.0 * radius
    assert g.top >= min(height, grid.reach(world, height)) + g.cell  # the rim is inside


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
        assert sim._engine.grid_errors() == 0
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
CELL = 1.1 * 2 * 12.0


def _edges_through(monkeypatch: pytest.MonkeyPatch, x: float, y: float) -> None:
    """Make the grid of the next engines have a column edge at x and a row edge at y."""
    from evapcool.physics.fast import grid

    def geometry(world, height):
        nx, ny = 40, 30
        return grid.Grid(x - 20 * CELL, y - 5 * CELL, CELL, nx, ny, 450.0)

    monkeypatch.setattr(grid, "geometry", geometry)


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
        assert eng.grid_errors() == 0
    return counts


def _bound(sim: Simulation) -> float:
    """Most wall bounces plus crossings a lone atom can have in a frame.

    A hop lasts at least v_min / (g/2 + a v^2) (test_stalls.py), an arc crosses a row
    edge at most twice, and the atom travels at most v_max px in a frame."""
    v2 = 2.0 * sim.total_energy()
    hops = 2.0 + (0.5 * G + A * v2) / 1e-3
    return hops * 3 + 2 * math.sqrt(v2) / CELL + 4


@pytest.mark.parametrize(
    ("x", "y", "vx", "vy"),
    [
        (0.0, 0.0, 0.0, 0.0),  # at rest in the vertex, on a column and a row edge
        (0.0, 1e-300, 0.0, 0.0),
        (50.0, 25.0, 0.0, 0.0),  # at rest on the slope, on both edges: rolls
        (0.0, 40.0, 0.0, 0.0),  # dropped along a column edge
        (0.0, 40.0, 0.0, 3.0),  # thrown up along it
        (-30.0, 40.0, 2.0, 0.0),  # at the top of its arc on a row edge, moving along it
        (20.0, 4.0, 1e-9, 0.0),  # hopping on the wall across a row edge
    ],
)
def test_atom_on_cell_edges_advances_with_bounded_events(monkeypatch, x, y, vx, vy) -> None:
    _edges_through(monkeypatch, x, y)
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
)
def test_any_state_on_cell_edges_advances_with_bounded_events(x, lift, speed, angle) -> None:
    with pytest.MonkeyPatch.context() as mp:
        y = A * x * x + lift
        _edges_through(mp, x, y)
        sim = _one_atom("fast", x, y, speed * math.cos(angle), speed * math.sin(angle))
        counts = _events_per_frame(sim, 3)
        assert max(counts) <= _bound(sim)
