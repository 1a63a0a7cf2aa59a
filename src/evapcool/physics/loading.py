"""Initial loading of the cup: rows of cells filled from the bottom (SPEC 1).

The original uses cells of radius R + 8 px for R = 12; for any radius the
cells have radius R * 20/12 and each atom sits at a random point within
R * 8/12 of its cell centre, so neighbouring atoms can never overlap. Speeds
are uniform in [v0 + k dv, v0 + (k + 1) dv] with k = (height of the row) /
40 px, the original's row spacing: hotter atoms start higher for every R.
The random numbers and the arithmetic are the shared start generator's
(`physics.start`, issue 22.1): the same seed gives the same start in the page.
The compiled core computes the same start (core/start.c, both editions' generator);
this module is its readable oracle and the fallback where the core is missing.
"""

from __future__ import annotations

import math
import sys

import numpy as np

from evapcool.limits import ParameterError
from evapcool.physics.core import compiled
from evapcool.physics.start import STREAM_DIRECTION, STREAM_JITTER, STREAM_SPEED, disk_points
from evapcool.physics.start import uniforms as _uniforms

V0 = 100.0 / 30.0  # px / frame, speed at the bottom row
DV = 10.0 / 30.0  # px / frame, speed step per 40 px of height
ROW_SPACING_ORIGINAL = 40.0  # px, the original's row spacing (R = 12)
_CELLS_AT_ONCE = 4096  # cells certified per NumPy call (memory: 64 x this floats)
#: cos(2 pi k / 64) for k = 0..16, as exact literals (no cos at run time, so every
#: language builds the same polygon); the other vertices follow by symmetry.
_QUARTER_COS = (
    1.0,
    0.9951847266721969,
    0.9807852804032304,
    0.9569403357322088,
    0.9238795325112867,
    0.881921264348355,
    0.8314696123025452,
    0.773010453362737,
    0.7071067811865476,
    0.6343932841636455,
    0.5555702330196023,
    0.4713967368259978,
    0.38268343236508984,
    0.29028467725446233,
    0.19509032201612833,
    0.09801714032956077,
    0.0,
)
#: A little above 1 / cos(pi / 64) = 1.00120599647...: the polygon with corners at this
#: many jitter radii circumscribes the jitter disk.
_SECANT = 1.00121


def _polygon() -> tuple[np.ndarray, np.ndarray]:
    """The 64 unit vertices (cos, sin) counter-clockwise from (1, 0)."""
    c = np.array(_QUARTER_COS)
    cos = np.concatenate((c[:16], -c[16:0:-1], -c[:16], c[16:0:-1]))
    sin = np.concatenate((c[16:0:-1], c[:16], -c[16:0:-1], -c[:16]))
    return cos, sin


_POLY_COS, _POLY_SIN = _polygon()


def _disk_inside_cup(xc: np.ndarray, yc: float, rad: float, a: float) -> np.ndarray:
    """True where the disk of radius rad around (xc, yc) lies inside y >= a x^2.

    The region is convex, so a circumscribing polygon with its corners inside
    proves the disk inside.
    """
    rho = rad * _SECANT
    px = xc[:, None] + rho * _POLY_COS[None, :]
    py = yc + rho * _POLY_SIN[None, :]
    inside: np.ndarray = np.all(py > a * px * px, axis=1)
    return inside


