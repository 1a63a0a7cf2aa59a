"""Evaporation with the knife against the truncated-Boltzmann model (docs/lab.md, "Evaporation").

The default run has the quick checks: the ledger of evaporated and spilled atoms, both
engines alike, and one short constant-eta measurement. The statistics (eta = 4, 5, 6, 7,
24 seeds of 300 atoms each; the quench; the tail below the cut) are marked slow:
`python -m pytest -m slow tests/lab/test_lab_evaporation.py` (about ten minutes, fast engine).
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest

from evapcool import Simulation
from evapcool.lab import parse_schedule, run_experiment
from evapcool.lab import theory as th
from evapcool.lab.campaign import RUN, pool, quench, run_eta

G, A = 1.0 / 3.0, 0.01
SEEDS = range(24)  # resolves the per-eta ratios to about 2 % (docs/lab.md)


def test_ledger_balances_atoms_and_energy_and_engines_agree():
    kw = dict(RUN, schedule="eta=5", frames=120, every=10, seed=4)
    ref = run_experiment(engine="reference", **kw)
    fast = run_experiment(engine="fast", **kw)
    for name, column in ref.columns.items():  # the same events: the same numbers
        assert np.array_equal(column, fast.columns[name]), name
    r = ref
    assert np.array_equal(r.escaped, r.evaporated + r.spilled)
    assert r.evaporated[-1] > 0
    assert r.spilled[0] > 0 and r.spilled[-1] > r.spilled[0]  # the first cut, then the schedule's
    # Collisions conserve energy: what the trap loses, the leavers took.
    kept = r.total_energy + r.evaporated_energy + r.spilled_energy
    np.testing.assert_allclose(kept, kept[0], rtol=1e-12)
    # Evaporated atoms were above the cut of their frame; spilled ones between two cuts.
    cut = G * r.trap_height
    assert np.all(np.diff(r.excess_energy) >= 0.0) and r.excess_energy[-1] > 0.0
    spilled = np.diff(r.spilled)
    some = spilled > 0
    per_atom = np.diff(r.spilled_energy)[some] / spilled[some]
    assert np.all(per_atom <= cut[:-1][some] * (1 + 1e-12))
    assert np.all(per_atom > cut[1:][some])


def test_knife_at_constant_eta_quick():
    """Two short runs at eta = 6: the collision rate and the efficiency (the quick version)."""
    pooled = pool(run_eta(6.0, [0, 1], frames=700))
    print({k: (round(v.measured, 5), round(v.predicted, 5)) for k, v in pooled.items()})
    assert pooled["Gamma_pair"].ratio == pytest.approx(1.0, abs=0.02)
    assert pooled["alpha"].ratio == pytest.approx(1.0, abs=0.10)


def test_theory_needs_a_long_enough_run():
    r = run_experiment(**dict(RUN, schedule="eta=6", frames=20, every=10, seed=1))
    with pytest.raises(ValueError, match="collisions per atom"):
        r.theory()


@cache
def _campaign(eta: float):
    pooled = pool(run_eta(eta, SEEDS))
    print(
        f"eta = {eta}: "
        + ", ".join(
            f"{k} {v.measured:.4g} / {v.predicted:.4g} = {v.ratio:.3f} +- {v.spread:.3f}"
            for k, v in pooled.items()
        )
    )
    return pooled


@pytest.mark.slow
@pytest.mark.parametrize("eta", [4.0, 5.0, 6.0, 7.0])
def test_knife_at_constant_eta_against_the_model(eta):
    pooled = _campaign(eta)
    assert pooled["Gamma_pair"].ratio == pytest.approx(1.0, abs=0.02)
    assert pooled["kappa"].ratio == pytest.approx(1.0, abs=0.10)
    assert pooled["alpha"].ratio == pytest.approx(1.0, abs=0.10)


EV_XFAIL = pytest.mark.xfail(
    strict=True,
    reason="measured 0.866 +- 0.017 of the truncated-Boltzmann rate: the gas below the cut is "
    "depleted (test_tail_below_the_cut_is_depleted), which the model leaves out (docs/lab.md)",
)


@pytest.mark.slow
@pytest.mark.parametrize("eta", [4.0, 5.0, 6.0, pytest.param(7.0, marks=EV_XFAIL)])
def test_evaporation_per_collision_at_constant_eta(eta):
    assert _campaign(eta)["Gamma_ev/gamma_el"].ratio == pytest.approx(1.0, abs=0.10)


@pytest.mark.slow
@pytest.mark.parametrize(("eta", "runs"), [(4.0, 400), (7.0, 2000)])
def test_evaporation_at_the_moment_of_the_cut_is_the_model(eta, runs):
    """Right after cutting an equilibrium cloud, the gas below the cut is exactly the law
    the model assumes: the first tenth of a collision time measures the model itself."""
    (_, _, events, ratio), *_ = quench(eta, runs, times=(0.1,))
    print(f"eta = {eta}: {events} evaporated, measured / model = {ratio:.3f}")
    assert events > 400  # about 5 % statistics
    assert ratio == pytest.approx(1.0, abs=0.10)


def _below_the_cut(seed: int, eta: float = 6.0, frames: int = 1400) -> list[np.ndarray]:
    """E - cut of every atom, in kT of the model, every 10 frames of a constant-eta run."""
    cup = th.Cup(radius=0.5, gravity=G, curvature=A)
    rng = np.random.default_rng(seed)
    pos, vel = th.thermal_cloud(300, 0.5, 60.0, gravity=G, curvature=A, rng=rng)
    sim = Simulation(
        300,
        0.5,
        1.0,
        curvature=A,
        gravity=G,
        trap_height=math.inf,
        engine="fast",
        escape="knife",
        win=False,
        positions=pos,
        velocities=vel,
    )
    schedule = parse_schedule(f"eta={eta}")
    schedule.apply(sim, 0.0)
    depths = []
    for frame in range(1, frames + 1):
        sim.advance(1.0)
        schedule.apply(sim, float(frame))
        if frame >= 200 and frame % 10 == 0:  # after ~10 collisions per atom
            cloud = th.TruncatedCloud.from_measured(
                cup, sim.n_trapped, sim.temperature, G * sim.trap_height
            )
            depths.append((cloud.eta, cloud.eta - sim.energies() / cloud.kt))
    return depths


@pytest.mark.slow
def test_tail_below_the_cut_is_depleted():
    """Under constant eta the law holds deep in the gas; the last half kT below the cut
    holds less than it says: the boundary layer that the evaporating collisions empty."""
    snapshots = [s for seed in range(4) for s in _below_the_cut(seed)]
    eta = float(np.mean([e for e, _ in snapshots]))
    depth = np.concatenate([d for _, d in snapshots])

    def law(lo: float, hi: float) -> float:  # share of the cut law from lo to hi kT below
        inside = float(th.gamma_p_half(2.5, eta))
        return float(th.gamma_p_half(2.5, eta - lo) - th.gamma_p_half(2.5, eta - hi)) / inside

    def measured(lo: float, hi: float) -> float:
        return np.count_nonzero((depth >= lo) & (depth < hi)) / depth.size

    deep, edge = measured(1.0, 3.0) / law(1.0, 3.0), measured(0.0, 0.5) / law(0.0, 0.5)
    print(
        f"1-3 kT below the cut: {deep:.3f} of the law; last 0.5 kT: {edge:.3f} "
        f"({depth.size} atom snapshots)"
    )
    assert deep == pytest.approx(1.0, abs=0.03)
    assert 0.7 < edge < 0.92
