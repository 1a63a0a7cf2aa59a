"""The cost of calling the engine core from Python: the CPython extension against ctypes.

    python scripts/bench_binding.py

Builds the core (core/*.c) once more as a plain shared library with setup.py's flags, loads
it through ctypes, sets up the same classic 49-atom gas in it and in the extension
(evapcool.physics._core), and times, interleaved, (1) a call that processes no event and
(2) one frame of the classic gas, through each binding; then Simulation.advance(1.0), which
also brings the World up to date. Medians of 5 repeats, ns or us per call (issue 32).
"""

from __future__ import annotations

import ast
import ctypes
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from evapcool import Simulation
from evapcool.physics.core import compiled

ROOT = Path(__file__).resolve().parents[1]
C_INT, C_DOUBLE, C_PTR = ctypes.c_int32, ctypes.c_double, ctypes.c_void_p


def setup_flags() -> list[str]:
    tree = ast.parse((ROOT / "setup.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "UNIX_FLAGS":
            return [f for f in ast.literal_eval(node.value) if f != "-fvisibility=hidden"]
    raise SystemExit("setup.py has no UNIX_FLAGS")


def ctypes_core(folder: Path) -> ctypes.CDLL:
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if cc is None:
        raise SystemExit("bench_binding: needs a C compiler (cc)")
    lib = folder / "libcore.so"
    sources = [str(p) for p in sorted((ROOT / "core").glob("*.c"))]
    subprocess.run([cc, *setup_flags(), "-shared", "-fPIC", *sources, "-o", str(lib)], check=True)
    core = ctypes.CDLL(str(lib))
    core.core_new.restype = C_PTR
    core.core_allocate.restype, core.core_allocate.argtypes = C_PTR, [C_PTR, C_INT, C_INT]
    core.core_load.argtypes = [C_PTR, C_PTR, *[C_DOUBLE] * 5, *[C_INT] * 3, C_DOUBLE, C_INT,
                               C_DOUBLE, C_DOUBLE]  # fmt: skip
    core.core_start.argtypes = [C_PTR, C_DOUBLE, C_DOUBLE]
    core.core_advance_to.restype, core.core_advance_to.argtypes = C_INT, [C_PTR, C_DOUBLE]
    core.core_fill_tc_table.argtypes = [C_PTR, C_DOUBLE, C_DOUBLE]
    return core


def per_call(call, t0: float, step: float, reps: int) -> float:
    """Median seconds per call of call(t) over 5 repeats, t advancing by step a call."""
    t = [t0]
    out = []
    for _ in range(5):
        start = time.perf_counter()
        for _ in range(reps):
            t[0] += step
            call(t[0])
        out.append((time.perf_counter() - start) / reps)
    return statistics.median(out)


def main() -> int:
    module = compiled()
    if module is None:
        print("bench_binding: the compiled core is not installed", file=sys.stderr)
        return 2
    w = Simulation.classic(seed=1, engine="fast")._world
    n = len(w.radius)
    inputs = np.concatenate([w.pos[:, 0], w.pos[:, 1], w.vel[:, 0], w.vel[:, 1], w.t_atom,
                             w.radius, w.mass])  # fmt: skip
    status = w.status.astype(np.int32)
    fixed = (w.gravity, w.curvature, w.x_left, w.x_right, w.y_bottom)
    native = module.Core(n, 1)
    native.load(inputs, status, *fixed, False, True, False, 0.0, False, 0, 0)
    native.fill_tc_table(w.tc0, w.tc_exponent)
    native.start(w.energy_sum, w.trap_height)
    with tempfile.TemporaryDirectory() as tmp:
        lib = ctypes_core(Path(tmp))
        c = lib.core_new()
        place = lib.core_allocate(c, n, 1)
        ctypes.memmove(place, inputs.ctypes.data, inputs.nbytes)
        ctypes.memmove(place + inputs.nbytes, status.ctypes.data, status.nbytes)
        lib.core_load(c, place, *fixed, 0, 1, 0, 0.0, 0, 0.0, 0.0)
        lib.core_fill_tc_table(c, w.tc0, w.tc_exponent)
        lib.core_start(c, w.energy_sum, w.trap_height)
        advance = lib.core_advance_to
        rows = {"CPython": native.advance_to, "ctypes": lambda t: advance(c, t)}
        print("one call that processes no event, ns (median of 5):")
        for name, call in rows.items():
            print(f"  {name:>8}: {per_call(call, 0.0, 0.0, 100_000) * 1e9:8.0f}")
        print("one frame of the classic gas, us (median of 5, 2000 frames each):")
        for name, call in rows.items():
            print(f"  {name:>8}: {per_call(call, 0.0, 1.0, 2000) * 1e6:8.2f}")
    sim = Simulation.classic(seed=1, engine="fast")
    frame = per_call(lambda _: sim.advance(1.0), 0.0, 1.0, 2000)
    print(f"Simulation.advance(1.0), the World brought up to date: {frame * 1e6:.2f} us a frame")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
