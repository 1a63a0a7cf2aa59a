"""The layers' imports point one way: physics <- game <- view <- app (docs/architecture.md)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "evapcool"

# Which evapcool subpackages each layer may import (besides itself).
ALLOWED = {
    "physics": {"extras"},
    "game": {"physics", "fileio", "about", "extras"},
    "view": {"physics", "game", "fileio", "about", "extras"},
    "lab": {"physics", "fileio", "argtypes", "about", "extras"},
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
