"""Issue 47: the overlap check is the core's (core/overlap.c), in both editions; the NumPy
grid of validation.py is its readable oracle and the fallback without the compiled core."""

from __future__ import annotations

import functools
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scripthelp import load_script

from evapcool.limits import CONTACT_TOLERANCE
from evapcool.physics import validation
from evapcool.physics.core import compiled
from evapcool.physics.validation import first_overlap, first_overlap_reference

ROOT = Path(__file__).resolve().parents[2]
CORE = compiled()
needs_core = pytest.mark.skipif(CORE is None, reason="the compiled core is not built")


@functools.cache
def _script() -> ModuleType:
    return load_script("overlap_cases")


def core_pair(x, y, radius, include, tol) -> tuple[int, int] | None:
    assert CORE is not None
    return CORE.first_overlap(x, y, radius, include.astype(np.int8), tol)


@st.composite
def configurations(draw):
    """Mixed radii (a factor 2000), near-touching pairs (contact give or take a few units in
    the last place), tolerances, masks."""
    n = draw(st.integers(0, 48))
    floats = st.floats(-80, 80, allow_subnormal=False)
    x = np.array(draw(st.lists(floats, min_size=n, max_size=n)), dtype=float)
    y = np.array(draw(st.lists(floats, min_size=n, max_size=n)), dtype=float)
    sizes = st.one_of(st.floats(0.01, 0.1), st.floats(0.5, 3), st.floats(5, 20))
    radius = np.array(draw(st.lists(sizes, min_size=n, max_size=n)), dtype=float)
    tol = draw(st.sampled_from([0.0, CONTACT_TOLERANCE, 1e-3, 0.05]) | st.floats(0, 0.5))
    for _ in range(draw(st.integers(0, 3)) if n >= 2 else 0):
        i, j = draw(st.lists(st.integers(0, n - 1), min_size=2, max_size=2, unique=True))
        angle = draw(st.floats(0, 2 * np.pi))
        reach = (radius[i] + radius[j]) * (1.0 - tol)
        x[j], y[j] = x[i] + reach * np.cos(angle), y[i] + reach * np.sin(angle)
        for _ in range(draw(st.integers(0, 3))):
            x[j] = np.nextafter(x[j], draw(st.sampled_from([-np.inf, np.inf])))
    include = np.array(draw(st.lists(st.booleans(), min_size=n, max_size=n)), dtype=bool)
    if draw(st.booleans()):
        include[:] = True
    return x, y, radius, include, tol


@needs_core
@settings(max_examples=400, deadline=None)
@given(configurations())
def test_the_cores_pair_is_the_readable_checks(config) -> None:
    x, y, radius, include, tol = config
    want = _script().reference_pair(x, y, radius, include, tol)
    assert core_pair(x, y, radius, include, tol) == want
    assert want == _script().every_pair(x, y, radius, include, tol)


@needs_core
def test_a_heap_a_crowd_and_wide_mixtures_are_answered_exactly() -> None:
    # Every atom on one spot: the first pair, at once; a tiny atom reaching a giant.
    n = 200_000
    heap = np.zeros(n), np.full(n, 10.0), np.ones(n), np.ones(n, bool)
    assert core_pair(*heap, 0.0) == (0, 1)
    mask = np.ones(n, bool)
    mask[:5] = False
    assert core_pair(heap[0], heap[1], heap[2], mask, 0.0) == (5, 6)
    x = np.append(np.arange(1000) * 0.05, 25.0)
    y = np.append(np.zeros(1000), 500.0 + 0.02 - 1e-9)
    radius = np.append(np.full(1000, 0.02), 500.0)
    assert core_pair(x, y, radius, np.ones(1001, bool), 0.0) == (500, 1000)


def test_without_the_core_the_reference_answers(monkeypatch: pytest.MonkeyPatch) -> None:
    pos = np.array([[-100.0, 300.0], [0.0, 300.0], [100.0, 300.0], [5.0, 300.0]])
    radii = np.full(4, 12.0)
    monkeypatch.setattr(validation, "compiled", lambda: None)
    assert first_overlap(pos, radii) == first_overlap_reference(pos, radii) == (1, 3)
    assert first_overlap(pos[:3], radii[:3]) is None


def test_the_shared_cases_are_fresh() -> None:
    assert _script().main(["--check"]) == 0
