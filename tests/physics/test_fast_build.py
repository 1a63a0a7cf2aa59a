"""How the fast engine is built (issue 17): never stale, compiled once, readable, prepared.

The slow test here compiles the engine twice from an empty cache (about half a
minute on the project machine): it is the proof that an edit of the kernels reaches
the compiled engine.
"""

from __future__ import annotations

import ast
import json
import os
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import pytest

pytest.importorskip("numba")

from evapcool.physics.fast import driver, jit  # driver: every compiled function registered

SRC = Path(__file__).resolve().parents[2] / "src"
FAST = SRC / "evapcool" / "physics" / "fast"


def _run(code: str, pythonpath: Path, cache: Path) -> str:
    env = dict(os.environ, PYTHONPATH=str(pythonpath), NUMBA_CACHE_DIR=str(cache))
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=900
    )
    assert out.returncode == 0, out.stderr
    return out.stdout.strip().splitlines()[-1]


def test_importing_the_package_does_not_import_numba() -> None:
    code = "import sys, evapcool.physics.fast as f; print('numba' in sys.modules)"
    assert _run(code, SRC, SRC / "unused") == "False"


def test_the_source_hash_covers_the_kernels(tmp_path: Path) -> None:
    copies = []
    for path in jit.SOURCES:
        copies.append(tmp_path / path.name)
        shutil.copy(path, copies[-1])
    before = jit.source_hash(tuple(copies))
    assert before == jit.SOURCE_HASH
    kernels = tmp_path / "kernels.py"
    kernels.write_text(kernels.read_text() + "\n# an edit\n")
    assert jit.source_hash(tuple(copies)) != before
    assert {p.name for p in jit.SOURCES} >= {"kernels.py", "world.py", "driver.py", "jit.py"}


def test_every_function_uses_the_source_keyed_cache() -> None:
    assert driver.run_until in jit.REGISTRY
    for disp in jit.REGISTRY:
        assert type(disp._cache).__name__ == "SourceKeyedCache", disp


# Run in a fresh process: compile (or load) everything, record what compiles, exercise
# the rare paths, and print a one-atom drop's events from both engines.
_BUILD = """
import collections, json
from numba.core import event
from evapcool import Simulation
from evapcool.physics import fast
from evapcool.physics.fast import driver
with event.install_recorder("numba:compile") as rec:
    fast.prepare(lambda *a: None)
    for kw in ({"escape": "knife", "record_events": True}, {"trap_height": 60.0}):
        sim = Simulation(n_atoms=150, radius=4.0, seed=2, engine="fast", **kw)
        sim.advance(50.0)
        sim.trap_height = 400.0
        sim.advance(20.0)
        sim.force_win()
        sim.advance(5.0)
        sim._engine.grid_errors()
compiles = collections.Counter(
    e.data["dispatcher"].py_func.__qualname__ for _, e in rec.buffer if e.is_start
)
logs = []
for engine in ("reference", "fast"):
    s = Simulation(n_atoms=1, radius=5.0, positions=[[3.0, 80.0]], velocities=[[0.5, 0.0]],
                   engine=engine, record_events=True)
    s.advance(60.0)
    logs.append(s.event_log)
hits = sum(driver.run_until.stats.cache_hits.values())
print(json.dumps({"ref": logs[0], "fast": logs[1], "cache_hits": hits,
                  "compiles": compiles}))
"""


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path, dict]:
    """A copy of the package, compiled from an empty cache: (source root, cache, output)."""
    root = tmp_path_factory.mktemp("build")
    shutil.copytree(SRC / "evapcool", root / "src" / "evapcool",
                    ignore=shutil.ignore_patterns("__pycache__"))  # fmt: skip
    cache = root / "cache"
    return root / "src", cache, json.loads(_run(_BUILD, root / "src", cache))


