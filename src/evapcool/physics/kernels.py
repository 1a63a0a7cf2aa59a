"""Scalar event kernels: free flight, contact times and collision rules.

Every function here is plain Python on floats with ``math`` only; the compiled
core (core/kernels.c) and the reference engine's NumPy code perform their
operations in the same order, so both engines do the same floating-point
arithmetic and process the same events.

Coordinates are trap coordinates (see docs/model.md): x right, y up, origin at
the lowest point an atom centre can reach; the centre-wall is y = a x^2.
Each atom stores its state (x, y, vx, vy) at its own time t0; predictions are
functions of stored states only, never of the moment they are made.
"""

from __future__ import annotations

import math

INF = math.inf


def flight_x(x: float, vx: float, dt: float) -> float:
    """Horizontal free flight, seed Eq. (3)."""
    return x + vx * dt


def flight_y(y: float, vy: float, half_g: float, dt: float) -> float:
    """Vertical free flight under gravity -g (y up), seed Eq. (3)."""
    return y + vy * dt - half_g * dt * dt


def flight_vy(vy: float, g: float, dt: float) -> float:
    """Vertical velocity after free flight, seed Eq. (4)."""
    return vy - g * dt


def atom_energy(m: float, y: float, vx: float, vy: float, g: float) -> float:
    """1/2 m v^2 + m g y, the summand of seed Eq. (1)."""
    return 0.5 * m * (vx * vx + vy * vy) + m * g * y


def pair_contact_time(
    x1: float,
    y1: float,
    vx1: float,
    vy1: float,
    t1: float,
    x2: float,
    y2: float,
    vx2: float,
    vy2: float,
    t2: float,
    sigma: float,
    g: float,
) -> float:
    """Absolute time when two centres reach distance sigma = R1 + R2 (seed Eqs. 15-19).

    Both states are first carried to the later of their two times. Only an
    approaching pair (r.v < 0) can collide; an overlapping, approaching pair
    collides at that reference time; a receding or missing pair never does.
    The root is taken in the cancellation-free form c / (-b + sqrt(D)).
    """
    half_g = 0.5 * g
    tr = t1 if t1 >= t2 else t2
    d1 = tr - t1
    d2 = tr - t2
    rx = (x1 + vx1 * d1) - (x2 + vx2 * d2)
    ry = (y1 + vy1 * d1 - half_g * d1 * d1) - (y2 + vy2 * d2 - half_g * d2 * d2)
    vx = vx1 - vx2
    vy = (vy1 - g * d1) - (vy2 - g * d2)
    b = rx * vx + ry * vy
    if b >= 0.0:
        return INF
    c = rx * rx + ry * ry - sigma * sigma
    if c <= 0.0:
        return tr
    vv = vx * vx + vy * vy
    disc = b * b - vv * c
    if disc <= 0.0:
        return INF
    return tr + c / (math.sqrt(disc) - b)


def wall_contact_time(
    x: float, y: float, vx: float, vy: float, t0: float, a: float, g: float
) -> float:
    """Absolute time when a trapped centre meets the wall y = a x^2 (SPEC 2.1).

    f(t) = A t^2 + B t + C with A = -(g/2 + a vx^2), B = vy - 2 a x vx,
    C = y - a x^2. From inside (C >= 0) with A < 0 there is exactly one
    non-negative root. A slightly negative C can only be round-off (trapped
    centres are inside by definition), so it is read as 0: an atom on the
    wall moving inwards (B > 0) gets the far root, one moving outwards
    bounces at once. Cancellation-free quadratic formula throughout.
    """
    A = -(0.5 * g + a * vx * vx)
    B = vy - 2.0 * a * x * vx
    C = y - a * x * x
    if C < 0.0:
        C = 0.0
    s = math.sqrt(B * B - 4.0 * A * C)
    if B >= 0.0:
        return t0 + (-0.5 * (B + s)) / A
    return t0 + C / (0.5 * (s - B))


