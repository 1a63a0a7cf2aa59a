"""Initial loading of the cup: rows of cells filled from the bottom (SPEC 1).

The original uses cells of radius R + 8 px for R = 12; for any radius the
cells have radius R * 20/12 and each atom sits at a random point within
R * 8/12 of its cell centre, so neighbouring atoms can never overlap. Speeds
are uniform in [v0 + k dv, v0 + (k + 1) dv] with k = (height of the row) /
40 px, the original's row spacing: hotter atoms start higher for every R.
"""

from __future__ import annotations

import math

import numpy as np

from evapcool.limits import ParameterError

V0 = 100.0 / 30.0  # px / frame, speed at the bottom row
DV = 10.0 / 30.0  # px / frame, speed step per 40 px of height
ROW_SPACING_ORIGINAL = 40.0  # px, the original's row spacing (R = 12)
_POLYGON = 64  # vertices of the polygon that certifies a jitter disk fits
_CELLS_AT_ONCE = 4096  # cells certified per NumPy call (memory: 64 x this floats)


def _disk_inside_cup(xc: np.ndarray, yc: float, rad: float, a: float) -> np.ndarray:
    """True where the disk of radius rad around (xc, yc) lies inside y >= a x^2.

    The region is convex, so a circumscribing polygon with its corners inside
    proves the disk inside.
    """
    rho = rad / math.cos(math.pi / _POLYGON)
    ang = np.linspace(0.0, 2.0 * math.pi, _POLYGON, endpoint=False)
    px = xc[:, None] + rho * np.cos(ang)[None, :]
    py = yc + rho * np.sin(ang)[None, :]
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


def cell_centres(n: int, radius: float, curvature: float, y_top: float) -> np.ndarray:
    """Centres of the first n cells, row by row from the bottom, centre-out in a row.

    Raises ValueError if n cells do not fit with their disks below y_top. Work and
    memory are O(n) whatever the radius.
    """
    jitter = radius * 8.0 / 12.0
    cell = radius + jitter
    spacing = 2.0 * cell
    # Lift row 0 a hair so its jitter disk is certified inside the vertex.
    y0 = jitter * 1.05
    rows: list[np.ndarray] = []
    found = 0
    k = 0
    while found < n:
        yc = y0 + k * spacing
        if yc + cell > y_top:
            raise ParameterError(
                "n_atoms",
                f"{n} atoms of radius {radius:g} do not fit in the cup "
                f"(curvature {curvature:g}) below the window top (at most {found} fit)",
                joint=("radius", "curvature"),
                sep=": ",
            )
        m = int(math.sqrt(yc / curvature) / spacing) + 1
        xs = _row(yc, n - found, m, spacing, jitter, curvature)
        rows.append(np.column_stack((xs, np.full(len(xs), yc))))
        found += len(xs)
        k += 1
    return np.concatenate(rows)


def load_cup(
    n: int,
    radius: float,
    curvature: float,
    y_top: float,
    rng: np.random.Generator,
) -> tuple[np.ndarray, np.ndarray]:
    """Positions and velocities of n atoms of equal radius, trap coordinates."""
    centres = cell_centres(n, radius, curvature, y_top)
    jitter = radius * 8.0 / 12.0
    u = rng.random((n, 4))
    r = jitter * np.sqrt(u[:, 0])
    phi = 2.0 * math.pi * u[:, 1]
    pos = centres + np.column_stack((r * np.cos(phi), r * np.sin(phi)))
    level = (centres[:, 1] - centres[0, 1]) / ROW_SPACING_ORIGINAL
    speed = V0 + (level + u[:, 2]) * DV
    theta = 2.0 * math.pi * u[:, 3]
    vel = np.column_stack((speed * np.cos(theta), speed * np.sin(theta)))
    return pos, vel


def capacity(radius: float, curvature: float, y_top: float) -> int:
    """How many atoms of this radius the loading places with every disk below y_top.

    The count `cell_centres` fills before it would raise: whole rows of cells whose
    disks (cell radius R * 20/12) stay under y_top, wherever the jitter puts them.
    """
    jitter = radius * 8.0 / 12.0
    cell = radius + jitter
    spacing = 2.0 * cell
    y0 = jitter * 1.05
    count, k = 0, 0
    while (yc := y0 + k * spacing) + cell <= y_top:
        m = int(math.sqrt(yc / curvature) / spacing) + 1
        xs = np.arange(-m, m + 1) * spacing
        count += int(np.count_nonzero(_disk_inside_cup(xs.astype(float), yc, jitter, curvature)))
        k += 1
    return count