def test_each_function_compiles_once(built: tuple[Path, Path, dict]) -> None:
    """No needless specialisations: one compile per function, whatever the run does."""
    engine_names = {d.py_func.__qualname__ for d in jit.REGISTRY}
    compiles = {k: v for k, v in built[2]["compiles"].items() if k in engine_names}
    assert len(compiles) > 20
    assert {k: v for k, v in compiles.items() if v > 1} == {}


def test_an_edit_of_the_kernels_reaches_the_compiled_engine(built: tuple[Path, Path, dict]) -> None:
    """Edit a copy of kernels.py: the engine, with its cache warm, must run the new code."""
    src, cache, first = built
    assert first["fast"] == first["ref"] and first["fast"]
    again = json.loads(_run(_BUILD, src, cache))
    assert again["fast"] == first["fast"] and again["cache_hits"] > 0
    assert not set(again["compiles"]) & {d.py_func.__qualname__ for d in jit.REGISTRY}
    kernels = src / "evapcool" / "physics" / "kernels.py"
    text = kernels.read_text()
    weaker = text.replace("A = -(0.5 * g + a * vx * vx)", "A = -(0.25 * g + a * vx * vx)")
    assert weaker != text
    kernels.write_text(weaker)  # the wall is met later: another event log
    edited = json.loads(_run(_BUILD, src, cache))
    assert edited["cache_hits"] == 0
    assert edited["fast"] == edited["ref"]
    assert edited["fast"][0][3] != first["fast"][0][3]


def test_python_only_modules_are_really_python_only() -> None:
    for name in jit.PYTHON_ONLY:
        text = (FAST / name).read_text()
        assert "@hot" not in text and "@entry" not in text and "@part" not in text, name


def test_prepare_reports_progress_from_a_worker_thread() -> None:
    from evapcool.physics import fast

    calls: list[tuple[int, int, str]] = []
    worker = threading.Thread(target=fast.prepare, args=(lambda *c: calls.append(c),))
    worker.start()
    worker.join(timeout=900)
    assert not worker.is_alive()
    assert calls, "no progress at all"
    done = [c[0] for c in calls]
    assert done == sorted(done)
    assert all(0 < d <= t for d, t, _ in calls)
    assert calls[-1][0] == calls[-1][1]
    assert all(isinstance(w, str) and w for _, _, w in calls)
    again: list[tuple[int, int, str]] = []
    fast.prepare(lambda *c: again.append(c))  # idempotent: nothing left but to say so
    assert again and again[-1][0] == again[-1][1]


def test_terminal_progress_is_one_updating_line(capsys: pytest.CaptureFixture[str]) -> None:
    from evapcool.physics.fast.warmup import TerminalProgress

    class Tty:
        def __init__(self) -> None:
            self.text = ""

        def isatty(self) -> bool:
            return True

        def write(self, s: str) -> None:
            self.text += s

        def flush(self) -> None:
            pass

    out = Tty()
    bar = TerminalProgress(out)
    bar.t0 -= 10.0  # as if compiling for 10 s
    for k in range(1, 5):
        bar(k, 4, "the event loop")
    bar.finish()
    assert out.text.count("\n") == 1  # the updating line, then "ready"
    assert out.text.count("\r") >= 4 and "ready" in out.text
    quiet = Tty()
    fast_start = TerminalProgress(quiet)  # a start from the cache: nothing shown
    fast_start(1, 2, "x")
    fast_start.finish()
    assert quiet.text == ""


def test_functions_fit_on_a_screen() -> None:
    """Readable: no function of the engine longer than 60 lines or with more than 6 parameters."""
    for path in sorted(FAST.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.FunctionDef):
                lines = node.end_lineno - node.lineno + 1
                assert lines <= 60, (path.name, node.name, lines)
                assert len(node.args.args) <= 6, (path.name, node.name)


def test_numba_internals_are_reached_in_one_place() -> None:
    """The prefetch intrinsic and the cache class are jit.py's business only."""
    for path in sorted(FAST.glob("*.py")):
        text = path.read_text()
        if path.name != "jit.py":
            assert "llvmlite" not in text and "numba.core" not in text.replace(
                "from numba.core import event", ""
            ), path.name
