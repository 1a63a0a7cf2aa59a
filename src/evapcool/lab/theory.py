"""Kinetic and evaporation theory for hard disks in the gravitational cup (SPEC section 4).

Trap coordinates as in the physics: centres live in y >= a x^2, potential m g y.
All energies are per atom in the simulation's units (mass x px^2 / frame^2);
``kT`` is the Boltzmann temperature, which in this cup is 2/5 of the mean energy
per atom that the game calls "temperature" (seed Eq. 1). See docs/lab.md for the
derivations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from evapcool.lab.scattering import collision_integrals

#: kT / <E> in equilibrium: kinetic kT plus potential 3/2 kT, g(E) ~ E^(3/2).
KT_PER_MEAN_ENERGY = 2.0 / 5.0


def kt_from_mean_energy(mean_energy: float) -> float:
    """kT = (2/5) <E> for the cup's density of states g(E) ~ E^(3/2), no cut (SPEC 4)."""
    return KT_PER_MEAN_ENERGY * mean_energy


#: Below this x the series of P(a, x) is used (its terms are all positive), above it 1 - Q.
_SERIES_BELOW = 6.0
_SERIES_TERMS = 60  # 6^60 / 60! < 1e-35


def gamma_p_half(a: float, x: np.ndarray | float) -> np.ndarray:
    """Regularised lower incomplete gamma P(a, x) for a half-integer a >= 1/2, without cancellation.

    Series x^a e^-x sum x^k / Gamma(a + k + 1) for small x; for larger x 1 - Q with
    Q(1/2, x) = erfc(sqrt x) and Q(b + 1, x) = Q(b, x) + x^b e^-x / Gamma(b + 1).
    """
    if a < 0.5 or (2.0 * a) % 1.0:
        raise ValueError(f"a must be a half-integer >= 1/2 (got {a!r})")
    x = np.maximum(np.asarray(x, dtype=float), 0.0)
    small = np.minimum(x, _SERIES_BELOW)[..., None]
    # Terms x^k / ((a + 1) ... (a + k)): below 1e-17 of the first by k = _SERIES_TERMS.
    ratios = small / (a + np.arange(1, _SERIES_TERMS + 1))
    series = 1.0 + np.sum(np.cumprod(ratios, axis=-1), axis=-1)
    lead = np.exp(a * np.log(np.maximum(small[..., 0], 1e-300)) - small[..., 0])
    series = np.where(small[..., 0] > 0.0, lead * series / math.gamma(a + 1.0), 0.0)
    big = np.maximum(x, _SERIES_BELOW)
    erfc = np.frompyfunc(math.erfc, 1, 1)
    q = np.asarray(erfc(np.sqrt(big)), dtype=float)
    b = 0.5
    while b < a:
        q = q + np.exp(b * np.log(big) - big) / math.gamma(b + 1.0)
        b += 1.0
    return np.where(x < _SERIES_BELOW, series, 1.0 - q)


def truncated_mean_energy(eta: np.ndarray | float) -> np.ndarray:
    """<E> / kT of P(E) ~ E^(3/2) exp(-E/kT) cut at E = eta kT: (5/2) P(7/2, eta) / P(5/2, eta).

    5/2 without a cut (eta -> inf), 5 eta / 7 for a shallow cut (eta -> 0), where the law is
    the density of states alone (Luiten, Reynolds & Walraven 1996, for g(E) ~ E^(3/2)).
    """
    eta = np.asarray(eta, dtype=float)
    return 2.5 * gamma_p_half(3.5, eta) / gamma_p_half(2.5, eta)


def kt_from_truncated_mean(mean_energy: float, eta: float) -> float:
    """kT of a gas truncated at eta kT whose mean energy per atom is mean_energy."""
    return float(mean_energy / truncated_mean_energy(eta))


