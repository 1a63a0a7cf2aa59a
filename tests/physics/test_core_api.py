"""The core's boundary is declared once, in core/evapcool_core.h (issue 47).

What both editions take from the header (the model's constants, CPython's method tables and
wrappers, the stub, the WebAssembly exports' interface) is written by scripts/core_api.py and
must be fresh; no core file declares an export of its own; the binding sees the API alone;
an extension built in place from sources since edited is refused, naming the rebuild.
"""

from __future__ import annotations

import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import pytest

from evapcool.physics import core, coresource, model, world

#: This module checks the repository itself (web/ beside src/): not in the sdist.
pytestmark = pytest.mark.skipif(
    not (Path(__file__).resolve().parents[2] / "web" / "package.json").exists(),
    reason="web/ is not in the sdist",
)

ROOT = Path(__file__).resolve().parents[2]


def _script(name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, ROOT / "scripts" / f"{name}.py")
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # its dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def test_every_file_written_from_the_header_is_fresh() -> None:
    """The check CI runs: each generated file is exactly what the header gives now."""
    api = _script("core_api")
    stale = [
        path.relative_to(ROOT).as_posix()
        for path, text in api.outputs()
        if not path.exists() or path.read_text(encoding="utf-8") != text
    ]
    assert stale == [], "run python scripts/core_api.py"
    run = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "core_api.py"), "--check"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert (run.returncode, run.stderr) == (0, "")


def test_the_check_names_a_stale_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Edit a constant in a copy of the header: --check fails and names what to regenerate."""
    api = _script("core_api")
    header = tmp_path / "evapcool_core.h"
    text = api.HEADER.read_text(encoding="utf-8")
    header.write_text(text.replace("#define WIN_DAMPING 0.2", "#define WIN_DAMPING 0.3"))
    monkeypatch.setattr(api, "HEADER", header)
    assert api.main(["--check"]) == 1
    py = dict(api.outputs())[api.PHYSICS / "model.py"]
    assert "WIN_DAMPING = 0.3\n" in py


def test_the_constants_are_the_headers_bit_for_bit() -> None:
    """model.py holds each #define's value as C computes it (doubles round-trip exactly)."""
    api = _script("core_api")
    parsed = api.parse(api.HEADER.read_text(encoding="utf-8"))
    assert len(parsed.constants) >= 25
    for c in parsed.constants:
        assert getattr(model, c.name) == api.value_of(c.text), c.name
    assert model.GRAVITY == 10.0 / 30.0 and model.TC_EXPONENT_SEED == 2.0 / 3.0
    # world.py and constants.py pass them on; nothing is written twice
    assert world.EVENT_NAMES == ("pair", "wall", "escape", "gone", "knife")
    assert world.ESCAPE_RULES[model.ESCAPE_KNIFE] == "knife"
    assert world.WALL_MIN_NORMAL_SPEED is model.WALL_MIN_NORMAL_SPEED
    for path in (ROOT / "src" / "evapcool" / "physics").glob("*.py"):
        if path.name != "model.py":
            text = path.read_text(encoding="utf-8")
            assert not re.search(r"^(TRAPPED|EV_PAIR|WIN_DAMPING|GRAVITY) = ", text, re.M), path


def test_the_page_takes_its_constants_from_the_generated_model() -> None:
    """web/src/physics/constants.ts copies no number of the model: it re-exports model.ts."""
    text = (ROOT / "web" / "src" / "physics" / "constants.ts").read_text(encoding="utf-8")
    assert not re.search(r"export const \w+ = [\d(]", text)
    assert 'from "./model"' in text


def test_exports_are_declared_in_the_header_only() -> None:
    """No core file exports on its own; the binding includes the API and nothing inside."""
    for path in sorted((ROOT / "core").glob("*.c")):
        text = path.read_text(encoding="utf-8")
        assert "export_name" not in text and "CORE_API(" not in text, path.name
    binding = (ROOT / "src" / "evapcool" / "physics" / "_coremodule.c").read_text("utf-8")
    assert re.findall(r'#include "(\w+\.h)"', binding) == ["evapcool_core.h", "_core_glue.h"]
    assert "core->" not in binding


