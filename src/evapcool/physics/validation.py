"""Checks of a starting state (issue 13): no overlapping pair, every centre in the cup.

Used by `Simulation` for given positions and by whatever loads a state from a file.
The overlap search is the core's (core/overlap.c, both editions') where it is installed;
`first_overlap_reference` is its readable oracle and the fallback: a grid in NumPy, linear
in the number of atoms: atoms are grouped into levels by radius (a factor 2 per level) and
each level gets cells two of its largest radii wide, so a pair can only touch within a
3 x 3 block of the larger atom's level, and a block holds a bounded number of
non-overlapping atoms.
"""

from __future__ import annotations

import numpy as np

from evapcool import limits
from evapcool.limits import CONTACT_TOLERANCE, POSITION_MAX, VELOCITY_MAX
from evapcool.physics.core import compiled
from evapcool.physics.world import TRAPPED, World

#: Candidate pairs examined at once (memory: about 100 bytes each).
_CHUNK = 1 << 20
#: After this many candidates per atom an overlap found so far is reported even if an
#: earlier pair might exist: only a heap of overlapping atoms gets there.
_BUDGET_PER_ATOM = 64


def _cells(xy: np.ndarray, size: float) -> tuple[np.ndarray, np.ndarray]:
    c = np.floor(xy / size).astype(np.int64)
    return c[:, 0], c[:, 1]


def _ranks(values: np.ndarray, table: np.ndarray) -> np.ndarray:
    """Index of each value in the sorted table, -1 where it is not there."""
    idx = np.searchsorted(table, values)
    idx_c = np.minimum(idx, len(table) - 1)
    return np.where(table[idx_c] == values, idx_c, -1)


