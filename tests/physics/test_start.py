"""The shared start generator and portable arithmetic (issue 22.1).

The same seed gives the same start in every edition: the golden starts and wins the web
edition replays (web/test/golden/starts.json, wins.json) are what this code writes, and
nothing that decides a start, an event or the win calls a function whose last bit differs
between languages (pow, exp, log, sin, cos).
"""

from __future__ import annotations

import importlib.util
import math
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from evapcool.physics.loading import load_cup
from evapcool.physics.portable import power
from evapcool.physics.simulation import Simulation
from evapcool.physics.start import (
    CANDIDATES,
    SEED_PORTABLE_MAX,
    STREAM_DIRECTION,
    _candidates,
    disk_points,
    random_seed,
    uniforms,
)

ROOT = Path(__file__).resolve().parents[2]


def _script():
    path = ROOT / "scripts" / "golden_starts.py"
    spec = importlib.util.spec_from_file_location("golden_starts", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.slow
def test_the_committed_golden_starts_and_wins_are_fresh() -> None:
    assert _script().main(["check"]) == 0


def test_the_golden_starts_are_this_generator() -> None:
    import json

    doc = json.loads((ROOT / "web/test/golden/starts.json").read_text(encoding="utf-8"))
    for case in doc["cases"][:5]:
        sim = Simulation(n_atoms=case["atoms"], radius=case["radius"], seed=case["seed"])
        assert sim.positions.ravel().tolist() == case["positions"]
        assert sim.velocities.ravel().tolist() == case["velocities"]


def test_same_seed_same_start_other_seed_other_start() -> None:
    a, b = Simulation.classic(seed=5), Simulation.classic(seed=5)
    assert np.array_equal(a.positions, b.positions) and np.array_equal(a.velocities, b.velocities)
    assert not np.array_equal(a.positions, Simulation.classic(seed=6).positions)


def test_no_seed_draws_one_that_replays_the_start() -> None:
    sim = Simulation.classic()
    assert sim.seed is not None and 0 <= sim.seed <= SEED_PORTABLE_MAX
    again = Simulation.classic(seed=sim.seed)
    assert np.array_equal(sim.positions, again.positions)
    assert all(0 <= random_seed() <= SEED_PORTABLE_MAX for _ in range(100))


@given(st.integers(0, 2**53 - 1), st.booleans())
def test_disk_points_lie_in_their_disk_or_ring(seed: int, ring: bool) -> None:
    inner = 1.0 / 16.0 if ring else 0.0
    p = disk_points(seed, STREAM_DIRECTION, 50, inner)
    r2 = p[:, 0] * p[:, 0] + p[:, 1] * p[:, 1]
    assert np.all((r2 >= inner) & (r2 < 1.0))


def test_an_atom_whose_candidates_all_miss_takes_its_fallback_point() -> None:
    # Seed 7: atom 1927's eight direction candidates all miss the ring (found by search).
    cand = _candidates(7, STREAM_DIRECTION, 1927, 1, CANDIDATES)[0]
    r2_all = cand[:, 0] ** 2 + cand[:, 1] ** 2
    assert not np.any((r2_all >= 1.0 / 16.0) & (r2_all < 1.0))
    p = disk_points(7, STREAM_DIRECTION, 1928, 1.0 / 16.0)
    r2 = p[1927, 0] ** 2 + p[1927, 1] ** 2
    assert 1.0 / 16.0 <= r2 < 1.0


def test_uniforms_are_in_the_unit_interval_and_even() -> None:
    u = uniforms(12345, 2, np.arange(200_000))
    assert u.min() >= 0.0 and u.max() < 1.0
    assert abs(u.mean() - 0.5) < 0.005
    counts, _ = np.histogram(u, bins=10, range=(0.0, 1.0))
    assert counts.min() > 19_000 and counts.max() < 21_000


def test_the_start_is_inside_the_cup_without_overlap() -> None:
    pos, vel = load_cup(400, 4.0, 0.01, 500.0, seed=3)
    assert np.all(pos[:, 1] > 0.01 * pos[:, 0] ** 2)  # centres inside the cup (trap frame)
    d = np.hypot(*(pos[:, None, :] - pos[None, :, :]).transpose(2, 0, 1))
    assert (d + np.eye(len(pos)) * 100).min() >= 8.0
    assert np.all(np.isfinite(vel))


@given(st.floats(1e-6, 1.0), st.floats(0.01, 10.0))
def test_power_is_within_a_few_ulps_of_the_true_power(x: float, p: float) -> None:
    want = x**p
    assert want == 0.0 or abs(power(x, p) - want) / want < 64 * 2.0**-52


def test_power_edge_values() -> None:
    assert power(0.0, 2 / 3) == 0.0
    assert power(1.0, 0.4) == 1.0
    assert power(0.25, 0.5) == 0.5
    assert power(0.5, 3.0) == 0.125


#: Files and the calls they may make: none of them decides a start, an event or the win.
ALLOWED = {
    "physics/validation.py": "log2 levels the grid; hypot in refusal checks",
    "physics/state.py": "hypot in an error message",
    "physics/state.ts": "hypot in an error message",
    "physics/validation.ts": "hypot in refusal checks",
}
FORBIDDEN = re.compile(
    r"\b(?:math|np|numpy|Math)\.(?:pow|power|exp|expm1|log|log2|log10|log1p|sin|cos|tan|"
    r"atan2?|hypot|cbrt)\b|[\w)\]]\s*\*\*\s*(?:self\.|[a-z_(])"
)


def test_the_physics_uses_only_portable_arithmetic() -> None:
    roots = [ROOT / "src/evapcool", ROOT / "web/src"]
    files = [p for p in (roots[0] / "physics").rglob("*.py")]
    files += list((roots[1] / "physics").glob("*.ts"))
    files += list((roots[1] / "game").glob("capacity.ts"))
    offenders = []
    # Only in a checkout: an sdist's tests have only part of web/ beside them.
    in_checkout = (ROOT / ".git").exists()
    gone = [n for n in ALLOWED if in_checkout and not (roots[n.endswith(".ts")] / n).is_file()]
    assert not gone, f"ALLOWED names files that are gone: {gone}"
    for path in files:
        rel = f"physics/{path.name}"
        if path.parent.name == "game":
            rel = f"game/{path.name}"
        if rel in ALLOWED:
            continue
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            code = line.split("#")[0] if path.suffix == ".py" else line.split("//")[0]
            if FORBIDDEN.search(code) and not code.strip().startswith(("*", "/*", '"""')):
                offenders.append(f"{rel}:{n}: {line.strip()}")
    assert not offenders, "\n".join(offenders)
    assert math.isfinite(power(0.3, 2 / 3))