def eta_from_cut(mean_energy: float, cut_energy: float) -> float:
    """The eta of the truncated law with this mean energy and cut eta kT = cut_energy.

    Solves eta / c(eta) = cut / <E>, c = truncated_mean_energy (increasing from 7/5 at
    eta -> 0); nan when cut / <E> <= 7/5 (no truncated law has that mean), inf without a cut.
    """
    if not mean_energy > 0.0 or math.isnan(cut_energy):
        return math.nan
    if math.isinf(cut_energy):
        return math.inf
    ratio = cut_energy / mean_energy
    if ratio <= 1.4:
        return math.nan
    # eta / c(eta) rises from 7/5 (eta -> 0) like 2 eta / 5 (eta -> inf); solve in ln eta.
    log_eta = _solve_increasing(
        lambda x: math.log(math.exp(x) / float(truncated_mean_energy(math.exp(x)))),
        math.log(ratio),
        math.log(2.5 * ratio),
        tol=1e-14,
    )
    return math.exp(log_eta)


def gamma52_cdf(x: np.ndarray | float) -> np.ndarray:
    """Regularised lower incomplete gamma P(5/2, x) = erf(sqrt x) - 2 sqrt(x/pi) e^-x (1 + 2x/3)."""
    x = np.maximum(np.asarray(x, dtype=float), 0.0)
    root = np.sqrt(x)
    erf = np.asarray(np.frompyfunc(math.erf, 1, 1)(root), dtype=float)
    return erf - 2.0 * np.sqrt(x / math.pi) * np.exp(-x) * (1.0 + 2.0 * x / 3.0)


def energy_cdf(energy: np.ndarray | float, kt: float) -> np.ndarray:
    """CDF of P(E) ~ E^(3/2) exp(-E/kT), the cup's equilibrium energy law."""
    return gamma52_cdf(np.asarray(energy, dtype=float) / kt)


def energy_pdf(energy: np.ndarray | float, kt: float) -> np.ndarray:
    """P(E) = E^(3/2) exp(-E/kT) / (Gamma(5/2) kT^(5/2)), normalised on E >= 0."""
    e = np.maximum(np.asarray(energy, dtype=float), 0.0)
    return e**1.5 * np.exp(-e / kt) / (math.gamma(2.5) * kt**2.5)


def truncated_energy_pdf(energy: np.ndarray | float, kt: float, cut: float) -> np.ndarray:
    """P(E) ~ E^(3/2) exp(-E/kT) on 0 <= E <= cut, normalised there (the knife's law)."""
    e = np.asarray(energy, dtype=float)
    inside = float(gamma_p_half(2.5, cut / kt)) if math.isfinite(cut) else 1.0
    return np.where(e <= cut, energy_pdf(e, kt) / inside, 0.0)


def ks_statistic(samples: np.ndarray, cdf) -> float:
    """Kolmogorov-Smirnov distance sup |F_n - F| of samples against a model CDF."""
    x = np.sort(np.asarray(samples, dtype=float))
    n = x.size
    if n == 0:
        raise ValueError("samples must not be empty")
    f = np.asarray(cdf(x), dtype=float)
    i = np.arange(1, n + 1)
    return float(max(np.max(i / n - f), np.max(f - (i - 1) / n)))


def ks_pvalue(d: float, n: float) -> float:
    """Asymptotic Kolmogorov p-value with Stephens' small-n correction (Stephens 1970)."""
    sn = math.sqrt(n)
    lam = (sn + 0.12 + 0.11 / sn) * d
    if lam < 0.2:
        return 1.0
    total = 0.0
    for j in range(1, 101):
        term = (-1.0) ** (j - 1) * math.exp(-2.0 * j * j * lam * lam)
        total += term
        if abs(term) < 1e-12:
            break
    return float(min(max(2.0 * total, 0.0), 1.0))


def henderson_g(phi: np.ndarray | float) -> np.ndarray:
    """Hard-disk contact value g(2R) = (1 - 7 phi/16) / (1 - phi)^2 (Henderson 1975)."""
    phi = np.asarray(phi, dtype=float)
    return (1.0 - 7.0 * phi / 16.0) / (1.0 - phi) ** 2


