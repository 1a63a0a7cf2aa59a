"""The lab's theory functions checked against independent numerics."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from evapcool.lab import theory as th


def _integrate(f, lo: float, hi: float, n: int = 200001) -> float:
    x = np.linspace(lo, hi, n)
    return float(np.trapezoid(f(x), x))


@given(st.floats(min_value=0.0, max_value=40.0))
def test_gamma52_cdf_matches_its_integral(x):
    # P(5/2, x) = int_0^x t^(3/2) e^-t dt / Gamma(5/2); substitute t = s^2 for accuracy.
    expect = _integrate(lambda s: 2.0 * s**4 * np.exp(-s * s), 0.0, math.sqrt(x), 40001)
    assert th.gamma52_cdf(x) == pytest.approx(expect / math.gamma(2.5), abs=1e-8)


def test_energy_pdf_moments():
    kt = 3.0
    f = lambda e: th.energy_pdf(e, kt)  # noqa: E731
    assert _integrate(f, 0.0, 200.0) == pytest.approx(1.0, rel=1e-6)
    mean = _integrate(lambda e: e * f(e), 0.0, 200.0)
    var = _integrate(lambda e: (e - mean) ** 2 * f(e), 0.0, 200.0)
    assert mean == pytest.approx(2.5 * kt, rel=1e-6)  # <E> = 5/2 kT
    assert var == pytest.approx(2.5 * kt * kt, rel=1e-6)  # var = 5/2 (kT)^2


def test_ks_on_exact_samples_and_against_a_wrong_law():
    rng = np.random.default_rng(0)
    e = rng.gamma(2.5, 2.0, 20000)  # exactly the law at kT = 2
    d = th.ks_statistic(e, lambda x: th.energy_cdf(x, 2.0))
    assert th.ks_pvalue(d, e.size) > 0.01
    d = th.ks_statistic(rng.gamma(1.5, 2.0, 20000), lambda x: th.energy_cdf(x, 2.0))
    assert th.ks_pvalue(d, 20000) < 1e-6


def test_ks_pvalue_known_points():
    # Kolmogorov's distribution: P(sqrt(n) D > 1.358) = 0.05, > 1.628 = 0.01 for large n.
    assert th.ks_pvalue(1.358 / math.sqrt(1e8), 1e8) == pytest.approx(0.05, abs=1e-3)
    assert th.ks_pvalue(1.628 / math.sqrt(1e8), 1e8) == pytest.approx(0.01, abs=5e-4)


def test_henderson_and_local_rate():
    assert th.henderson_g(0.0) == 1.0
    assert th.henderson_g(0.5) == pytest.approx((1 - 7 / 32) / 0.25)
    # Uniform dilute gas: z = n sigma_2D <v_rel>, sigma_2D = 4R, <v_rel> = sqrt(pi kT / m).
    rng = np.random.default_rng(1)
    v = rng.normal(0.0, math.sqrt(2.0), (2, 400000, 2))  # kT/m = 2
    vrel = float(np.mean(np.hypot(*(v[0] - v[1]).T)))
    z = th.local_collision_rate(1e-9, 1.5, 2.0, 1.0) / 1e-9
    assert z == pytest.approx(4 * 1.5 * vrel, rel=5e-3)


def test_bessel_i0():
    assert th.bessel_i0(0.0) == 1.0
    theta = np.linspace(0.0, 2.0 * math.pi, 100000, endpoint=False)
    assert th.bessel_i0(0.7) == pytest.approx(np.mean(np.exp(0.7 * np.sin(theta))), rel=1e-6)


@pytest.mark.parametrize(
    ("n", "r", "kt", "tol"),
    [(300, 1.0, 65.0, 2e-3), (100, 3.0, 5.0, 1.5e-2)],
)
def test_cup_pair_rate_against_monte_carlo_of_the_exact_integral(n, r, kt, tol):
    """Monte Carlo of 1/2 int dA1 n1 int 2R dtheta n(r1 + 2R e) 1_D sqrt(kT/pi m), g = 1."""
    g, a, m = 1.0 / 3.0, 0.01, 1000000
    lam = kt / g
    rng = np.random.default_rng(3)
    y = rng.gamma(1.5, lam, m)
    x = rng.uniform(-1.0, 1.0, m) * np.sqrt(y / a)
    t = rng.uniform(0.0, 2.0 * math.pi, m)
    x2, y2 = x + 2 * r * np.cos(t), y + 2 * r * np.sin(t)
    n0 = th.cup_central_density(n, kt, 1.0, g, a)
    partner = np.where(y2 >= a * x2 * x2, n0 * np.exp(-y2 / lam), 0.0)
    exact = 0.5 * n * partner.mean() * 2 * math.pi * 2 * r * math.sqrt(kt / math.pi)
    dilute = dict(n_atoms=n, radius=r, kt=kt, mass=1.0, gravity=g, curvature=a)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(th, "henderson_g", lambda phi: np.ones_like(np.asarray(phi, dtype=float)))
        formula = th.cup_pair_collision_rate(**dilute)
        no_wall = th.cup_pair_collision_rate(**dilute, wall_correction=False)
    assert formula == pytest.approx(exact, rel=tol)
    assert abs(no_wall / exact - 1.0) > 3 * tol  # the wall term matters


def test_truncation_helpers():
    assert th.truncation_eta(th.truncation_height(6.0, 2.0, 1.0, 0.5), 2.0, 1.0, 0.5) == 6.0
    q = _integrate(lambda x: th.energy_pdf(x, 1.0), 6.0, 200.0)
    assert th.fraction_above(6.0) == pytest.approx(q, rel=1e-6)
    mean = _integrate(lambda x: x * th.energy_pdf(x, 1.0), 6.0, 200.0) / q
    assert th.mean_energy_above(6.0) == pytest.approx(mean, rel=1e-6)


def test_thermal_cloud_is_inside_and_not_overlapping():
    pos, vel = th.thermal_cloud(200, 2.0, 30.0, rng=np.random.default_rng(4))
    a = 0.01
    assert np.all(pos[:, 1] >= a * pos[:, 0] ** 2)
    d = np.hypot(*(pos[:, None, :] - pos[None, :, :]).transpose(2, 0, 1))
    d[np.diag_indices(200)] = np.inf
    assert d.min() > 4.0
    assert vel.shape == (200, 2)
    with pytest.raises(ValueError, match="n_atoms"):
        th.thermal_cloud(500, 20.0, 1.0, rng=np.random.default_rng(0), max_tries=20)