def _pairs_in_chunk(
    q: np.ndarray, start: np.ndarray, count: np.ndarray, order: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(query atom, target atom) for every target slot [start, start + count) of each query."""
    total = int(count.sum())
    rep = np.repeat(np.arange(len(q)), count)
    first = np.cumsum(count) - count
    slot = start[rep] + (np.arange(total) - first[rep])
    return q[rep], order[slot]


def _closer(
    pos: np.ndarray, radii: np.ndarray, i: np.ndarray, j: np.ndarray, tol: float
) -> np.ndarray:
    d = pos[i] - pos[j]
    sigma = (radii[i] + radii[j]) * (1.0 - tol)
    closer: np.ndarray = (i != j) & (d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1] < sigma * sigma)
    return closer


def first_overlap(pos: np.ndarray, radii: np.ndarray, tol: float = 0.0) -> tuple[int, int] | None:
    """The first pair (i < j, least i, then least j) closer than (r_i + r_j)(1 - tol), or None:
    the core's (core/overlap.c) where it is installed, else `first_overlap_reference`'s."""
    module = compiled()
    if module is None:
        return first_overlap_reference(pos, radii, tol)
    x, y = (np.ascontiguousarray(pos[:, k], dtype=np.float64) for k in (0, 1))
    r = np.ascontiguousarray(radii, dtype=np.float64)
    pair: tuple[int, int] | None = module.first_overlap(x, y, r, np.ones(len(r), np.int8), tol)
    return pair


def first_overlap_reference(
    pos: np.ndarray, radii: np.ndarray, tol: float = 0.0
) -> tuple[int, int] | None:
    """first_overlap in NumPy: the readable oracle of core/overlap.c, the fallback without it
    (a heap of overlapping atoms may end its search early, at a pair not the first)."""
    n = len(radii)
    if n < 2:
        return None
    level = np.floor(np.log2(radii / radii.min())).astype(np.int64)
    best: tuple[int, int] | None = None
    seen = 0
    for lev in np.unique(level):
        targets = np.flatnonzero(level == lev)
        size = 2.0 * float(radii[targets].max())
        tx, ty = _cells(pos[targets], size)
        ux, uy = np.unique(tx), np.unique(ty)
        key = _ranks(ty, uy) * len(ux) + _ranks(tx, ux)
        order = np.argsort(key, kind="stable")
        sorted_key = key[order]
        target_atoms = targets[order]
        queries = np.flatnonzero(level <= lev)
        qx, qy = _cells(pos[queries], size)
        for dy in (-1, 0, 1):
            ry = _ranks(qy + dy, uy)
            for dx in (-1, 0, 1):
                rx = _ranks(qx + dx, ux)
                k = np.where((ry >= 0) & (rx >= 0), ry * len(ux) + rx, -1)
                lo = np.searchsorted(sorted_key, k, "left")
                count = np.where(k >= 0, np.searchsorted(sorted_key, k, "right") - lo, 0)
                ends = np.cumsum(count)
                a = 0
                while a < len(queries):
                    b = max(a + 1, int(np.searchsorted(ends, ends[a] - count[a] + _CHUNK, "right")))
                    i, j = _pairs_in_chunk(queries[a:b], lo[a:b], count[a:b], target_atoms)
                    seen += len(i)
                    hit = _closer(pos, radii, i, j, tol)
                    if hit.any():
                        p = np.minimum(i[hit], j[hit])
                        q = np.maximum(i[hit], j[hit])
                        m = np.lexsort((q, p))[0]
                        pair = (int(p[m]), int(q[m]))
                        best = pair if best is None else min(best, pair)
                        if seen > _BUDGET_PER_ATOM * n:
                            return best
                    a = b
    return best


def first_outside(pos: np.ndarray, curvature: float, tol: float = 0.0) -> int | None:
    """The first centre below the wall y = a x^2 (on it is inside), or None."""
    x, y = pos[:, 0], pos[:, 1]
    below = y - curvature * x * x < -tol * np.maximum(np.abs(y), 1.0)
    idx = np.flatnonzero(below)
    return int(idx[0]) if idx.size else None


def check_bounds(pos: np.ndarray, vel: np.ndarray, ids: np.ndarray | None = None) -> None:
    """ValueError naming the first atom farther than POSITION_MAX or faster than VELOCITY_MAX."""
    ids = np.arange(len(pos)) if ids is None else np.asarray(ids)
    far = np.flatnonzero(np.abs(pos).max(axis=1, initial=0.0) > POSITION_MAX)
    if far.size:
        i = int(far[0])
        raise ValueError(
            f"positions must be within {POSITION_MAX:g} px of the cup's lowest point "
            f"(atom {ids[i]} is at ({pos[i, 0]:g}, {pos[i, 1]:g}))"
        )
    fast = np.flatnonzero(np.hypot(vel[:, 0], vel[:, 1]) > VELOCITY_MAX)
    if fast.size:
        i = int(fast[0])
        raise ValueError(
            f"velocities must be at most {VELOCITY_MAX:g} px/frame in speed "
            f"(atom {ids[i]} has ({vel[i, 0]:g}, {vel[i, 1]:g}))"
        )


def check_start(
    pos: np.ndarray,
    vel: np.ndarray,
    radii: np.ndarray,
    curvature: float,
    ids: np.ndarray | None = None,
    tol: float = 0.0,
) -> None:
    """ValueError naming the first offending atoms of a starting state, else None.

    pos, vel: finite (N, 2) arrays (trap coordinates); radii: (N,); ids: the atoms'
    numbers in messages (default 0..N-1, e.g. the trapped atoms' indices in a saved run);
    tol: relative round-off allowed (0 for a new start: exactly y >= a x^2 and
    |r_i - r_j| >= r_i + r_j; CONTACT_TOLERANCE for a state saved mid-run).
    """
    ids = np.arange(len(radii)) if ids is None else np.asarray(ids)
    check_bounds(pos, vel, ids)
    out = first_outside(pos, curvature, tol)
    if out is not None:
        x, y = pos[out]
        raise ValueError(
            f"positions must be centres inside the cup or on its wall, y >= a x^2 "
            f"(atom {ids[out]} at ({x:g}, {y:g}) is below the wall y = {curvature * x * x:g})"
        )
    pair = first_overlap(pos, radii, tol)
    if pair is not None:
        i, j = pair
        d = float(np.hypot(*(pos[i] - pos[j])))
        a, b = int(ids[i]), int(ids[j])
        raise ValueError(
            f"positions must not overlap: every pair at least r_i + r_j apart "
            f"(atoms {a} and {b} are {d:.6g} px apart, r_{a} + r_{b} = "
            f"{radii[i] + radii[j]:.6g} px)"
        )


def check_world(world: World, *, placement: bool = True) -> None:
    """The checks of `Simulation` for a World built another way (a state read from a file):
    every parameter within its range (limits.py), the trapped atoms within reach and speed,
    and (placement) as a start up to CONTACT_TOLERANCE: no overlap, centres in the cup."""
    w = world
    limits.N_ATOMS.check("n_atoms", len(w.radius))
    limits.CURVATURE.check("curvature", w.curvature)
    limits.GRAVITY.check("gravity", w.gravity)
    limits.TRAP_HEIGHT.check("trap_height", w.trap_height)
    limits.TC_EXPONENT.check("tc_exponent", w.tc_exponent)
    for name, values, rng in (("radius", w.radius, limits.RADIUS), ("mass", w.mass, limits.MASS)):
        bad = np.flatnonzero(~((values >= rng.low) & (values <= rng.high)))
        if bad.size:
            i = int(bad[0])
            raise ValueError(f"{name} must be {rng.allowed()} (atom {i} has {float(values[i])!r})")
    trapped = np.flatnonzero(w.status == TRAPPED)
    pos, vel = w.state_at(trapped, w.time)
    if not (np.all(np.isfinite(pos)) and np.all(np.isfinite(vel))):
        raise ValueError("positions and velocities must be finite")
    if placement:
        check_start(pos, vel, w.radius[trapped], w.curvature, trapped, CONTACT_TOLERANCE)
    else:
        check_bounds(pos, vel, trapped)
