"""Two-dimensional hard-disk collisions in a truncated Maxwellian gas (docs/lab.md, "Evaporation").

Velocities in units of sqrt(2 kT / m), so that a kinetic energy is w^2 kT. The local
velocity law at a height where the cut leaves kinetic energy kappa kT is
exp(-w^2) / pi on the disk w^2 < kappa. For a pair with centre-of-mass velocity W and
relative velocity u, a hard-disk collision with impact parameter b, uniform on
(-2R, 2R), turns u by psi = pi - 2 arcsin(b / 2R): the turn has density sin(psi/2) / 4
on (0, 2 pi), back-scattering favoured (unlike 3D hard spheres, 2D disks do not scatter
isotropically). Afterwards the atoms' kinetic energies are W^2 + u^2/4 +- W.u'; one of
them is above the cut if |W.u'| > kappa - W^2 - u^2/4 (both cannot be: their sum is
below 2 kappa).

collision_integrals(kappa) returns, per pair of the truncated law (each density 1):
    J     = < |w1 - w2| >                                 (collisions)
    J_ev  = < |w1 - w2| [an outgoing atom is above the cut] > (evaporating collisions)
    J_E   = < |w1 - w2| [...] w_out^2 >                  (their kinetic energy, in kT)
with <.> = int int exp(-w1^2 - w2^2) / pi^2 over w1^2, w2^2 < kappa (not normalised by
the fraction inside, so J(inf) = sqrt(pi/2)). With W = sqrt(kappa) r cos(om),
u/2 = sqrt(kappa) r sin(om) the kappa dependence separates:
    J_x(kappa) = (16/pi) kappa^(5/2) int_0^1 r^4 exp(-2 kappa r^2) H_x(r) dr,
H_x(r) = int_0^(pi/2) cos(om) sin^2(om) G_x(c) dom, c = (1 - r^2) / (r^2 sin 2 om),
where G_x(c) are the angle integrals below. The tables are built once (a fraction of a
second) and checked against a Monte Carlo of real collisions in tests/test_lab_theory.py.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

#: Above this kappa the cut is out of reach of any pair (J_ev ~ exp(-kappa)): the limits hold.
KAPPA_FAR = 60.0
R_STAR = 1.0 / math.sqrt(2.0)  # below it W^2 + u^2/4 + W u < kappa: no pair can evaporate
_NODES = 64


def _gauss(n: int, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (hi - lo) * x + 0.5 * (hi + lo), 0.5 * (hi - lo) * w


def _gauss_sqrt_ends(n: int, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """Gauss nodes for sqrt behaviour at both ends: x = lo + (hi - lo)(1 - cos pi v) / 2."""
    v, w = _gauss(n, 0.0, 1.0)
    x = lo + (hi - lo) * 0.5 * (1.0 - np.cos(math.pi * v))
    return x, w * (hi - lo) * 0.5 * math.pi * np.sin(math.pi * v)


def _turn_integrals(theta: np.ndarray, beta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """int dpsi sin(psi/2)/4 over the turns that put u' at |cos(theta + psi)| > cos(beta),
    and the same with the weight |cos(theta + psi)|, in closed form.

    The allowed directions theta + psi lie in (k pi - beta, k pi + beta), cos of sign (-1)^k.
    """

    def prob(p):
        return -0.5 * np.cos(0.5 * p)

    # sin(psi/2) cos(theta + psi) / 4 = [sin(theta + 3 psi/2) - sin(theta + psi/2)] / 8
    def weighted(p):
        return 0.125 * (2.0 * np.cos(theta + 0.5 * p) - (2.0 / 3.0) * np.cos(theta + 1.5 * p))

    g = np.zeros(np.broadcast(theta, beta).shape)
    ge = np.zeros_like(g)
    for k in range(-1, 4):
        lo = np.clip(k * math.pi - beta - theta, 0.0, 2.0 * math.pi)
        hi = np.clip(k * math.pi + beta - theta, 0.0, 2.0 * math.pi)
        g += prob(hi) - prob(lo)
        ge += (-1.0) ** k * (weighted(hi) - weighted(lo))
    return g, ge


def angle_integrals(c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """G(c), G_E(c) for 0 <= c <= 1: the incoming direction theta of u relative to W with
    |cos theta| < c (both atoms below the cut), the outgoing one with |cos theta'| > c.

    G = int dtheta [|cos theta| < c] int dpsi sin(psi/2)/4 [|cos theta'| > c]; G_E has the
    extra weight |cos theta'|. (Without the outgoing condition the integral is 4 arcsin c.)
    """
    c = np.clip(np.asarray(c, dtype=float), 0.0, 1.0)
    beta = np.arccos(c)[..., None]
    v, w = _gauss(_NODES, 0.0, 1.0)
    # theta in (beta, pi - beta); the half-turn theta + pi gives the same, hence 2x.
    span = np.maximum(math.pi - 2.0 * beta, 0.0)
    theta = beta + span * v
    g, ge = _turn_integrals(theta, beta)
    return 2.0 * np.sum(g * w * span, axis=-1), 2.0 * np.sum(ge * w * span, axis=-1)


@lru_cache(maxsize=1)
def _tables() -> dict[str, np.ndarray]:
    """Nodes and weights in r with H_0, H_ev, H_E at each (see the module docstring)."""
    r_lo, w_lo = _gauss(_NODES, 0.0, R_STAR)
    r_hi, w_hi = _gauss_sqrt_ends(_NODES, R_STAR, 1.0)
    # Below R_STAR (and outside the band in om) c >= 1: G_0 = 2 pi, G = G_E = 0;
    # int_0^(pi/2) cos sin^2 = 1/3.
    h0_lo = np.full_like(r_lo, 2.0 * math.pi / 3.0)
    s0 = (1.0 - r_hi**2) / r_hi**2  # c < 1 where sin 2 om > s0
    om1 = 0.5 * np.arcsin(np.minimum(s0, 1.0))
    om2 = 0.5 * math.pi - om1
    v, wv = _gauss_sqrt_ends(_NODES, 0.0, 1.0)
    om = om1[:, None] + (om2 - om1)[:, None] * v
    wom = (om2 - om1)[:, None] * wv
    sin2 = np.sin(2.0 * om)
    c = s0[:, None] / sin2
    g, ge = angle_integrals(c)
    shape = np.cos(om) * np.sin(om) ** 2 * wom
    outside = 2.0 * math.pi / 3.0 * (np.sin(om1) ** 3 + 1.0 - np.sin(om2) ** 3)
    h0_hi = outside + np.sum(4.0 * np.arcsin(np.minimum(c, 1.0)) * shape, axis=1)
    return {
        "r": np.concatenate((r_lo, r_hi)),
        "w": np.concatenate((w_lo, w_hi)),
        "H0": np.concatenate((h0_lo, h0_hi)),
        "Hev": np.concatenate((np.zeros_like(r_lo), np.sum(g * shape, axis=1))),
        "HE": np.concatenate((np.zeros_like(r_lo), np.sum((g + ge * sin2) * shape, axis=1))),
    }


def collision_integrals(kappa: np.ndarray | float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(J, J_ev, J_E) at local cut kappa (in kT), elementwise; see the module docstring."""
    k = np.maximum(np.asarray(kappa, dtype=float), 0.0)
    t = _tables()
    near = np.minimum(k, KAPPA_FAR)[..., None]
    r, w = t["r"], t["w"]
    e = w * r**4 * np.exp(-2.0 * near * r * r)
    scale = 16.0 / math.pi * near[..., 0] ** 2.5
    j = scale * np.sum(e * t["H0"], axis=-1)
    j_ev = scale * np.sum(e * t["Hev"], axis=-1)
    j_e = scale * near[..., 0] * np.sum(e * r * r * t["HE"], axis=-1)
    far = k > KAPPA_FAR
    j = np.where(far, math.sqrt(math.pi / 2.0), j)
    return j, np.where(far, 0.0, j_ev), np.where(far, 0.0, j_e)