def local_collision_rate(
    n: np.ndarray | float, radius: float, kt: float, mass: float
) -> np.ndarray:
    """Collisions per atom per frame in a uniform 2D gas: z = n (4R) sqrt(pi kT/m) g(2R).

    The 2D cross-section of two disks of radius R is the impact-parameter
    width 2 (2R) = 4R; the mean relative speed is sqrt(pi kT/m). See docs/lab.md.
    """
    n = np.asarray(n, dtype=float)
    phi = math.pi * n * radius * radius
    return n * 4.0 * radius * math.sqrt(math.pi * kt / mass) * henderson_g(phi)


def henderson_compressibility(phi: np.ndarray | float) -> np.ndarray:
    """Hard-disk equation of state p / (n kT) = (1 + phi^2/8) / (1 - phi)^2 = 1 + 2 phi g(2R)."""
    phi = np.asarray(phi, dtype=float)
    return (1.0 + phi * phi / 8.0) / (1.0 - phi) ** 2


def henderson_excess_mu(phi: np.ndarray | float) -> np.ndarray:
    """Excess chemical potential mu_ex / kT = int_0^phi (Z - 1) dphi'/phi' + Z - 1 (Henderson)."""
    phi = np.asarray(phi, dtype=float)
    return (
        9.0 / 8.0 * phi / (1.0 - phi)
        - 7.0 / 8.0 * np.log1p(-phi)
        + henderson_compressibility(phi)
        - 1.0
    )


def _henderson_dlog_fugacity(phi: np.ndarray) -> np.ndarray:
    """d(ln phi + mu_ex/kT) / d ln phi = d(phi Z)/d phi: the inverse compressibility."""
    one = 1.0 - phi
    return ((1.0 + 3.0 * phi * phi / 8.0) * one + 2.0 * phi * (1.0 + phi * phi / 8.0)) / one**3


def _kinetic_mean(kappa: np.ndarray) -> np.ndarray:
    """<m v^2/2> / kT of a 2D Maxwellian cut at kinetic energy kappa kT: 1 - kappa/(e^kappa - 1)."""
    k = np.minimum(np.asarray(kappa, dtype=float), 700.0)  # k / (e^k - 1) underflows to 0
    return np.where(k > 1e-8, 1.0 - k / np.expm1(np.maximum(k, 1e-300)), 0.5 * k)


#: Heights above this many kT / (m g) hold nothing that counts (e^-45 of the bottom).
_T_FAR = 45.0
#: The local-density model is used up to this packing fraction (Henderson's law holds there).
MAX_PACKING = 0.6
#: ...and while the wall strip (2R/pi wide) takes at most this share of the collisions
#: (the Monte Carlo test in test_lab_theory.py checks it to 1.5 % at 27 %).
MAX_WALL_SHARE = 0.3


@lru_cache(maxsize=8)
def _legendre(nodes: int) -> tuple[np.ndarray, np.ndarray]:
    return np.polynomial.legendre.leggauss(nodes)


@dataclass(frozen=True)
class Cup:
    """Hard disks of one radius and mass in the parabolic cup y >= a x^2 under gravity."""

    radius: float
    mass: float = 1.0
    gravity: float = 10.0 / 30.0
    curvature: float = 0.01


