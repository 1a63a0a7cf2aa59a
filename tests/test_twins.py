"""The register of twins (docs/twins.md) lists every same-named Python/TypeScript pair.

A Python file under src/evapcool/ and a TypeScript file under web/src/ with the same name
are either a concept written in both languages (the first table: why, and what binds them)
or two different things (the second table); a pair in neither fails here, and so does a
TypeScript twin that does not name its Python file in its first lines (issue 47).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

#: This module checks the repository itself (web/ beside src/): not in the sdist.
pytestmark = pytest.mark.skipif(
    not (Path(__file__).resolve().parents[1] / "web" / "package.json").exists(),
    reason="web/ is not in the sdist",
)

ROOT = Path(__file__).resolve().parents[1]
PY = ROOT / "src" / "evapcool"
TS = ROOT / "web" / "src"
REGISTER = ROOT / "docs" / "twins.md"
#: A twin names its Python file within this many first lines.
HEAD_LINES = 12


def same_named(py_root: Path, ts_root: Path) -> set[tuple[str, str]]:
    """(Python path under py_root, TypeScript path under ts_root) of every same-named pair."""
    py: dict[str, list[str]] = {}
    for p in py_root.rglob("*.py"):
        py.setdefault(p.stem, []).append(p.relative_to(py_root).as_posix())
    pairs = set()
    for t in ts_root.rglob("*.ts"):
        if not t.name.endswith(".d.ts"):
            for p in py.get(t.stem, []):
                pairs.add((p, t.relative_to(ts_root).as_posix()))
    return pairs


def register(text: str) -> tuple[set[tuple[str, str]], set[tuple[str, str]]]:
    """(twins, same name only) from the two tables of the register."""
    twins_part, _, other_part = text.partition("## Same name, different things")

    def rows(part: str) -> set[tuple[str, str]]:
        found = re.findall(r"^\| `([\w/.]+\.py)` \| `([\w/.]+\.ts)` \|", part, flags=re.M)
        return set(found)

    return rows(twins_part), rows(other_part)


def unregistered(py_root: Path, ts_root: Path, text: str) -> list[str]:
    twins, others = register(text)
    return sorted(f"{p} / {t}" for p, t in same_named(py_root, ts_root) - twins - others)


def unnamed(py_root: Path, ts_root: Path, text: str) -> list[str]:
    """TypeScript twins whose first lines do not name their Python file."""
    bad = []
    for p, t in sorted(register(text)[0]):
        head = "\n".join((ts_root / t).read_text("utf-8").splitlines()[:HEAD_LINES])
        if p not in head:
            bad.append(t)
    return bad


def _tree(root: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")


def test_the_checks_catch_a_pair_missing_and_a_twin_unnamed(tmp_path: Path) -> None:
    files = {
        "py/game/rules.py": "",
        "py/app/store.py": "",
        "ts/game/rules.ts": "/** The game (Python: game/rules.py). */\n",
        "ts/app/store.ts": "",
        "ts/app/only.ts": "",
        "ts/app/types.d.ts": "",
        "py/app/types.py": "",
    }
    _tree(tmp_path, files)
    py, ts = tmp_path / "py", tmp_path / "ts"
    text = "| `game/rules.py` | `game/rules.ts` | why | cases |\n"
    assert unregistered(py, ts, text) == ["app/store.py / app/store.ts"]
    text += "## Same name, different things\n| `app/store.py` | `app/store.ts` | two stores |\n"
    assert unregistered(py, ts, text) == []
    assert unnamed(py, ts, text) == []
    (ts / "game" / "rules.ts").write_text("/** The game. */\n")
    assert unnamed(py, ts, text) == ["game/rules.ts"]


def test_every_same_named_pair_is_in_the_register() -> None:
    text = REGISTER.read_text(encoding="utf-8")
    pairs = same_named(PY, TS)
    assert len(pairs) >= 40
    assert unregistered(PY, TS, text) == []


def test_the_register_names_only_files_that_exist() -> None:
    twins, others = register(REGISTER.read_text(encoding="utf-8"))
    assert not twins & others
    gone = [f for p, t in twins | others for f in (PY / p, TS / t) if not f.is_file()]
    assert gone == []


@pytest.mark.parametrize("part", ["twins", "others"])
def test_each_row_says_why(part: str) -> None:
    """Every row has its reasons filled in (no empty cell)."""
    twins_part, _, other_part = REGISTER.read_text("utf-8").partition("## Same name")
    rows = [r for r in (twins_part if part == "twins" else other_part).splitlines()]
    rows = [r for r in rows if r.startswith("| `")]
    width = 4 if part == "twins" else 3
    assert rows and all(
        len(cells := [c.strip() for c in r.strip("|").split(" | ")]) == width and all(cells)
        for r in rows
    )


def test_every_typescript_twin_names_its_python_file_in_its_first_lines() -> None:
    assert unnamed(PY, TS, REGISTER.read_text(encoding="utf-8")) == []


def test_the_pages_saved_run_has_the_labs_columns():
    """The page's "Save this run" (web/src/app/runlog.ts) writes the lab's CSV: its first line
    and columns are labformat.py's, in order (the desktop's runlog imports them)."""
    from evapcool.labformat import COLUMNS, CSV_MAGIC

    text = (TS / "app" / "runlog.ts").read_text(encoding="utf-8")
    listed = re.search(r"export const LAB_COLUMNS = \[(.*?)\] as const;", text, re.S)
    assert listed is not None, "LAB_COLUMNS not found in runlog.ts"
    assert tuple(re.findall(r'"(\w+)"', listed.group(1))) == COLUMNS
    assert f'const CSV_MAGIC = "{CSV_MAGIC}";' in text
