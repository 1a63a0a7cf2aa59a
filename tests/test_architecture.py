"""The layers' imports point one way, and no modules import each other in a circle; the C
core's files (core/) call each other one way and none is over 400 lines.

physics <- game <- view <- app, and beside them the lab, the optimizer, the benchmarks and
the web launcher (docs/architecture.md). Every import form counts: `import evapcool.x`,
`from evapcool import x`, `from evapcool.x import y`, relative `from . import x` and
`from ..x import y`, at module level, under TYPE_CHECKING or inside a function. Each
checker is first shown to catch a violation in a small synthetic tree (tmp_path).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = "evapcool"

#: The top-level modules, lowest first; each may import those before it in its own set.
BASE = {
    "about": set(),
    "extras": set(),
    "limits": set(),
    # The lab's CSV format: the lab and the game's "Save this run" both write it.
    "labformat": set(),
    "fileio": {"limits"},
    "argtypes": {"limits", "fileio", "about"},
    # The message catalogs and their translator (issue 23): words for every layer above.
    "i18n": set(),
}
_BELOW_PHYSICS = set(BASE)
#: The package itself ("": evapcool/__init__.py re-exports Simulation and __version__)
#: is above physics: the layers above the game may import it.
_ROOT = ""
#: Which parts of evapcool each layer may import (besides itself). "" is the package itself.
ALLOWED: dict[str, set[str]] = {
    **BASE,
    "physics": {"limits", "extras", "about"},
    "game": {"physics", "fileio", "limits", "about", "extras", "i18n"},
    "view": {"physics", "game", "fileio", "limits", "about", "extras", "i18n"},
    "lab": {"physics", "game", *_BELOW_PHYSICS, _ROOT},
    "optimize": {"physics", "game", "lab", *_BELOW_PHYSICS, _ROOT},
    "app": {"physics", "game", "view", *_BELOW_PHYSICS, _ROOT},
    "web": {"about", "argtypes", "extras"},
    "bench": {"physics", "game", "view", "app", "lab", "optimize", *_BELOW_PHYSICS, _ROOT},
    # The class competition: replays through the game's rules, never the view or the app.
    "classroom": {"physics", "game", *_BELOW_PHYSICS, _ROOT},
    "data": set(),
    "cli": {"app", "lab", "optimize", "bench", "web", "classroom", *_BELOW_PHYSICS, _ROOT},
    "__main__": {"cli"},
    "": {"about", "physics"},
}
FORBIDDEN_THIRD_PARTY = {"physics": {"pygame"}, "game": {"pygame"}, "lab": {"pygame"}}


def modules(root: Path, package: str) -> dict[str, Path]:
    """Dotted module name -> file, for every .py under root/package."""
    out = {}
    for path in sorted((root / package).rglob("*.py")):
        parts = list(path.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def _resolve(name: str, known: dict[str, Path]) -> str:
    """The module a dotted name refers to: itself, or the module that defines it."""
    while name and name not in known:
        name = name.rpartition(".")[0]
    return name


def imports_of(module: str, path: Path, known: dict[str, Path]) -> tuple[set[str], set[str]]:
    """(modules of the package this one imports, other top-level names it imports)."""
    is_package = path.name == "__init__.py"
    inside: set[str] = set()
    outside: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = module.split(".")
                anchor = anchor[: len(anchor) - node.level + (1 if is_package else 0)]
                base = ".".join([*anchor, *([base] if base else [])])
            targets = [f"{base}.{a.name}" for a in node.names] if base else []
            if base and not node.level and base.split(".")[0] != module.split(".")[0]:
                targets = [base]
        else:
            continue
        for target in targets:
            if target.split(".")[0] == module.split(".")[0] and _resolve(target, known):
                inside.add(_resolve(target, known))
            else:
                outside.add(target.split(".")[0])
    inside.discard(module)
    return inside, outside


def graph(root: Path, package: str) -> dict[str, set[str]]:
    known = modules(root, package)
    return {m: imports_of(m, p, known)[0] for m, p in known.items()}


def _part(module: str) -> str:
    """The layer (or top-level module) a module belongs to: '' for the package itself."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def layer_violations(root: Path, package: str, allowed: dict[str, set[str]]) -> list[str]:
    known = modules(root, package)
    bad = []
    for module, path in known.items():
        part = _part(module)
        inside, outside = imports_of(module, path, known)
        for target in sorted(inside):
            other = _part(target)
            if other != part and other not in allowed.get(part, set()):
                bad.append(f"{module} imports {target}")
        for name in sorted(outside & FORBIDDEN_THIRD_PARTY.get(part, set())):
            bad.append(f"{module} imports {name}")
    return bad


def cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """The import circles: strongly connected groups of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                found.append(sorted(group))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def _package_edges(edges: dict[str, set[str]]) -> dict[str, set[str]]:
    """Without the edges into a package's own __init__ from its modules (Python runs a
    parent package first anyway; a circle through it is the package re-exporting)."""
    return {m: {t for t in ts if not m.startswith(t + ".")} for m, ts in edges.items()}


# -- the checkers catch what they should (synthetic trees) --------------------------------


def _tree(tmp_path: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return tmp_path


@pytest.mark.parametrize(
    "form",
    [
        "import pkg.view.draw",
        "from pkg import view",
        "from pkg.view import draw",
        "from pkg.view.draw import line",
        "from .. import view",
        "from ..view import draw",
        "from ..view.draw import line",
        "def f():\n    from pkg.view.draw import line\n",
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import pkg.view.draw\n",
    ],
)
def test_every_import_form_is_seen(tmp_path: Path, form: str) -> None:
    root = _tree(
        tmp_path,
        {
            "pkg/__init__.py": "",
            "pkg/physics/__init__.py": "",
            "pkg/physics/model.py": form + "\n",
            "pkg/view/__init__.py": "",
            "pkg/view/draw.py": "line = 1\n",
        },
    )
    bad = layer_violations(root, "pkg", {"physics": set(), "view": {"physics"}})
    assert bad and all(b.startswith("pkg.physics.model imports pkg.view") for b in bad), bad
    assert not layer_violations(root, "pkg", {"physics": {"view"}, "view": {"physics"}})


def test_a_forbidden_third_party_import_is_seen(tmp_path: Path) -> None:
    root = _tree(tmp_path, {"pkg/__init__.py": "", "pkg/physics/m.py": "import pygame.draw\n"})
    assert layer_violations(root, "pkg", {"physics": set()}) == ["pkg.physics.m imports pygame"]


@pytest.mark.parametrize(
    ("a", "b"),
    [
        ("from pkg.room import b", "def f():\n    from pkg.room.a import X\n"),
        ("from . import b", "from .a import X\n"),
        (
            "import pkg.room.b",
            "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import pkg.room.a\n",
        ),
    ],
)
def test_an_import_circle_is_found(tmp_path: Path, a: str, b: str) -> None:
    root = _tree(
        tmp_path,
        {
            "pkg/__init__.py": "",
            "pkg/room/__init__.py": "",
            "pkg/room/a.py": a + "\nX = 1\n",
            "pkg/room/b.py": b,
            "pkg/room/c.py": "from pkg.room import a\n",
        },
    )
    assert cycles(_package_edges(graph(root, "pkg"))) == [["pkg.room.a", "pkg.room.b"]]


def test_no_circle_in_a_tree_that_points_one_way(tmp_path: Path) -> None:
    root = _tree(
        tmp_path,
        {
            "pkg/__init__.py": "from pkg.room.a import X\n",
            "pkg/room/__init__.py": "from .a import X\n",
            "pkg/room/a.py": "from pkg.room import b\nX = 1\n",
            "pkg/room/b.py": "import pkg.room.c\n",
            "pkg/room/c.py": "",
        },
    )
    assert cycles(_package_edges(graph(root, "pkg"))) == []


# -- the real package ---------------------------------------------------------------------


def test_every_part_of_the_package_has_rules() -> None:
    parts = {_part(m) for m in modules(SRC, PACKAGE)}
    assert parts <= set(ALLOWED), sorted(parts - set(ALLOWED))
    assert {"physics", "game", "view", "app", "lab", "optimize", "bench", "web"} <= parts


def test_layer_imports_point_one_way() -> None:
    assert layer_violations(SRC, PACKAGE, ALLOWED) == []


def test_no_import_circles_between_modules() -> None:
    assert cycles(_package_edges(graph(SRC, PACKAGE))) == []


# -- the class server's rooms (issue 45) --------------------------------------------------

#: The longest file the class server's package may hold.
CLASSROOM_LINES = 400
#: The store layer of the class server, and what it may import of the package besides
#: itself: the views and the server's state sit above it, never below.
STORE_LAYER = ("classroom.store", "classroom.storage", "classroom.pgstore")
STORE_MAY_IMPORT = ("classroom.names", "classroom.ratelimit", "classroom.rooms")
#: The modules that route to the views (above them: a view importing one is a circle).
ROUTERS = ("classroom.app", "classroom.server")


def _under(module: str, package: str, prefixes: tuple[str, ...]) -> bool:
    """Whether a module is one of `prefixes` (dotted, below the package) or inside one."""
    name = module.removeprefix(package + ".")
    return any(name == p or name.startswith(p + ".") for p in prefixes)


def long_classroom_files(root: Path, package: str, limit: int = CLASSROOM_LINES) -> list[str]:
    """The files of the package's classroom/ over `limit` lines, with their lengths."""
    out = []
    for path in sorted((root / package / "classroom").rglob("*.py")):
        lines = len(path.read_text(encoding="utf-8").splitlines())
        if lines > limit:
            out.append(f"{path.relative_to(root).as_posix()}: {lines} lines")
    return out


