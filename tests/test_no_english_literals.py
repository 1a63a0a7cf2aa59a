"""No English sentence on the desktop's screens outside the catalog (issue 23).

Scans the desktop's layers (evapcool.app, .view, .game) for string literals a person could
read and fails on any not in ALLOWED. Not scanned: docstrings; the command line's and the
log's words (argparse help, stderr lines, exception messages: the command line stays
English, and a ValueError's text reaches the screen only through a catalog message's
{problem}); dict keys and comparisons (names in code, not words on screen).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "evapcool"
LAYERS = ("app", "view", "game")
#: Calls whose string arguments are for programmers or the terminal, not the window.
TERMINAL_CALLS = {"print", "warn", "log", "error_line", "note_line", "add_argument", "getenv"}
TERMINAL_CALLS |= {"OneLineParser", "ArgumentTypeError", "StartCancelledError", "Thread", "get"}
TERMINAL_CALLS |= {"strftime", "strptime", "setdefault", "environ", "register_profile"}
#: (file, literal) pairs that are not words: symbols, units, key caps, formats, names.
ALLOWED = {
    ("view/scene.py", "Tc"),  # the thermometer's symbols (physics, not English)
    ("view/scene.py", "T"),
    ("view/panels.py", "Ag"),  # a measuring string for the line height
    ("view/fonts.py", "H"),  # the capital whose height matches fonts
    ("game/highscores.py", "Anonymous"),  # the stored name of a nameless winner (data)
    # A saved run's CSV (issue 48): the lab file's first line and its schedule (data).
    ("app/runlog.py", "# evapcool lab results"),
    ("app/runlog.py", "by hand"),
    ("game/autopilot.py", "the demo strategy"),  # a strategy file's description (data)
    # Technical details a translated notice carries as {why} or {reason}: a damaged
    # file's JSON error, a replay code's refusal (the class server's word for it), and the
    # atom-count range of a ParameterError (the command line's).
    ("game/highscores.py", "nested too deeply"),
    ("game/replay.py", "other version"),
    ("game/replay.py", "does not replay to the claimed score"),
    ("game/replay.py", "settings.radius must be "),
    ("game/replay.py", "settings.escape must be rim or knife"),
    ("game/replay.py", "settings.tc_exponent must be in (0, 2]"),
    ("game/replay.py", "seed must be 0..2^53-1"),
    ("game/replay.py", "edition must be desktop or web"),
    ("game/replay.py", "moves: each run needs frames >= 1"),
    ("game/replay.py", "frames must equal the moves' frames"),
    ("game/replay.py", "score must be 0..n_atoms"),
    ("game/replay.py", "score must be 0 without a win"),
    ("game/replay.py", "settings.n_atoms must be "),
    ("game/replay.py", "moves: heights must be "),
    ("game/replay.py", "moves: at most "),
    ("game/settings.py", "below the rim"),
    ("game/settings.py", "below the window's top"),
    ("game/settings.py", "not a JSON object"),
    ("game/settings.py", "not valid JSON: nested too deeply"),
    ("game/settings.py", "not valid JSON: "),
}
#: What makes a literal read as words: a word, a space or comma, another word.
SENTENCE = re.compile(r"[A-Za-z]{2,}[ ,;:]+[A-Za-z]+")


def _docstrings(tree: ast.AST) -> set[int]:
    found = set()
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        first = body[0] if isinstance(body, list) and body else None
        if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
            found.add(id(first.value))
    return found


def _call_name(call: ast.Call) -> str:
    f = call.func
    return f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")


def _for_terminal(node: ast.AST) -> bool:
    """Raise statements, terminal calls, subscripts, comparisons, programmer's docs."""
    if isinstance(node, (ast.Raise, ast.Subscript, ast.Compare, ast.Assert)):
        return True
    if isinstance(node, ast.Call) and _call_name(node) in TERMINAL_CALLS:
        return True
    if isinstance(node, ast.keyword) and node.arg in ("doc", "help", "description"):
        return True
    names = [t.id for t in getattr(node, "targets", []) if isinstance(t, ast.Name)]
    # Command-line templates (BAD_*, *_HELP) and export lists.
    return any(n.startswith("BAD_") or n.endswith("_HELP") or n == "__all__" for n in names)


def _exempt(tree: ast.AST) -> set[int]:
    """Ids of the literals inside anything `_for_terminal` accepts."""
    found: set[int] = set()
    for node in ast.walk(tree):
        if _for_terminal(node):
            found |= {id(n) for n in ast.walk(node) if isinstance(n, ast.Constant)}
    return found


def english_literals(path: Path) -> list[str]:
    """The literals of one file that read as English words on a screen."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    skip = _docstrings(tree) | _exempt(tree)
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in skip:
            text = node.value.strip()
            if SENTENCE.search(text):
                out.append(node.value)
    return out


def _files() -> list[Path]:
    return [p for layer in LAYERS for p in sorted((SRC / layer).glob("*.py"))]


@pytest.mark.parametrize("path", _files(), ids=lambda p: f"{p.parent.name}/{p.name}")
def test_no_english_on_screen_outside_the_catalog(path: Path) -> None:
    name = f"{path.parent.name}/{path.name}"
    if name in ("app/cli.py", "app/open_cli.py"):  # the command line stays English
        return
    found = [s for s in english_literals(path) if (name, s) not in ALLOWED]
    assert found == [], f"{name}: move these to src/evapcool/locales/en.json"


def test_the_scanner_finds_a_sentence(tmp_path: Path) -> None:
    sample = tmp_path / "x.py"
    sample.write_text('"""Doc."""\nraise ValueError("bad thing")\npen.text("Press R now")\n')
    assert english_literals(sample) == ["Press R now"]
