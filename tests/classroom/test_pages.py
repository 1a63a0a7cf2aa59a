"""The class pages' scripts and styles: built from web/src/classroom, shipped as package data,
inlined whole and allowed by their hashes only."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import pytest

from evapcool.classroom import pages


def words(key: str) -> str:
    return f"[{key}]"


def test_pages_inline_the_built_files_their_policies_allow() -> None:
    projector = pages.projector_page(words, "en", "ltr", "http://10.0.0.2:8000/", "<svg></svg>")
    lecturer = pages.lecturer_page(words, "en", "ltr", "KEY")
    for text, name, policy in (
        (projector, "projector", pages.PROJECTOR_POLICY),
        (lecturer, "lecturer", pages.LECTURER_POLICY),
    ):
        script, style = pages.built(f"{name}.js"), pages.built(f"{name}.css")
        assert len(script) > 500 and len(style) > 100
        assert f"<script>{script}</script>" in text and f"<style>{style}</style>" in text
        assert f"script-src {pages.source_hash(script)};" in policy
        assert f"style-src {pages.source_hash(style)};" in policy


def test_a_built_file_with_a_closing_tag_is_refused(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    (tmp_path / "web" / "class").mkdir(parents=True)
    (tmp_path / "web" / "class" / "bad.js").write_text('x("</script><script>alert(1)")')
    monkeypatch.setattr(resources, "files", lambda _package: tmp_path)
    with pytest.raises(ValueError, match=r"bad\.js holds a closing tag"):
        pages.built("bad.js")