def _row(yc: float, need: int, m: int, spacing: float, jitter: float, a: float) -> np.ndarray:
    """x of the first `need` accepted cells of a row of half-width m cells, centre-out.

    Cells go 0, +1, -1, +2, -2, ...; only the first few are built, so a row as wide
    as the cup is in radii (tiny atoms) costs no more than the atoms it takes.
    """
    k = min(m, need // 2 + 1)
    while True:
        js = np.arange(-k, k + 1)
        js = js[np.argsort(np.abs(js) * 2 - (js > 0), kind="stable")]
        xs = js * spacing
        ok = np.concatenate(
            [
                _disk_inside_cup(xs[c : c + _CELLS_AT_ONCE].astype(float), yc, jitter, a)
                for c in range(0, len(xs), _CELLS_AT_ONCE)
            ]
        )
        taken = xs[ok]
        if len(taken) >= need or k >= m:
            row: np.ndarray = taken[:need].astype(float)
            return row
        k = min(m, 2 * k)


def _too_many(n: int, radius: float, curvature: float, found: int) -> ParameterError:
    return ParameterError(
        "n_atoms",
        f"{n} atoms of radius {radius:g} do not fit in the cup "
        f"(curvature {curvature:g}) below the window top (at most {found} fit)",
        joint=("radius", "curvature"),
        sep=": ",
    )


def _cells(n: int, radius: float, curvature: float, y_top: float) -> np.ndarray:
    """Centres of the first n cells, row by row from the bottom, centre-out in a row; fewer
    (the whole rows whose disks stay below y_top) if n do not fit. Work and memory are O(n)
    whatever the radius."""
    jitter = radius * 8.0 / 12.0
    cell = radius + jitter
    spacing = 2.0 * cell
    # Lift row 0 a hair so its jitter disk is certified inside the vertex.
    y0 = jitter * 1.05
    rows = [np.empty((0, 2))]
    found = 0
    k = 0
    while found < n and (yc := y0 + k * spacing) + cell <= y_top:
        m = int(math.sqrt(yc / curvature) / spacing) + 1
        xs = _row(yc, n - found, m, spacing, jitter, curvature)
        rows.append(np.column_stack((xs, np.full(len(xs), yc))))
        found += len(xs)
        k += 1
    return np.concatenate(rows)


def cell_centres(n: int, radius: float, curvature: float, y_top: float) -> np.ndarray:
    """Centres of the first n cells (`_cells`); ParameterError if they do not fit below y_top."""
    centres = _cells(n, radius, curvature, y_top)
    if len(centres) < n:
        raise _too_many(n, radius, curvature, len(centres))
    return centres


def load_cup(
    n: int,
    radius: float,
    curvature: float,
    y_top: float,
    seed: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Positions and velocities of n atoms of equal radius, trap coordinates.

    Each atom sits at a uniform point of the jitter disk round its cell centre and moves
    in a uniform direction (a point of the ring 1/16 <= r^2 < 1, normalised by sqrt).
    Computed by the compiled core where it is installed, else by `load_cup_reference`:
    the same bits.
    """
    module = compiled()
    if module is None:
        return load_cup_reference(n, radius, curvature, y_top, seed)
    pos, vel = np.empty((n, 2)), np.empty((n, 2))
    placed = module.load_cup(pos, vel, radius, curvature, y_top, seed)
    if placed < 0:
        raise RuntimeError(f"no point in the disk for an atom (seed {seed}): impossible odds")
    if placed < n:
        raise _too_many(n, radius, curvature, placed)
    return pos, vel


def load_cup_reference(
    n: int,
    radius: float,
    curvature: float,
    y_top: float,
    seed: int,
) -> tuple[np.ndarray, np.ndarray]:
    """load_cup in NumPy: the readable oracle of core/start.c, the fallback without it."""
    centres = cell_centres(n, radius, curvature, y_top)
    jitter = radius * 8.0 / 12.0
    offset = disk_points(seed, STREAM_JITTER, n)
    pos = np.column_stack(
        (centres[:, 0] + jitter * offset[:, 0], centres[:, 1] + jitter * offset[:, 1])
    )
    level = (centres[:, 1] - centres[0, 1]) / ROW_SPACING_ORIGINAL
    speed = V0 + (level + _uniforms(seed, STREAM_SPEED, np.arange(n))) * DV
    ring = disk_points(seed, STREAM_DIRECTION, n, inner=1.0 / 16.0)
    norm = np.sqrt(ring[:, 0] * ring[:, 0] + ring[:, 1] * ring[:, 1])
    vel = np.column_stack(((speed * ring[:, 0]) / norm, (speed * ring[:, 1]) / norm))
    return pos, vel


def capacity(radius: float, curvature: float, y_top: float) -> int:
    """How many atoms of this radius the loading places with every disk below y_top: the
    whole rows of cells whose disks (cell radius R * 20/12) stay under it, wherever the
    jitter puts them (the count `cell_centres` fills before it would raise)."""
    module = compiled()
    if module is not None:
        return int(module.cup_capacity(radius, curvature, y_top))
    return len(_cells(sys.maxsize, radius, curvature, y_top))