class TruncatedCloud:
    """N hard disks at kT cut at eta kT: the truncated-Boltzmann model of evaporation.

    Phase-space density exp(-E/kT) for E = m v^2/2 + m g y < eta kT (Luiten, Reynolds &
    Walraven 1996), with the local-density correction for hard disks (dense=True): the
    positional factor carries exp(-mu_ex(phi)/kT) of the local packing fraction (Henderson
    1975), so the cloud is pushed up as it gets dense. Rates follow from the 2D hard-disk
    collision integrals (lab/scattering.py) with the contact value g(2R); docs/lab.md derives
    every formula. Lengths in px, times in frames, energies in m px^2 / frame^2.
    """

    def __init__(
        self,
        cup: Cup,
        n_atoms: float,
        kt: float,
        eta: float,
        *,
        dense: bool = True,
        wall: bool = True,
        nodes: int = 128,
    ) -> None:
        if not (n_atoms > 0 and kt > 0 and eta > 0):
            raise ValueError(f"n_atoms, kt and eta must be > 0 (got {n_atoms}, {kt}, {eta})")
        self.cup, self.n_atoms, self.kt, self.eta, self.dense = cup, n_atoms, kt, eta, dense
        self.scale_height = kt / (cup.mass * cup.gravity)  # lambda
        lam, a = self.scale_height, cup.curvature
        u, w = _legendre(nodes)
        top = math.sqrt(min(eta, _T_FAR))
        u = 0.5 * top * (u + 1.0)  # y = lambda u^2: no sqrt end-point at the vertex
        w = 0.5 * top * w
        self.t = u * u  # height in units of lambda: m g y / kT
        self.kappa = eta - self.t  # the cut's kinetic energy at that height, in kT
        self.area = 4.0 * lam**1.5 / math.sqrt(a) * u * u * w  # dA = 2 sqrt(y/a) dy
        # ds along both branches of the wall (all zero: no wall correction, for tests)
        self.wall = 4.0 * lam * np.sqrt(u * u + 1.0 / (4.0 * a * lam)) * w * float(wall)
        self.inside = -np.expm1(-self.kappa)  # fraction of the local Maxwellian below the cut
        self._solve_profile()

    # -- the density profile ------------------------------------------------------
    def _density(self, z: float) -> tuple[np.ndarray, np.ndarray]:
        """(n, zeta) for fugacity z: n = zeta (1 - e^-kappa), zeta = z e^-t e^(-mu_ex(phi))."""
        zeta = z * np.exp(-self.t)
        if not self.dense:
            return zeta * self.inside, zeta
        disk = math.pi * self.cup.radius**2
        target = np.log(disk * zeta * self.inside)  # ln phi + mu_ex(phi) = ln(ideal phi)
        x = target - np.log1p(4.0 * np.exp(target))  # start: first-order virial
        for _ in range(100):
            phi = np.minimum(np.exp(x), MAX_PACKING)
            step = (x + henderson_excess_mu(phi) - target) / _henderson_dlog_fugacity(phi)
            x = x - step
            if np.max(np.abs(step)) < 1e-14:
                break
        phi = np.exp(x)
        if np.max(phi) >= MAX_PACKING:
            raise ValueError(
                f"the gas is too dense for the model (packing fraction {np.max(phi):.2f} "
                f">= {MAX_PACKING})"
            )
        n = phi / disk
        return n, n / self.inside

    def _solve_profile(self) -> None:
        """Fugacity z such that the profile holds n_atoms; N(z) increases with z."""
        z = self.n_atoms / float(np.sum(self.area * np.exp(-self.t) * self.inside))
        count = lambda z: float(np.sum(self.area * self._density(z)[0]))  # noqa: E731
        if self.dense:
            z = _solve_increasing(lambda lz: math.log(count(math.exp(lz))), math.log(self.n_atoms),
                                  math.log(z))  # fmt: skip
            z = math.exp(z)
        self.fugacity = z
        self.n, self.zeta = self._density(z)
        self.packing = math.pi * self.cup.radius**2 * self.n

    # -- energies -----------------------------------------------------------------
    @property
    def mean_energy(self) -> float:
        """<m v^2/2 + m g y> per atom: what the game calls the temperature."""
        kinetic = _kinetic_mean(self.kappa) + self.t
        return self.kt * float(np.sum(self.area * self.n * kinetic)) / self.n_atoms

    @property
    def cut_energy(self) -> float:
        return self.eta * self.kt

    @property
    def peak_packing(self) -> float:
        """Packing fraction pi R^2 n at the bottom of the cup."""
        return float(self.packing[0])

    # -- collision rates ------------------------------------------------------------
    def _rate(self, local: np.ndarray) -> float:
        """1/2 (4R) sqrt(2kT/m) I0(2R/lambda) (1 - 1/N) [int zeta^2 g L dA - (2R/pi) oint ... ds].

        (1 - 1/N): N atoms make N (N - 1) / 2 pairs, not N^2 / 2.
        """
        r = self.cup.radius
        weight = self.zeta**2 * henderson_g(self.packing) * local
        bulk = float(np.sum(self.area * weight))
        wall = 2.0 * r / math.pi * float(np.sum(self.wall * weight))
        if wall > MAX_WALL_SHARE * bulk:
            raise ValueError(
                f"the cloud is too small for the model: the wall takes {wall / bulk:.0%} "
                f"of the collisions (the strip correction holds below {MAX_WALL_SHARE:.0%})"
            )
        bracket = bulk - wall
        speed = math.sqrt(2.0 * self.kt / self.cup.mass)
        pairs = max(1.0 - 1.0 / self.n_atoms, 0.0)
        return 0.5 * 4.0 * r * speed * float(np.i0(2.0 * r / self.scale_height)) * pairs * bracket

    @cached_property
    def _integrals(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return collision_integrals(self.kappa)

    @cached_property
    def pair_collision_rate(self) -> float:
        """Pair collisions per frame in the whole cloud (each collision counted once)."""
        return self._rate(self._integrals[0])

    @property
    def elastic_collision_rate(self) -> float:
        """gamma_el: collisions per atom per frame (an atom takes part), 2 Gamma_pair / N."""
        return 2.0 * self.pair_collision_rate / self.n_atoms

    @cached_property
    def evaporation_flux(self) -> float:
        """Atoms per frame that collisions send above the cut (at most one per collision)."""
        return self._rate(self._integrals[1])

    @property
    def evaporation_rate(self) -> float:
        """Gamma_ev: evaporation per atom per frame, -(dN/dt)_ev / N."""
        return self.evaporation_flux / self.n_atoms

    @property
    def evaporation_per_collision(self) -> float:
        """Gamma_ev / gamma_el = evaporations / (2 pair collisions)."""
        return self.evaporation_flux / (2.0 * self.pair_collision_rate)

    @cached_property
    def kappa_excess(self) -> float:
        """kappa: an evaporated atom carries (eta + kappa) kT on average."""
        _, j_ev, j_e = self._integrals
        carried = self._rate(j_e + self.t * j_ev)  # kinetic + potential, in kT
        return carried / self.evaporation_flux - self.eta

    @property
    def spill_density(self) -> float:
        """s = (kT/N) dN/d(cut): the fraction removed per kT the cut comes down."""
        return float(np.sum(self.area * self.zeta * np.exp(-self.kappa))) / self.n_atoms

    # -- evaporation at constant eta --------------------------------------------------
    def _with(self, n_atoms: float, kt: float) -> TruncatedCloud:
        return TruncatedCloud(self.cup, n_atoms, kt, self.eta, dense=self.dense)

    @cached_property
    def efficiency(self) -> float:
        """alpha = d ln T / d ln N at constant eta: collisions carry (eta + kappa) kT away,
        the cut follows T down and spills the atoms at eta kT (docs/lab.md)."""
        e = self.mean_energy / self.kt
        if self.dense:
            h = 1e-4
            up, down = (
                self._with(self.n_atoms * (1 + h), self.kt),
                self._with(self.n_atoms * (1 - h), self.kt),
            )
            e_n = (up.mean_energy - down.mean_energy) / (2 * h * self.kt)
            up, down = (
                self._with(self.n_atoms, self.kt * (1 + h)),
                self._with(self.n_atoms, self.kt * (1 - h)),
            )
            e_t = (up.mean_energy - down.mean_energy) / (2 * h * self.kt)
        else:
            e_n, e_t = 0.0, e  # <E> = c(eta) kT
        s, eta, kappa = self.spill_density, self.eta, self.kappa_excess
        # Per fraction x evaporated by collisions: d ln T = tau x, d ln N = (s eta tau - 1) x.
        tau = -(eta + kappa - e - e_n) / (e_t + s * eta * (e + e_n - eta))
        return tau / (s * eta * tau - 1.0)

    @classmethod
    def from_measured(
        cls, cup: Cup, n_atoms: float, mean_energy: float, cut_energy: float, *, dense: bool = True
    ) -> TruncatedCloud:
        """The cloud with this many atoms, mean energy per atom and cut (inf: none): solves kT."""
        eta0 = eta_from_cut(mean_energy, cut_energy)
        if math.isnan(eta0):
            raise ValueError(
                f"no truncated law has mean energy {mean_energy:g} below the cut {cut_energy:g}"
            )
        kt0 = cut_energy / eta0 if math.isfinite(eta0) else kt_from_mean_energy(mean_energy)
        if not dense:
            return cls(cup, n_atoms, kt0, eta0, dense=False)

        def cloud(log_kt: float) -> TruncatedCloud:
            kt = math.exp(log_kt)
            return cls(cup, n_atoms, kt, cut_energy / kt)

        # At a fixed cut the mean energy rises with kT.
        log_kt = _solve_increasing(lambda x: cloud(x).mean_energy, mean_energy, math.log(kt0))
        return cloud(log_kt)


def _solve_increasing(f, target: float, x0: float, *, tol: float = 1e-12) -> float:
    """x with f(x) = target for an increasing f: bracket from x0 by doubling, then Illinois."""
    step = 0.05
    lo, flo = x0, f(x0) - target
    hi, fhi = lo, flo
    while flo > 0.0:
        hi, fhi = lo, flo
        lo -= step
        step *= 2.0
        flo = f(lo) - target
    while fhi <= 0.0:
        lo, flo = hi, fhi
        hi += step
        step *= 2.0
        fhi = f(hi) - target
    side = 0
    for _ in range(200):
        x = hi - fhi * (hi - lo) / (fhi - flo)
        fx = f(x) - target
        if abs(fx) <= tol * max(abs(target), 1.0) or hi - lo <= tol * max(abs(x), 1.0):
            return x
        if fx > 0.0:
            hi, fhi = x, fx
            if side == 1:
                flo *= 0.5
            side = 1
        else:
            lo, flo = x, fx
            if side == -1:
                fhi *= 0.5
            side = -1
    return x


def cup_central_density(n_atoms: float, kt: float, mass: float, gravity: float, a: float) -> float:
    """n0 in n(x, y) = n0 exp(-m g y / kT) on y >= a x^2, normalised to N atoms."""
    lam = kt / (mass * gravity)
    return n_atoms * math.sqrt(a / math.pi) / lam**1.5


def cup_pair_collision_rate(
    n_atoms: float,
    radius: float,
    kt: float,
    mass: float,
    gravity: float,
    curvature: float,
    *,
    wall_correction: bool = True,
    dense: bool = False,
) -> float:
    """Total pair-collision rate (per frame) of an equilibrium gas in the cup (no cut).

    Gamma = 1/2 (4R) sqrt(pi kT/m) I0(2R/lambda) (1 - 1/N) [ int n^2 g dA - (2R/pi) oint n^2 g ds ]:
    the dilute rate integrated over the barometric profile (lambda = kT/mg), less the
    collisions lost because a partner's centre cannot lie beyond the centre-wall; dense=True
    uses the local-density profile. TruncatedCloud with eta = inf (docs/lab.md).
    """
    cup = Cup(radius=radius, mass=mass, gravity=gravity, curvature=curvature)
    cloud = TruncatedCloud(cup, n_atoms, kt, math.inf, dense=dense, wall=wall_correction)
    return cloud.pair_collision_rate


def truncation_height(eta: float, kt: float, mass: float, gravity: float) -> float:
    """Trap height H with m g H = eta kT (Ketterle & van Druten 1996)."""
    return eta * kt / (mass * gravity)


def truncation_eta(height: float, kt: float, mass: float, gravity: float) -> float:
    """eta = m g H / kT, the truncation parameter (Luiten, Reynolds & Walraven 1996)."""
    return mass * gravity * height / kt if kt > 0.0 else math.inf


def fraction_above(eta: float) -> float:
    """Equilibrium fraction of atoms with E > eta kT: 1 - P(5/2, eta)."""
    return float(1.0 - gamma52_cdf(eta))


def mean_energy_above(eta: float) -> float:
    """<E | E > eta kT> / kT = eta + kappa for g(E) ~ E^(3/2) (Ketterle & van Druten 1996)."""
    q = fraction_above(eta)
    if q <= 0.0:
        return float(eta)
    # int_eta^inf x^(5/2) e^-x dx = eta^(5/2) e^-eta + 5/2 Gamma(5/2, eta).
    upper = eta**2.5 * math.exp(-eta) / math.gamma(2.5) + 2.5 * q
    return float(upper / q)


def _room(grid: dict, xs: list, ys: list, cx: int, cy: int, x: float, y: float, limit: float):
    """True if no placed centre in the 3 x 3 cells around (cx, cy) is within sqrt(limit)."""
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for j in grid.get((cx + dx, cy + dy), ()):
                ex, ey = xs[j] - x, ys[j] - y
                if ex * ex + ey * ey <= limit:
                    return False
    return True


def thermal_cloud(
    n_atoms: int,
    radius: float,
    kt: float,
    *,
    mass: float = 1.0,
    gravity: float = 10.0 / 30.0,
    curvature: float = 0.01,
    rng: np.random.Generator | None = None,
    equal_speeds: bool = False,
    max_tries: int = 1000,
) -> tuple[np.ndarray, np.ndarray]:
    """Non-overlapping centres drawn from n ~ exp(-m g y / kT) on y >= a x^2, and velocities.

    Velocities are Maxwellian at kT, or (equal_speeds) all of speed sqrt(2 kT/m)
    in random directions: the same mean energy but not yet the equilibrium law.
    """
    if rng is None:
        rng = np.random.default_rng()
    lam = kt / (mass * gravity)
    pos = np.empty((n_atoms, 2))
    sigma2 = (2.0 * radius) ** 2
    limit = sigma2 * 1.0001
    # Atoms closer than sqrt(limit) share a cell or neighbour one: each try is O(1), not O(i).
    cell = 2.0 * radius * 1.0001
    grid: dict[tuple[int, int], list[int]] = {}
    xs: list[float] = []
    ys: list[float] = []
    for i in range(n_atoms):
        for _ in range(max_tries):
            # The y-marginal of the profile is Gamma(3/2, lam); x is uniform across the cup.
            y = rng.gamma(1.5, lam)
            x = rng.uniform(-1.0, 1.0) * math.sqrt(y / curvature)
            cx, cy = math.floor(x / cell), math.floor(y / cell)
            if _room(grid, xs, ys, cx, cy, x, y, limit):
                pos[i] = (x, y)
                xs.append(float(pos[i, 0]))
                ys.append(float(pos[i, 1]))
                grid.setdefault((cx, cy), []).append(i)
                break
        else:
            raise ValueError(f"n_atoms: {n_atoms} disks of radius {radius:g} are too dense")
    if equal_speeds:
        theta = rng.uniform(0.0, 2.0 * math.pi, n_atoms)
        speed = math.sqrt(2.0 * kt / mass)
        vel = speed * np.column_stack((np.cos(theta), np.sin(theta)))
    else:
        vel = rng.normal(0.0, math.sqrt(kt / mass), (n_atoms, 2))
    return pos, vel
