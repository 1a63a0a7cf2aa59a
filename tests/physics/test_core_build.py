"""The core's build flags keep IEEE arithmetic as written (issue 32).

The probe a * b + c (core/kernels.c) is compiled here the way setup.py compiles the core,
with -march=native added (the CPU's fused multiply-add available to the compiler), and once
with contraction allowed: the first must round twice like Python, the second shows the probe
does catch a contracting build on this machine.
"""

from __future__ import annotations

import ast
import ctypes
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CC = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")


def _setup_flags() -> list[str]:
    """UNIX_FLAGS as written in setup.py (read, not run: setup.py builds when imported)."""
    tree = ast.parse((ROOT / "setup.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "UNIX_FLAGS":
            return list(ast.literal_eval(node.value))
    raise AssertionError("setup.py has no UNIX_FLAGS")


def _probe(tmp_path: Path, flags: list[str]) -> float:
    lib = tmp_path / f"probe{len(list(tmp_path.iterdir()))}.so"
    built = subprocess.run(
        [CC, *flags, "-march=native", "-shared", "-fPIC", "-I", str(ROOT / "core"),
         str(ROOT / "core" / "kernels.c"), "-o", str(lib)],
        capture_output=True, text=True,
    )  # fmt: skip
    if built.returncode != 0 and "native" in built.stderr:
        pytest.skip(f"this compiler has no -march=native: {built.stderr.strip()[:200]}")
    assert built.returncode == 0, built.stderr
    probe = ctypes.CDLL(str(lib)).core_contraction_probe
    probe.restype = ctypes.c_double
    probe.argtypes = [ctypes.c_double] * 3
    return float(probe(0.1, 10.0, -1.0))


@pytest.mark.skipif(CC is None or not (ROOT / "setup.py").exists(), reason="no C compiler")
def test_setup_flags_never_contract_even_with_native_fma(tmp_path) -> None:
    flags = _setup_flags()
    assert "-ffp-contract=off" in flags and "-fno-fast-math" in flags
    visible = [f for f in flags if f != "-fvisibility=hidden"]  # ctypes must see the probe
    assert _probe(tmp_path, visible) == 0.0
    contracting = [f for f in visible if f not in ("-ffp-contract=off", "-std=c11")]
    fused = _probe(tmp_path, [*contracting, "-ffp-contract=fast"])
    if fused == 0.0:
        pytest.skip("this CPU or compiler has no fused multiply-add: nothing to tell apart")
    assert fused == 2.0**-54  # the fused result: the probe tells a contracting build