def room_violations(root: Path, package: str) -> list[str]:
    """Imports against the class server's rooms: the store layer importing anything of the
    classroom above it, a view importing a router, and circles between the views."""
    edges = graph(root, package)
    bad = []
    for module, targets in sorted(edges.items()):
        for target in sorted(targets):
            if _part(target) != "classroom":
                continue
            if _under(module, package, STORE_LAYER) and not _under(
                target, package, STORE_LAYER + STORE_MAY_IMPORT
            ):
                bad.append(f"{module} imports {target}")
            if _under(module, package, ("classroom.views",)) and _under(target, package, ROUTERS):
                bad.append(f"{module} imports {target}")
    views = {
        m: {t for t in ts if _under(t, package, ("classroom.views",))}
        for m, ts in _package_edges(edges).items()
        if _under(m, package, ("classroom.views",))
    }
    bad += [" <-> ".join(group) for group in cycles(views)]
    return bad


def _room_tree(tmp_path: Path, extra: dict[str, str]) -> Path:
    files = {
        "pkg/__init__.py": "",
        "pkg/classroom/__init__.py": "",
        "pkg/classroom/names.py": "",
        "pkg/classroom/store.py": "from pkg.classroom.storage import base\n",
        "pkg/classroom/storage/__init__.py": "",
        "pkg/classroom/storage/base.py": "from pkg.classroom import names\n",
        "pkg/classroom/app.py": "from pkg.classroom.views import play\n",
        "pkg/classroom/views/__init__.py": "",
        "pkg/classroom/views/common.py": "from pkg.classroom import store\n",
        "pkg/classroom/views/play.py": "from pkg.classroom.views import common\n",
        "pkg/classroom/views/board.py": "from pkg.classroom.views.common import x\n",
    }
    return _tree(tmp_path, {**files, **extra})


def test_a_long_classroom_file_is_found(tmp_path: Path) -> None:
    root = _room_tree(
        tmp_path,
        {
            "pkg/classroom/views/board.py": "x = 1\n" * (CLASSROOM_LINES + 1),
            "pkg/classroom/views/play.py": "x = 1\n" * CLASSROOM_LINES,
        },
    )
    assert long_classroom_files(root, "pkg") == [
        f"pkg/classroom/views/board.py: {CLASSROOM_LINES + 1} lines"
    ]


