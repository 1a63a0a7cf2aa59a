"""The fast engine (issue 4): the reference engine's events exactly, and sound at 10 000 atoms."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from evapcool import Simulation
from evapcool.physics.world import TRAPPED

pytest.importorskip("numba")


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


def test_atoms_far_above_the_grid_still_collide(monkeypatch: pytest.MonkeyPatch) -> None:
    # Two trapped atoms thrown far above the nominal grid (here sized for the slow
    # atoms only) meet there, in the clamped top row, and bounce apart.
    from evapcool.physics.fast import grid

    monkeypatch.setattr(grid, "BOX_PERCENTILE", 0.0)
    pos = [(-30.0, 100.0), (30.0, 100.0), (0.0, 5.0), (10.0, 5.0), (-10.0, 5.0)]
    vel = [(1.0, 20.0), (-1.0, 20.0), (0.5, 0.0), (-0.5, 0.0), (0.1, 0.0)]
    sims = [
        Simulation(
            5,
            radius=2.0,
            positions=pos,
            velocities=vel,
            engine=e,
            trap_height=math.inf,
            record_events=True,
        )
        for e in ("reference", "fast")
    ]
    for sim in sims:
        sim.advance(80.0)
    ref, fast = sims
    _nx, ny, cs = fast._engine.grid_shape
    assert ny * cs < 100.0  # the meeting point, about 600 px up, is far above the box
    assert ("pair", 0, 1) in {e[:3] for e in ref.event_log}
    _assert_same(ref, fast)


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
