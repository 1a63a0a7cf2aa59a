"""The lab's theory functions checked against independent numerics."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
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
    # N (N - 1) / 2 pairs: the partner density of N atoms is (1 - 1/N) n.
    exact = 0.5 * n * (1 - 1 / n) * partner.mean() * 2 * math.pi * 2 * r * math.sqrt(kt / math.pi)
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


# -- the truncated law ---------------------------------------------------------------


@settings(deadline=None)  # a 40 000-point integral per example
@given(st.sampled_from([0.5, 1.5, 2.5, 3.5]), st.floats(min_value=0.0, max_value=60.0))
def test_incomplete_gamma_matches_its_integral(a, x):
    # P(a, x) = int_0^x t^(a-1) e^-t dt / Gamma(a); t = s^2 removes the end-point behaviour.
    f = lambda s: 2.0 * s ** (2 * a - 1) * np.exp(-s * s)  # noqa: E731
    expect = _integrate(f, 0.0, math.sqrt(x), 40001) / math.gamma(a)
    assert th.gamma_p_half(a, x) == pytest.approx(expect, abs=1e-9)


def test_incomplete_gamma_has_no_cancellation_at_small_x():
    # P(a, x) -> x^a / Gamma(a + 1) as x -> 0: full relative precision, not round-off.
    for a in (0.5, 2.5, 3.5):
        x = 1e-6
        assert th.gamma_p_half(a, x) == pytest.approx(x**a / math.gamma(a + 1), rel=1e-5)
    assert th.gamma_p_half(0.5, 2.0) == pytest.approx(math.erf(math.sqrt(2.0)), rel=1e-14)
    assert np.allclose(
        th.gamma_p_half(2.5, np.linspace(0, 30, 61)), th.gamma52_cdf(np.linspace(0, 30, 61))
    )
    with pytest.raises(ValueError, match="half-integer"):
        th.gamma_p_half(1.2, 1.0)


@pytest.mark.parametrize("eta", [0.3, 2.0, 4.0, 5.0, 6.0, 7.0, 12.0])
def test_truncated_mean_energy_is_the_mean_of_the_cut_law(eta):
    e = np.linspace(0.0, eta, 400001)
    w = e**1.5 * np.exp(-e)
    mean = float(np.trapezoid(e * w, e) / np.trapezoid(w, e))
    assert th.truncated_mean_energy(eta) == pytest.approx(mean, rel=1e-8)
    # ... and the inverse: eta back from the mean energy and the cut, at any kT.
    kt = 3.7
    exact = float(th.truncated_mean_energy(eta))
    assert th.eta_from_cut(exact * kt, eta * kt) == pytest.approx(eta, rel=1e-10)


def test_truncated_law_limits_and_the_issue_numbers():
    assert th.truncated_mean_energy(60.0) == pytest.approx(2.5, rel=1e-12)
    assert th.truncated_mean_energy(1e-6) == pytest.approx(5e-6 / 7.0, rel=1e-5)  # flat: 5/7 cut
    assert math.isnan(th.eta_from_cut(1.0, 1.39))  # no law has <E> above 5/7 of the cut
    assert th.eta_from_cut(1.0, math.inf) == math.inf
    # The old schedule took kT = 2/5 <E>: its eta = e solved eta_run = e (2/5) c(eta_run).
    ran = [
        th.eta_from_cut(1.0, target * 0.4)  # cut = target * kT_old, kT_old = 0.4 <E>, <E> = 1
        for target in (4.0, 5.0, 6.0, 7.0)
    ]
    np.testing.assert_allclose(ran, [1.75, 3.9, 5.4, 6.7], atol=0.06)


# -- hard-disk collisions in a truncated gas --------------------------------------------


def _collisions_monte_carlo(kappa: float, m: int, seed: int) -> tuple[float, float, float]:
    """J, J_ev, J_E by sampling pairs and impact parameters, colliding them with the engine's
    own kernel (physics.kernels.collide_pair): nothing of lab/scattering.py is used."""
    from evapcool.physics.kernels import collide_pair

    rng = np.random.default_rng(seed)
    w1 = rng.normal(0.0, math.sqrt(0.5), (m, 2))  # exp(-w^2)/pi: kinetic energy w^2 kT
    w2 = rng.normal(0.0, math.sqrt(0.5), (m, 2))
    s = rng.uniform(-1.0, 1.0, m)  # impact parameter / 2R
    j = j_ev = j_e = 0.0
    for a, b, si in zip(w1, w2, s, strict=True):
        if a @ a >= kappa or b @ b >= kappa:
            continue
        rel = b - a  # velocity of 2 relative to 1
        speed = math.hypot(*rel)
        e, perp = rel / speed, np.array((-rel[1], rel[0])) / speed
        contact = -math.sqrt(1.0 - si * si) * e + si * perp  # (r2 - r1) / 2R at contact
        v = collide_pair(contact[0], contact[1], a[0], a[1], b[0], b[1], 1.0, 1.0)
        out = max(v[0] ** 2 + v[1] ** 2, v[2] ** 2 + v[3] ** 2)
        j += speed
        if out > kappa:
            j_ev += speed
            j_e += speed * out
    return j / m, j_ev / m, j_e / m


@pytest.mark.parametrize("kappa", [1.0, 3.0, 6.0])
def test_collision_integrals_against_collisions_of_the_engine(kappa):
    from evapcool.lab.scattering import collision_integrals

    m = 200000
    mc = np.array(_collisions_monte_carlo(kappa, m, seed=int(kappa)))
    j, j_ev, j_e = (float(x) for x in collision_integrals(kappa))
    # Binomial-like noise of the evaporating share; J itself is a plain mean.
    assert mc[0] == pytest.approx(j, rel=0.01)
    tol = 4.0 / math.sqrt(j_ev / j * m)
    assert mc[1] == pytest.approx(j_ev, rel=tol)
    assert mc[2] == pytest.approx(j_e, rel=tol)


def test_collision_integrals_limits():
    from evapcool.lab.scattering import angle_integrals, collision_integrals

    j, j_ev, j_e = collision_integrals(np.array([0.0, 80.0]))
    assert j[0] == j_ev[0] == j_e[0] == 0.0
    assert j[1] == pytest.approx(math.sqrt(math.pi / 2.0), rel=1e-14)  # <|w1 - w2|>, no cut
    assert j_ev[1] == 0.0
    # No cut left to cross and no way to be below it both give G = 0.
    g, ge = angle_integrals(np.array([0.0, 1.0]))
    assert np.allclose(g, 0.0) and np.allclose(ge, 0.0)
    # The angle integrals against sampling (2D hard disks: turn density sin(psi/2)/4).
    rng = np.random.default_rng(5)
    theta = rng.uniform(0.0, 2.0 * math.pi, 400000)
    psi = math.pi - 2.0 * np.arcsin(rng.uniform(-1.0, 1.0, 400000))
    for c in (0.3, 0.7):
        hit = (np.abs(np.cos(theta)) < c) & (np.abs(np.cos(theta + psi)) > c)
        g, ge = angle_integrals(c)
        assert 2 * math.pi * hit.mean() == pytest.approx(float(g), rel=0.01)
        w = np.abs(np.cos(theta + psi))
        assert 2 * math.pi * (hit * w).mean() == pytest.approx(float(ge), rel=0.01)


# -- the cloud -----------------------------------------------------------------------

CUP = th.Cup(radius=0.5, mass=1.0, gravity=1.0 / 3.0, curvature=0.01)


@pytest.mark.parametrize("dense", [False, True])
@pytest.mark.parametrize("eta", [4.0, 7.0, math.inf])
def test_cloud_holds_its_atoms_and_the_ideal_one_its_law(eta, dense):
    cloud = th.TruncatedCloud(CUP, 300, 30.0, eta, dense=dense)
    assert float(np.sum(cloud.area * cloud.n)) == pytest.approx(300, rel=1e-10)
    if not dense:
        assert cloud.mean_energy / cloud.kt == pytest.approx(
            float(th.truncated_mean_energy(eta)) if math.isfinite(eta) else 2.5, rel=1e-9
        )
        if math.isfinite(eta):  # atoms per kT at the cut: eta^(3/2) e^-eta / gamma(5/2, eta)
            s = eta**1.5 * math.exp(-eta) / (math.gamma(2.5) * float(th.gamma_p_half(2.5, eta)))
            assert cloud.spill_density == pytest.approx(s, rel=1e-9)


def test_dense_profile_is_hydrostatic_and_thermodynamically_consistent():
    cup = th.Cup(radius=2.0, gravity=1.0 / 3.0, curvature=0.01)
    cloud = th.TruncatedCloud(cup, 300, 30.0, math.inf, nodes=1000)
    assert cloud.peak_packing > 0.15  # dense enough to matter
    # dp/dy = -n m g with p = n kT Z(phi): in units of kT/(mg), d(n Z)/dt = -n.
    p = cloud.n * th.henderson_compressibility(cloud.packing)
    dpdt = np.diff(p) / np.diff(cloud.t)  # at the midpoints, second order in the spacing
    mid = 0.5 * (cloud.n[1:] + cloud.n[:-1])
    bulk = cloud.t[1:] < 8.0  # where the nodes are close enough for the difference quotient
    np.testing.assert_allclose(dpdt[bulk], -mid[bulk], rtol=1e-3)
    # mu_ex from Henderson's Z: d(ln phi + mu_ex)/d phi = (1/phi) d(phi Z)/d phi.
    phi = np.linspace(0.05, 0.6, 12)
    h = 1e-6
    lhs = (
        np.log(phi + h)
        + th.henderson_excess_mu(phi + h)
        - np.log(phi - h)
        - th.henderson_excess_mu(phi - h)
    ) / (2 * h)
    rhs = (
        (
            (phi + h) * th.henderson_compressibility(phi + h)
            - (phi - h) * th.henderson_compressibility(phi - h)
        )
        / (2 * h)
        / phi
    )
    np.testing.assert_allclose(lhs, rhs, rtol=1e-7)
    # Henderson's Z is 1 + 2 phi g(2R) with the contact value the rates use.
    np.testing.assert_allclose(
        th.henderson_compressibility(phi), 1 + 2 * phi * th.henderson_g(phi), rtol=1e-14
    )


def test_dense_model_becomes_the_ideal_one_for_small_disks():
    cup = th.Cup(radius=1e-4, gravity=1.0 / 3.0, curvature=0.01)
    dense = th.TruncatedCloud(cup, 300, 30.0, 6.0)
    ideal = th.TruncatedCloud(cup, 300, 30.0, 6.0, dense=False)
    for name in (
        "mean_energy",
        "pair_collision_rate",
        "evaporation_per_collision",
        "kappa_excess",
        "efficiency",
        "spill_density",
    ):
        assert getattr(dense, name) == pytest.approx(getattr(ideal, name), rel=1e-4), name


@pytest.mark.parametrize("dense", [False, True])
def test_from_measured_recovers_kt(dense):
    cloud = th.TruncatedCloud(CUP, 250, 41.0, 5.5, dense=dense)
    again = th.TruncatedCloud.from_measured(
        CUP, 250, cloud.mean_energy, cloud.cut_energy, dense=dense
    )
    assert again.kt == pytest.approx(41.0, rel=1e-9)
    assert again.eta == pytest.approx(5.5, rel=1e-9)
    with pytest.raises(ValueError, match="no truncated law"):
        th.TruncatedCloud.from_measured(CUP, 250, 100.0, 120.0)


def test_uniform_dilute_limit_of_the_rates():
    # Without cut and in the dilute limit: Gamma_pair = (N^2/2) R sqrt(2 a kT/m) / lambda^(3/2)
    # (docs/lab.md), times (1 - 1/N) for the pairs; the wall strip and I0 are small here.
    cup = th.Cup(radius=0.01, gravity=1.0 / 3.0, curvature=0.01)
    n, kt = 300, 30.0
    lam = kt / cup.gravity
    closed = n * n * cup.radius * math.sqrt(cup.curvature * kt) / (math.sqrt(2) * lam**1.5)
    rate = th.TruncatedCloud(cup, n, kt, math.inf, dense=False).pair_collision_rate
    assert rate == pytest.approx(closed * (1 - 1 / n), rel=1e-3)


def _step_model(eta: float, n: float, kt: float, lost: float) -> tuple[float, float]:
    """One small step of evaporation at constant eta, the slow way (ideal gas): collisions
    remove `lost` N atoms carrying (eta + kappa) kT; the rest re-thermalise at the same cut;
    the cut then comes down to eta kT, spilling the law's atoms between the cuts, and so on
    until eta kT is the cut again. Returns (N, kT) afterwards."""
    cloud = th.TruncatedCloud(CUP, n, kt, eta, dense=False)
    energy = n * cloud.mean_energy - lost * n * (eta + cloud.kappa_excess) * kt
    n, cut = n * (1 - lost), eta * kt
    for _ in range(100):
        kt_now = cut / th.eta_from_cut(energy / n, cut)
        new_cut = eta * kt_now
        if abs(new_cut - cut) < 1e-13 * cut:
            return n, kt_now
        a, b = new_cut / kt_now, cut / kt_now  # the band spilled, in kT of the law now
        inside = float(th.gamma_p_half(2.5, b))
        share = (th.gamma_p_half(2.5, b) - th.gamma_p_half(2.5, a)) / inside
        band = 2.5 * kt_now * (th.gamma_p_half(3.5, b) - th.gamma_p_half(3.5, a)) / inside
        n, energy, cut = n * (1 - share), energy - n * band, new_cut
    raise AssertionError("the cut did not settle")


@pytest.mark.parametrize("eta", [4.0, 6.0])
def test_efficiency_against_stepping_the_model(eta):
    n0, kt0 = 300.0, 30.0
    n, kt = n0, kt0
    for _ in range(40):
        n, kt = _step_model(eta, n, kt, 1e-3)
    stepped = math.log(kt / kt0) / math.log(n / n0)
    alpha = th.TruncatedCloud(CUP, n0, kt0, eta, dense=False).efficiency
    assert stepped == pytest.approx(alpha, rel=2e-3)
    # Without the spill, the textbook large-eta form (eta + kappa) / (5/2) - 1 would be off.
    kappa = th.TruncatedCloud(CUP, n0, kt0, eta, dense=False).kappa_excess
    assert abs((eta + kappa) / 2.5 - 1 - stepped) > 0.02
