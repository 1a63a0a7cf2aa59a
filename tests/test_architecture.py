"""The layers' imports point one way: physics <- game <- view <- app (docs/architecture.md)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "evapcool"

# Which evapcool subpackages each layer may import (besides itself).
ALLOWED = {
    "physics": {"limits", "extras"},
    "game": {"physics", "fileio", "limits", "about", "extras"},
    "view": {"physics", "game", "fileio", "limits", "about", "extras"},
    "lab": {"physics", "game", "fileio", "argtypes", "limits", "about", "extras"},
}
#: Top-level modules below physics (or beside it): what each may import from evapcool.
BASE_MODULES = {
    "about": set(),
    "extras": set(),
    "limits": set(),
    "fileio": {"limits"},
    "argtypes": {"limits", "fileio", "about"},
}
FORBIDDEN_MODULES = {"physics": {"pygame"}, "game": {"pygame"}, "lab": {"pygame"}}


def _imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module)
    return names


@pytest.mark.parametrize("layer", sorted(ALLOWED))
def test_layer_imports_point_one_way(layer: str) -> None:
    files = list((SRC / layer).rglob("*.py"))
    if not files:
        pytest.skip(f"{layer} has no modules yet")
    for f in files:
        for name in _imports(f):
            top = name.split(".")[0]
            assert top not in FORBIDDEN_MODULES.get(layer, set()), f"{f.name} imports {name}"
            if top == "evapcool" and "." in name:
                sub = name.split(".")[1]
                assert sub == layer or sub in ALLOWED[layer], f"{f.name} imports {name}"


@pytest.mark.parametrize("module", sorted(BASE_MODULES))
def test_base_modules_import_only_what_is_below_them(module: str) -> None:
    for name in _imports(SRC / f"{module}.py"):
        if name.split(".")[0] == "evapcool":
            sub = name.split(".")[1] if "." in name else ""
            assert sub in BASE_MODULES[module], f"{module}.py imports {name}"
