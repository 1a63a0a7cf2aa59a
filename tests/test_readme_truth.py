"""What a newcomer reads first holds (issue 49): the install commands work today, the test
section carries no count that drifts, and it names every part test-all.sh may skip."""

from __future__ import annotations

import re
from pathlib import Path

import strictskips
from test_docs import ALL

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")


def _released() -> bool:
    """A version of the CHANGELOG is out (a section other than Unreleased)."""
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    return bool(re.search(r"^## \[\d+\.\d+\.\d+\]", text, re.MULTILINE))


def test_no_install_from_the_index_before_a_release():
    """Until a release is on PyPI, `pip install evapcool` finds nothing: the README and
    getting started install from a clone (or a wheel built there) and say why."""
    if _released():
        return
    for path in (ROOT / "README.md", ROOT / "docs" / "getting-started.md"):
        code = "\n".join(c for p, _, info, c in ALL if p == path and info.startswith("sh"))
        assert not re.search(r"pip install [\"']?evapcool", code), path.name
        assert "pip install -e ." in code, path.name
        words = " ".join(path.read_text(encoding="utf-8").split())
        assert "No release is on PyPI yet" in words and "releasing" in words, path.name


def test_the_test_section_carries_no_counts():
    tests = README.split("## Tests", 1)[1].split("\n## ", 1)[0]
    assert "| tests |" not in tests
    assert not re.search(r"\b\d[\d ]{2,} (tests|passed)\b", tests)


def test_the_readme_names_every_part_test_all_may_skip():
    tests = " ".join(README.split("## Tests", 1)[1].split("\n## ", 1)[0].split())
    for words in ("`nginx` and `caddy`", "running as root or not", "fused multiply-add"):
        assert words in tests, words
    assert "nginx" in strictskips.OPTIONAL_SKIPS.pattern
    assert "last line says what it skipped" in tests