@pytest.mark.parametrize(
    ("where", "text", "found"),
    [
        ("pkg/classroom/storage/base.py", "from pkg.classroom.views import common\n", "base"),
        ("pkg/classroom/store.py", "def f():\n    from pkg.classroom import app\n", "store"),
        ("pkg/classroom/views/common.py", "from pkg.classroom.app import x\n", "common"),
        ("pkg/classroom/views/common.py", "from pkg.classroom.views import play\n", "<->"),
    ],
)
def test_a_room_import_against_the_layers_is_found(
    tmp_path: Path, where: str, text: str, found: str
) -> None:
    assert room_violations(_room_tree(tmp_path, {}), "pkg") == []
    bad = room_violations(_room_tree(tmp_path, {where: text}), "pkg")
    assert len(bad) == 1 and found in bad[0], bad


def test_no_classroom_file_is_over_400_lines() -> None:
    assert long_classroom_files(SRC, PACKAGE) == []


def test_the_class_server_rooms_point_one_way() -> None:
    assert room_violations(SRC, PACKAGE) == []


def test_the_architecture_names_every_room_of_the_class_server() -> None:
    text = (SRC.parent / "docs" / "architecture.md").read_text(encoding="utf-8")
    start = text.index("classroom/ class competitions")
    paragraph = text[start : text.index("\nview/ ", start)]
    rooms = sorted((SRC / PACKAGE / "classroom").rglob("*.py"))
    missing = [p.name for p in rooms if p.name != "__init__.py" and p.name not in paragraph]
    assert missing == []


# -- core/: the C core's rooms call one way, and each fits the house's limit ----------------

CORE = SRC.parent / "core"
#: The house's limit for a file of the core (issue 47).
CORE_FILE_LINES = 400
_C_COMMENT = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)
#: A function defined at file level (not static): its name before the parameters' brace.
_C_DEFINITION = re.compile(r"^(?!static\b)[A-Za-z_][\w \t\*]*?\b(\w+)\s*\([^;{}]*\)\s*\{", re.M)


def c_calls(root: Path) -> dict[str, set[str]]:
    """core/*.c -> the other .c files whose (non-static) functions it calls."""
    texts = {p.name: _C_COMMENT.sub("", p.read_text("utf-8")) for p in sorted(root.glob("*.c"))}
    owner: dict[str, str] = {}
    for name, text in texts.items():
        for m in _C_DEFINITION.finditer(text):
            owner.setdefault(m[1], name)
    return {
        name: {owner[f] for f in re.findall(r"\b(\w+)\s*\(", text) if owner.get(f, name) != name}
        for name, text in texts.items()
    }


def test_a_call_circle_between_c_files_is_found(tmp_path: Path) -> None:
    root = _tree(
        tmp_path,
        {
            "a.c": "int f(int x) { return g(x) + 1; }\nstatic int h(void) { return 0; }\n",
            "b.c": "/* f( in a comment */\nint g(int x) {\n  return x ? f(x - 1) : 0;\n}\n",
            "c.c": "void k(void) { f(2); }\n",
        },
    )
    assert c_calls(root) == {"a.c": {"b.c"}, "b.c": {"a.c"}, "c.c": {"a.c"}}
    assert cycles(c_calls(root)) == [["a.c", "b.c"]]
    (root / "b.c").write_text("int g(int x) { return x; }\n")
    assert cycles(c_calls(root)) == []


def test_the_cores_files_call_each_other_one_way() -> None:
    calls = c_calls(CORE)
    assert len(calls) >= 10 and calls["driver.c"] >= {"calendar.c", "events.c", "predict.c"}
    assert cycles(calls) == []


def test_no_file_of_the_core_is_over_the_limit() -> None:
    files = sorted([*CORE.glob("*.c"), *CORE.glob("*.h")])
    long = {
        p.name: n for p in files if (n := len(p.read_text("utf-8").splitlines())) > CORE_FILE_LINES
    }
    assert len(files) >= 12 and long == {}
