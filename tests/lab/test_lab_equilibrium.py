"""The simulated gas against kinetic theory (SPEC section 4, docs/lab.md).

One dilute equilibrium run serves every test here: 300 disks of radius 0.5 px
with kT ~ 67 (scale height kT/mg ~ 200 px, packing fraction 0.5 % at the
bottom), the rim out of reach (H = inf), started far from the equilibrium law
(all atoms at one speed), equilibrated for ~90 collisions per atom, then
sampled every 5 frames for 3000 frames.
"""

from __future__ import annotations

import importlib.util
import math
import os

import numpy as np
import pytest

from evapcool import Simulation
from evapcool.lab import theory as th

N, R, KT, G, A = 300, 0.5, 66.7, 1.0 / 3.0, 0.01
EQUILIBRATE, MEASURE, STEP = 1500.0, 3000.0, 5.0


def lab_engine() -> str:
    """The compiled core if built ("auto" picks it here), else the reference (~15 s)."""
    default = "auto" if importlib.util.find_spec("evapcool.physics._core") else "reference"
    return os.environ.get("EVAPCOOL_LAB_ENGINE", default)


def integrated_autocorrelation(series: np.ndarray) -> float:
    """Integrated autocorrelation time (in samples) of per-atom series[t, atom] (Sokal window)."""
    d = series - series.mean()
    var = float(np.mean(d * d))
    tau = 0.5
    for lag in range(1, len(d)):
        tau += float(np.mean(d[:-lag] * d[lag:])) / var
        if lag >= 5.0 * tau:
            break
    return tau


@pytest.fixture(scope="module")
def gas():
    rng = np.random.default_rng(2)
    pos, vel = th.thermal_cloud(N, R, KT, gravity=G, curvature=A, rng=rng, equal_speeds=True)
    sim = Simulation(
        N,
        R,
        1.0,
        curvature=A,
        gravity=G,
        trap_height=math.inf,
        seed=2,
        engine=lab_engine(),
        positions=pos,
        velocities=vel,
    )
    e0 = sim.energies()
    sim.advance(EQUILIBRATE)
    pairs0, t0 = sim.pair_collision_count, sim.time
    energies, kinetic = [], []
    for _ in range(int(MEASURE / STEP)):
        sim.advance(STEP)
        energies.append(sim.energies())
        v = sim.velocities
        kinetic.append(0.5 * np.sum(v * v, axis=1))
    energies = np.array(energies)
    assert sim.n_trapped == N
    return {
        "initial": e0,
        "E": energies,
        "K": np.array(kinetic),
        "kT": th.kt_from_mean_energy(float(energies.mean())),
        "pair_rate": (sim.pair_collision_count - pairs0) / (sim.time - t0),
    }


def test_energy_law_passes_kolmogorov_smirnov(gas):
    e, kt = gas["E"], gas["kT"]
    # Snapshots of one atom are correlated over a few collisions; count independent samples.
    n_eff = e.size / (2.0 * integrated_autocorrelation(e))
    d = th.ks_statistic(e.ravel(), lambda x: th.energy_cdf(x, kt))
    p = th.ks_pvalue(d, n_eff)
    print(f"KS D = {d:.4f}, n_eff = {n_eff:.0f}, p = {p:.3f}")
    assert p > 0.01
    # The same test has power: the start (one speed) and a 10 % wrong kT both fail it.
    d0 = th.ks_statistic(gas["initial"], lambda x: th.energy_cdf(x, kt))
    assert th.ks_pvalue(d0, N) < 1e-3
    d_wrong = th.ks_statistic(e.ravel(), lambda x: th.energy_cdf(x, 1.1 * kt))
    assert th.ks_pvalue(d_wrong, n_eff) < 1e-3


def test_mean_kinetic_energy_is_two_fifths_of_mean_energy(gas):
    ratio = float(gas["K"].mean()) / gas["kT"]
    print(f"<m v^2/2> / (2/5 <E>) = {ratio:.4f}")
    assert ratio == pytest.approx(1.0, abs=0.02)


def test_energy_variance_is_five_halves_kt_squared(gas):
    ratio = float(gas["E"].var()) / (2.5 * gas["kT"] ** 2)
    print(f"var(E) / (5/2 kT^2) = {ratio:.4f}")
    assert ratio == pytest.approx(1.0, abs=0.08)


def test_pair_collision_rate_matches_hard_disk_theory(gas):
    cup = th.Cup(radius=R, mass=1.0, gravity=G, curvature=A)
    mean = 2.5 * gas["kT"]  # the measured mean energy
    cloud = th.TruncatedCloud.from_measured(cup, N, mean, math.inf)  # local density, no cut
    ratio = gas["pair_rate"] / cloud.pair_collision_rate
    print(
        f"pair collisions per frame {gas['pair_rate']:.3f}, "
        f"theory {cloud.pair_collision_rate:.3f}, ratio {ratio:.4f}"
    )
    assert ratio == pytest.approx(1.0, abs=0.02)


def test_dense_gas_collision_rate_needs_the_local_density_profile():
    """Peak packing 0.1: the local-density model within 2 %, the barometric one 13 % high."""
    from evapcool.lab.campaign import equilibrium

    dense, barometric, phi = equilibrium(1.5, [0, 1], engine=lab_engine())
    print(f"peak packing {phi:.3f}: measured / model {dense:.4f}, / barometric {barometric:.4f}")
    assert phi > 0.1
    assert dense == pytest.approx(1.0, abs=0.02)
    assert barometric < 0.9