def test_the_compiled_module_has_every_binding_the_header_names() -> None:
    module = core.compiled()
    if module is None:
        pytest.skip("the compiled core is not installed here (core.available() is False)")
    api = _script("core_api")
    bound = api.bindings(api.parse(api.HEADER.read_text(encoding="utf-8")))
    assert len(bound) >= 18
    for b in bound:
        owner = module.Core if b.owner else module
        assert callable(getattr(owner, b.name)), b.name
    stub = (ROOT / "src" / "evapcool" / "physics" / "_core.pyi").read_text(encoding="utf-8")
    public = {n for n in dir(module.Core) if not n.startswith("_")}
    assert public == {b.name for b in bound if b.owner and not b.name.startswith("_")}
    assert all(f"def {n}(" in stub for n in public)


def _checkout_copy(tmp_path: Path, extension: Path) -> Path:
    """The sources the extension is built from and the package, copied (never edited here)."""
    copy = tmp_path / "checkout"
    shutil.copytree(ROOT / "core", copy / "core")
    shutil.copytree(
        ROOT / "src", copy / "src", ignore=shutil.ignore_patterns("__pycache__", "*.pyc")
    )
    shutil.copy2(ROOT / "setup.py", copy / "setup.py")
    assert (copy / "src" / "evapcool" / "physics" / extension.name).is_file()
    return copy


def _use_core(copy: Path) -> subprocess.CompletedProcess[str]:
    """A fresh interpreter importing the copy's package and asking for its core."""
    code = "from evapcool.physics import core; print(core.compiled().__file__)"
    env = {"PYTHONPATH": str(copy / "src"), "PATH": "/usr/bin:/bin"}
    return subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=False
    )


def test_an_edited_core_built_in_place_is_refused_naming_the_rebuild(tmp_path: Path) -> None:
    """In a copy of the checkout with its in-place build: used as built, refused once a core
    source changes (a 1e-6 gain per wall bounce would otherwise run the old core)."""
    module = core.compiled()
    if module is None or coresource.checkout_of(Path(module.__file__ or "")) is None:
        pytest.skip("the compiled core here is not built in place in a source checkout")
    extension = Path(module.__file__ or "")
    copy = _checkout_copy(tmp_path, extension)
    fresh = _use_core(copy)
    assert fresh.returncode == 0, fresh.stderr
    assert fresh.stdout.strip().startswith(str(copy))

    kernels = copy / "core" / "kernels.c"
    text = kernels.read_text(encoding="utf-8")
    head = "void bounce_wall(State *s, double a, double v_min) {"
    edited = text.replace(head, head + "\n  s->vx *= 1.000001; /* a gain per bounce */")
    assert edited != text
    kernels.write_text(edited, encoding="utf-8")
    stale = _use_core(copy)
    assert stale.returncode != 0
    last = stale.stderr.strip().splitlines()[-1]
    assert "StaleCoreError" in last and "older than its sources" in last
    assert last.endswith(f"rebuild it with: {coresource.REBUILD}")


def test_the_command_line_refuses_a_stale_core_in_one_line(tmp_path: Path) -> None:
    """evapcool's commands say it in one line (exit 2), no traceback."""
    module = core.compiled()
    if module is None or coresource.checkout_of(Path(module.__file__ or "")) is None:
        pytest.skip("the compiled core here is not built in place in a source checkout")
    copy = _checkout_copy(tmp_path, Path(module.__file__ or ""))
    (copy / "core" / "game.c").write_text(
        (copy / "core" / "game.c").read_text(encoding="utf-8") + "\n/* edited */\n"
    )
    env = {"PYTHONPATH": str(copy / "src"), "PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}
    run = subprocess.run(
        [sys.executable, "-m", "evapcool", "lab", "--atoms", "20", "--frames", "1", "--out",
         str(tmp_path / "out.csv")],
        capture_output=True, text=True, env=env, cwd=tmp_path, check=False,
    )  # fmt: skip
    assert run.returncode == 2, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in run.stderr
    assert lines[0].endswith(coresource.REBUILD)
    assert not (tmp_path / "out.csv").exists()
