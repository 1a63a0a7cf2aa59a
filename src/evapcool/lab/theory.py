"""Kinetic and evaporation theory for hard disks in the gravitational cup (SPEC section 4).

Trap coordinates as in the physics: centres live in y >= a x^2, potential m g y.
All energies are per atom in the simulation's units (mass x px^2 / frame^2);
``kT`` is the Boltzmann temperature, which in this cup is 2/5 of the mean energy
per atom that the game calls "temperature" (seed Eq. 1). See doc/lab.md for the
derivations.
"""

from __future__ import annotations

import math

import numpy as np

#: kT / <E> in equilibrium: kinetic kT plus potential 3/2 kT, g(E) ~ E^(3/2).
KT_PER_MEAN_ENERGY = 2.0 / 5.0


def kt_from_mean_energy(mean_energy: float) -> float:
    """kT = (2/5) <E> for the cup's density of states g(E) ~ E^(3/2) (SPEC 4)."""
    return KT_PER_MEAN_ENERGY * mean_energy


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
    width 2 (2R) = 4R; the mean relative speed is sqrt(pi kT/m). See doc/lab.md.
    """
    n = np.asarray(n, dtype=float)
    phi = math.pi * n * radius * radius
    return n * 4.0 * radius * math.sqrt(math.pi * kt / mass) * henderson_g(phi)


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
    points: int = 20001,
) -> float:
    """Total pair-collision rate (per frame) of an equilibrium gas in the cup.

    Gamma = 1/2 (4R) sqrt(pi kT/m) I0(2R/lambda) [ int n^2 g dA - (2R/pi) oint n^2 g ds ]:
    the dilute rate integrated over the barometric profile (lambda = kT/mg), less the
    collisions lost because a partner's centre cannot lie beyond the centre-wall.
    I0 averages the density change across one contact distance (doc/lab.md).
    """
    a = curvature
    lam = kt / (mass * gravity)
    n0 = cup_central_density(n_atoms, kt, mass, gravity, a)
    # y = u^2 removes the sqrt(y) and 1/sqrt(y) end-point behaviour at the vertex.
    u = np.linspace(0.0, math.sqrt(40.0 * lam), points)
    y = u * u
    n = n0 * np.exp(-y / lam)
    n2g = n * n * henderson_g(math.pi * n * radius * radius)
    width = 2.0 * u / math.sqrt(a)  # 2 sqrt(y / a)
    bulk = np.trapezoid(n2g * width * 2.0 * u, u)
    # Both branches of the wall: ds = sqrt(1 + (dx/dy)^2) dy, dx/dy = 1 / (2 sqrt(a y)).
    wall = np.trapezoid(2.0 * n2g * np.sqrt(4.0 * u * u + 1.0 / a), u)
    if not wall_correction:
        wall = 0.0
    speed = math.sqrt(math.pi * kt / mass)
    tilt = bessel_i0(2.0 * radius / lam)
    return float(0.5 * 4.0 * radius * speed * tilt * (bulk - 2.0 * radius / math.pi * wall))


def bessel_i0(x: float) -> float:
    """Modified Bessel I0(x) = sum (x/2)^(2k) / (k!)^2: the mean of exp(x sin theta)."""
    term = total = 1.0
    q = 0.25 * x * x
    for k in range(1, 200):
        term *= q / (k * k)
        total += term
        if term < 1e-17 * total:
            break
    return total


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
