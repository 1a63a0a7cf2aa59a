"""Write web/test/cases/overlaps.json: configurations of atoms with the first overlapping pair
the Python edition's readable overlap check finds in them (issue 47), which the core's
check, core/overlap.c, must find in WebAssembly too.

    python scripts/overlap_cases.py           # (re)write the fixture
    python scripts/overlap_cases.py --check   # exit 1 if it is stale

The pair is physics/validation.py's first_overlap_reference (NumPy), checked here against
every pair; tests/physics/test_overlap.py checks the fixture fresh and the native core
against the same oracle, web/test/overlap.test.ts the WebAssembly core against the cases.
Cases: mixed radii (a factor 100 in a case), pairs at their contact distance and a few units in the
last place either side of it, tolerances 0, CONTACT_TOLERANCE and 0.05, masks, heaps.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import numpy as np
from fixture_cli import fixture_main

from evapcool.limits import CONTACT_TOLERANCE
from evapcool.physics.validation import first_overlap_reference

FIXTURE = Path(__file__).resolve().parents[1] / "web" / "test" / "cases" / "overlaps.json"
#: Tolerances the cases use: a new start's, a saved state's, and a wide one.
TOLERANCES = (0.0, CONTACT_TOLERANCE, 0.05)


def reference_pair(
    x: np.ndarray, y: np.ndarray, radius: np.ndarray, include: np.ndarray, tol: float
) -> tuple[int, int] | None:
    """The oracle's first pair among the included atoms, in the atoms' own numbers."""
    idx = np.flatnonzero(include)
    pair = first_overlap_reference(np.column_stack((x[idx], y[idx])), radius[idx], tol)
    return None if pair is None else (int(idx[pair[0]]), int(idx[pair[1]]))


def every_pair(
    x: np.ndarray, y: np.ndarray, radius: np.ndarray, include: np.ndarray, tol: float
) -> tuple[int, int] | None:
    """The first pair by looking at every one (the comparison of the oracle and the core)."""
    n = len(x)
    for i in range(n):
        for j in range(i + 1, n):
            dx, dy = x[i] - x[j], y[i] - y[j]
            lim = (radius[i] + radius[j]) * (1.0 - tol)
            if include[i] and include[j] and dx * dx + dy * dy < lim * lim:
                return i, j
    return None


def configuration(rng: np.random.Generator, n: int) -> dict[str, Any]:
    """n atoms of mixed radii in a box, some pairs put at their contact distance (give or
    take a few units in the last place), some left out by the mask."""
    scale = rng.choice([0.01, 1.0, 12.0])
    radius = scale * rng.choice([0.5, 1.0, 1.0, 3.0, 40.0], n) * rng.uniform(0.8, 1.2, n)
    if rng.random() < 0.6:  # a shuffled lattice spaced about the largest contact distance
        step = 2.0 * float(radius.max(initial=1.0)) * rng.uniform(0.97, 1.5)
        cols = int(np.ceil(np.sqrt(n))) or 1
        spot = rng.permutation(n)
        x, y = (spot % cols) * step, (spot // cols) * step + rng.uniform(0.0, 1e3)
    else:  # a box: overlaps by chance
        side = float(np.sqrt(n) * 4.0 * scale * rng.uniform(0.5, 3.0))
        x, y = rng.uniform(-side, side, n), rng.uniform(0.0, 2.0 * side, n)
    tol = float(rng.choice(TOLERANCES))
    for _ in range(int(rng.integers(0, 4)) if n >= 2 else 0):
        i, j = (int(k) for k in rng.choice(n, 2, replace=False))
        angle = rng.uniform(0.0, 2.0 * np.pi)
        reach = (radius[i] + radius[j]) * (1.0 - tol)
        x[j] = x[i] + reach * np.cos(angle)
        y[j] = y[i] + reach * np.sin(angle)
        steps = int(rng.integers(-3, 4))
        for _ in range(abs(steps)):
            x[j] = np.nextafter(x[j], np.copysign(np.inf, steps * (x[j] - x[i])))
    if n and rng.random() < 0.1:  # a small heap on one spot
        k = rng.choice(n, min(n, 5), replace=False)
        x[k], y[k] = x[k[0]], y[k[0]]
    include = rng.random(n) < rng.choice([1.0, 0.9, 0.5])
    return {"x": x, "y": y, "radius": radius, "include": include, "tol": tol}


def cases() -> list[dict[str, Any]]:
    """Seeded configurations of 0 to 120 atoms, each with the oracle's pair."""
    rng = np.random.default_rng(47)
    out = []
    for n in [0, 1, 2, 2, 3, *rng.integers(4, 60, 70).tolist(), 120, 120]:
        c = configuration(rng, int(n))
        args = (c["x"], c["y"], c["radius"], c["include"], c["tol"])
        pair = reference_pair(*args)
        assert pair == every_pair(*args), (n, pair)
        out.append(
            {
                "x": c["x"].tolist(),
                "y": c["y"].tolist(),
                "radius": c["radius"].tolist(),
                "include": c["include"].astype(int).tolist(),
                "tol": c["tol"],
                "pair": None if pair is None else list(pair),
            }
        )
    return out


def fixture_text() -> str:
    doc = {"comment": __doc__.splitlines()[0], "cases": cases()}
    return json.dumps(doc, separators=(",", ":")) + "\n"


def main(argv: list[str] | None = None) -> int:
    return fixture_main(__doc__, __file__, FIXTURE, fixture_text, argv)


if __name__ == "__main__":
    sys.exit(main())
