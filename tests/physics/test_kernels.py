"""Property-based checks of the contact-time kernels: predicted contacts really happen first."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from evapcool import Simulation
from evapcool.physics import kernels as k
from evapcool.physics.reference import ReferenceEngine
from evapcool.physics.simulation import GRAVITY

G = GRAVITY
coord = st.floats(-200, 200, allow_nan=False)
speed = st.floats(-8, 8, allow_nan=False)
radius = st.floats(0.5, 15, allow_nan=False)
stamp = st.floats(0, 5, allow_nan=False)


def _at(x, y, vx, vy, t0, t):
    d = t - t0
    return x + vx * d, y + vy * d - 0.5 * G * d * d


def _size(x, y, vx, vy, t0, t):
    """The largest terms _at adds up: its round-off is about 1e-16 of this."""
    d = t - t0
    return abs(x) + abs(y) + abs(vx * d) + abs(vy * d) + 0.5 * G * d * d


@settings(max_examples=400, deadline=None)
@given(coord, coord, speed, speed, stamp, coord, coord, speed, speed, stamp, radius, radius)
def test_pair_contact_is_real_and_first(x1, y1, vx1, vy1, t1, x2, y2, vx2, vy2, t2, r1, r2) -> None:
    sigma = r1 + r2
    tr = max(t1, t2)
    p1, p2 = _at(x1, y1, vx1, vy1, t1, tr), _at(x2, y2, vx2, vy2, t2, tr)
    rx, ry = p1[0] - p2[0], p1[1] - p2[1]
    assume(math.hypot(rx, ry) > sigma * (1 + 1e-6))  # start apart
    vx, vy = vx1 - vx2, (vy1 - G * (tr - t1)) - (vy2 - G * (tr - t2))
    t = k.pair_contact_time(x1, y1, vx1, vy1, t1, x2, y2, vx2, vy2, t2, sigma, G)
    # |r + v s|^2 is a convex quadratic in s; distance^2 at time s after tr:
    vv, b, c = vx * vx + vy * vy, rx * vx + ry * vy, rx * rx + ry * ry
    if math.isfinite(t):
        s = t - tr
        assert s >= 0
        q1, q2 = _at(x1, y1, vx1, vy1, t1, t), _at(x2, y2, vx2, vy2, t2, t)
        d = math.hypot(q1[0] - q2[0], q1[1] - q2[1])
        # Long flights (a slow approach from far) reach positions ~1e7 px: evaluating
        # them here costs ~1e-16 of that, more than the kernel's own error.
        size = _size(x1, y1, vx1, vy1, t1, t) + _size(x2, y2, vx2, vy2, t2, t)
        assert abs(d - sigma) <= 1e-9 * sigma + 1e-12 * math.hypot(rx, ry) + 1e-15 * size
        # First contact: still approaching at s (the earlier root is the one taken).
        assert b + vv * s <= 1e-9 * math.sqrt(vv) * sigma
    else:
        # Never closer than sigma in the future: the minimum is >= sigma^2 or lies in the past.
        s_min = -b / vv if vv > 0 else 0.0
        if s_min > 0:
            assert c + 2 * b * s_min + vv * s_min * s_min >= sigma * sigma * (1 - 1e-9)


@settings(max_examples=400, deadline=None)
@given(
    st.floats(-150, 150),
    st.floats(0, 450),
    speed,
    speed,
    stamp,
    st.sampled_from([0.001, 0.01, 0.05]),
)
def test_wall_contact_is_real_and_first(x, y, vx, vy, t0, a) -> None:
    assume(y > a * x * x)
    t = k.wall_contact_time(x, y, vx, vy, t0, a, G)
    assert math.isfinite(t) and t >= t0
    xs, ys = _at(x, y, vx, vy, t0, t)
    scale = max(1.0, y, 1.0 / a)
    assert abs(ys - a * xs * xs) <= 1e-9 * scale
    # Inside at every earlier moment: f is concave with f(t0) > 0, so f(mid) > 0 suffices,
    # and at contact the centre moves outwards (f' <= 0).
    xm, ym = _at(x, y, vx, vy, t0, 0.5 * (t0 + t))
    assert ym - a * xm * xm > -1e-9 * scale
    vy_c = vy - G * (t - t0)
    assert vy_c - 2 * a * xs * vx <= 1e-9 * math.hypot(vx, vy_c) + 1e-12


@settings(max_examples=200, deadline=None)
@given(st.floats(-150, 150), speed, speed, st.sampled_from([0.001, 0.01, 0.05]))
def test_after_a_bounce_the_far_root_is_taken(x, vx, vy, a) -> None:
    # On the wall, moving inwards: the next contact is a real flight, never the round-off root.
    y = a * x * x
    vx2, vy2 = k.reflect_wall(x, vx, vy, a, 1.0)
    inward = vy2 - 2 * a * x * vx2
    assume(inward > 1e-6)
    t = k.wall_contact_time(x, y, vx2, vy2, 0.0, a, G)
    expected = inward / (G / 2 + a * vx2 * vx2)
    assert math.isclose(t, expected, rel_tol=1e-9)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 10_000))
def test_vectorised_pair_row_matches_the_kernel_bit_for_bit(seed: int) -> None:
    sim = Simulation.classic(seed=seed, engine="reference")
    sim.advance(3.0)
    w = sim._world
    eng = ReferenceEngine(w)
    i = seed % w.pos.shape[0]
    row = eng._pair_row(i)
    for j in range(w.pos.shape[0]):
        if j == i:
            continue
        t = k.pair_contact_time(
            *w.pos[i], *w.vel[i], w.t_atom[i], *w.pos[j], *w.vel[j], w.t_atom[j],
            w.radius[i] + w.radius[j], w.gravity,
        )  # fmt: skip
        assert row[j] == t or (math.isinf(row[j]) and math.isinf(t))


def test_reflection_preserves_speed_and_tangent() -> None:
    rng = np.random.default_rng(0)
    for x, vx, vy in rng.uniform(-100, 100, (200, 3)):
        ux, uy = k.reflect_wall(x, vx, vy, 0.01, 1.0)
        tx, ty = 1.0, 0.02 * x  # tangent of y = a x^2
        assert math.isclose(math.hypot(ux, uy), math.hypot(vx, vy), rel_tol=1e-13)
        assert math.isclose(ux * tx + uy * ty, vx * tx + vy * ty, rel_tol=1e-12, abs_tol=1e-10)


def test_pair_contact_after_a_slow_approach_from_far() -> None:
    """Found by hypothesis: two atoms falling together, 29 px apart, meet after 11 239 frames."""
    t = k.pair_contact_time(0.0, 31.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0078125, 2.0, G)
    q1, q2 = _at(0.0, 31.0, 0.0, 0.0, 0.0, t), _at(1.0, 0.0, 0.0, 0.0, 0.0078125, t)
    assert 11_000 < t < 11_500
    assert math.hypot(q1[0] - q2[0], q1[1] - q2[1]) == pytest.approx(2.0, abs=1e-8)
