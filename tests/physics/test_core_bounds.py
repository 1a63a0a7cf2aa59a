"""The core's pair scan skips a pair only when it surely comes too late (core/kernels.c).

`pair_contact_time(p, q, sigma, g, beat)` returns inf without solving for a pair whose
contact a bound shows to be past `beat`. Compiled here from the core's source with setup.py's
flags and called through ctypes: whatever `beat` is, it returns either the time the
reference engine's kernel gives, bit for bit, or inf for a contact later than `beat`; and
never inf for one at or before `beat`, ties included (a tie is decided by the keys).
"""

from __future__ import annotations

import ctypes
import math
import shutil
import subprocess
from pathlib import Path

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from evapcool.physics import kernels as k
from evapcool.physics.simulation import GRAVITY

ROOT = Path(__file__).resolve().parents[2]
CC = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
FLAGS = ["-std=c11", "-O2", "-ffp-contract=off", "-fno-fast-math"]


class State(ctypes.Structure):
    """core/tables.h's State: what the pair scan reads of an atom."""

    _fields_ = [
        ("x", ctypes.c_double), ("y", ctypes.c_double),
        ("vx", ctypes.c_double), ("vy", ctypes.c_double),
        ("t", ctypes.c_double), ("radius", ctypes.c_double),
        ("count", ctypes.c_int64), ("atom", ctypes.c_int64),
    ]  # fmt: skip


@pytest.fixture(scope="module")
def contact_time(tmp_path_factory):
    if CC is None or not (ROOT / "core" / "kernels.c").exists():
        pytest.skip("no C compiler, or no core sources beside the tests")
    lib = tmp_path_factory.mktemp("bounds") / "kernels.so"
    built = subprocess.run(
        [CC, *FLAGS, "-shared", "-fPIC", str(ROOT / "core" / "kernels.c"), "-o", str(lib)],
        capture_output=True, text=True,
    )  # fmt: skip
    assert built.returncode == 0, built.stderr
    f = ctypes.CDLL(str(lib)).pair_contact_time
    f.restype = ctypes.c_double
    f.argtypes = [ctypes.POINTER(State), ctypes.POINTER(State)] + [ctypes.c_double] * 3
    return f


coord = st.floats(-60, 60, allow_nan=False)
speed = st.floats(-8, 8, allow_nan=False)
stamp = st.floats(0, 5000, allow_nan=False)
# where `beat` lies against the pair's own contact time: exactly on it, an ulp either side,
# a little either side, anywhere
# how far apart (relative) a touching pair starts: 0 is touching, which round-off may make
# an overlap
GAPS = [0.0, 1e-16, 1e-14, 1e-12, 1e-9, 1e-6]
offset = st.sampled_from(["on", "ulp-", "ulp+", "near-", "near+"]) | st.floats(-50, 50)


def _beat(full: float, tr: float, how: object) -> float:
    base = full if math.isfinite(full) else tr + 3.0
    if how == "on":
        return base
    if how in ("ulp-", "ulp+"):
        return math.nextafter(base, -math.inf if how == "ulp-" else math.inf)
    if how in ("near-", "near+"):
        return base + (-1e-9 if how == "near-" else 1e-9) * max(1.0, abs(base))
    return base + float(how)  # type: ignore[arg-type]


@settings(max_examples=1500, deadline=None)
@given(coord, coord, speed, speed, stamp, coord, coord, speed, speed, st.floats(0, 3),
       st.floats(0.5, 15), offset)  # fmt: skip
def test_a_pair_is_skipped_only_when_it_comes_too_late(
    contact_time, x1, y1, vx1, vy1, t1, x2, y2, vx2, vy2, lag, sigma, how
) -> None:
    t2 = t1 + lag  # the second atom's clock a little later, as in a scan
    p = State(x1, y1, vx1, vy1, t1, sigma / 2, 0, 0)
    q = State(x2, y2, vx2, vy2, t2, sigma / 2, 0, 1)
    reference = k.pair_contact_time(x1, y1, vx1, vy1, t1, x2, y2, vx2, vy2, t2, sigma, GRAVITY)
    full = contact_time(ctypes.byref(p), ctypes.byref(q), sigma, GRAVITY, math.inf)
    assert full == reference or (math.isnan(full) and math.isnan(reference))
    beat = _beat(full, max(t1, t2), how)
    t = contact_time(ctypes.byref(p), ctypes.byref(q), sigma, GRAVITY, beat)
    if full <= beat:
        assert t == full  # in time (or tied): never skipped
    else:
        assert t == full or t == math.inf  # too late: skipped, or solved all the same


@settings(max_examples=1500, deadline=None)
@given(coord, coord, speed, speed, stamp, st.floats(0, 2 * math.pi), speed, speed,
       st.sampled_from(GAPS), st.floats(0.5, 15), offset)  # fmt: skip
# found by this test: touching, approaching at 1e-169 px/frame (b * b underflows to 0), and
# at 1e-161 (b * b keeps 4 digits: the bound was too tight)
@example(0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0665467813888665e-169, 0.0, 1.0, "on")
@example(
    4.0, 0.0, 0.0, 0.0, 0.0, 0.5383971056360455, 0.0, -1.4379284358935283e-161, 0.0, 15.0, "on"
)
def test_a_touching_pair_is_never_skipped_in_time(
    contact_time, x1, y1, vx1, vy1, t1, angle, vx2, vy2, gap, sigma, how
) -> None:
    """Pairs a hair apart (or overlapping by round-off): where the bound is tightest."""
    reach = sigma * (1.0 + gap)
    x2, y2 = x1 + reach * math.cos(angle), y1 + reach * math.sin(angle)
    p = State(x1, y1, vx1, vy1, t1, sigma / 2, 0, 0)
    q = State(x2, y2, vx2, vy2, t1, sigma / 2, 0, 1)
    reference = k.pair_contact_time(x1, y1, vx1, vy1, t1, x2, y2, vx2, vy2, t1, sigma, GRAVITY)
    full = contact_time(ctypes.byref(p), ctypes.byref(q), sigma, GRAVITY, math.inf)
    assert full == reference
    beat = _beat(full, t1, how)
    t = contact_time(ctypes.byref(p), ctypes.byref(q), sigma, GRAVITY, beat)
    if full <= beat:
        assert t == full
    else:
        assert t == full or t == math.inf