def exit_time(
    x: float,
    y: float,
    vx: float,
    vy: float,
    t0: float,
    g: float,
    x_left: float,
    x_right: float,
    y_bottom: float,
) -> float:
    """Absolute time when a free-falling centre first crosses the window bounds.

    The bounds already include the atom's radius, so crossing them means the
    whole disk has left through the left, right or bottom edge.
    """
    if x <= x_left or x >= x_right or y <= y_bottom:
        return t0
    dt = INF
    if vx < 0.0:
        dt = (x_left - x) / vx
    elif vx > 0.0:
        dt = (x_right - x) / vx
    h = y - y_bottom
    s = math.sqrt(vy * vy + 2.0 * g * h)
    dy = (vy + s) / g if vy > 0.0 else 2.0 * h / (s - vy)
    if dy < dt:
        dt = dy
    return t0 + dt


def collide_pair(
    rx: float,
    ry: float,
    vx1: float,
    vy1: float,
    vx2: float,
    vy2: float,
    m1: float,
    m2: float,
) -> tuple[float, float, float, float]:
    """Elastic hard-disk collision along the line of centres, seed Eqs. (10)-(12).

    (rx, ry) = r2 - r1 at contact. Returns (vx1', vy1', vx2', vy2').
    """
    d = math.sqrt(rx * rx + ry * ry)
    nx = rx / d
    ny = ry / d
    dv = nx * (vx1 - vx2) + ny * (vy1 - vy2)
    k1 = 2.0 * m2 / (m1 + m2) * dv
    k2 = 2.0 * m1 / (m1 + m2) * dv
    return vx1 - k1 * nx, vy1 - k1 * ny, vx2 + k2 * nx, vy2 + k2 * ny


def reflect_wall(x: float, vx: float, vy: float, a: float, keep: float) -> tuple[float, float]:
    """Reflect v about the tangent of y = a x^2 at x, scaled by keep = 1 - damping.

    v' = keep (v - 2 (v.n) n), n = (-2 a x, 1) / |(-2 a x, 1)| (SPEC 2.1,
    the exact form of seed Eqs. 32-34).
    """
    sx = -2.0 * a * x
    nn = sx * sx + 1.0
    vn = vx * sx + vy
    f = 2.0 * vn / nn
    return keep * (vx - f * sx), keep * (vy - f)


def bounce_wall(x: float, vx: float, vy: float, a: float, v_min: float) -> tuple[float, float]:
    """Elastic bounce (SPEC 2.1) that leaves the wall at least v_min along the normal.

    Exact elastic dynamics of an atom grazing or resting on the wall is an
    endless run of ever shorter hops (the limit is sliding), so a bounce whose
    inward normal speed would be below v_min is turned, not scaled: the normal
    part becomes v_min and the tangential part keeps its sign and takes the
    rest of the speed, so the energy is unchanged. Only an atom slower than
    v_min (at rest on the wall) gains speed, to exactly v_min along the normal.
    Hops then last at least about 2 v_min / (g + 2 a v^2): events per frame are bounded.
    """
    ux, uy = reflect_wall(x, vx, vy, a, 1.0)
    sx = -2.0 * a * x
    nn = math.sqrt(sx * sx + 1.0)
    nx = sx / nn  # inward unit normal (nx, ny); unit tangent (ny, -nx)
    ny = 1.0 / nn
    un = ux * nx + uy * ny
    if un >= v_min:
        return ux, uy
    ut = ux * ny - uy * nx
    rest = (ux * ux + uy * uy) - v_min * v_min
    wt = 0.0
    if rest > 0.0:
        wt = math.sqrt(rest)
        if ut < 0.0:
            wt = -wt
    return v_min * nx + wt * ny, v_min * ny - wt * nx


def settle_wall(
    x: float, vx: float, vy: float, a: float, keep: float, v_floor: float
) -> tuple[float, float]:
    """Damped bounce after the win (seed Eq. 34) that cannot collapse.

    A damped atom sliding along the bowl would see its normal speed shrink
    geometrically while gravity keeps its speed near the damping threshold: the
    bounces would come ever faster (inelastic collapse). The inward normal speed
    after the bounce is therefore at least v_floor; the tangential part is damped
    as usual, so every damped bounce still removes energy when v_floor^2 is small
    against the speed threshold.
    """
    ux, uy = reflect_wall(x, vx, vy, a, keep)
    sx = -2.0 * a * x
    nn = math.sqrt(sx * sx + 1.0)
    vn = (ux * sx + uy) / nn
    if vn < v_floor:
        d = (v_floor - vn) / nn
        ux = ux + d * sx
        uy = uy + d
    return ux, uy
