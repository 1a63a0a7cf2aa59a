"""`evapcool web` and the bundled browser page (the page's own tests run in Chromium: web/)."""

from __future__ import annotations

import re
import webbrowser

import pytest

from evapcool.cli import main
from evapcool.web import page_path


def test_page_is_bundled_self_contained_and_small() -> None:
    page = page_path()
    text = page.read_text(encoding="utf-8")
    # Won back in session 16 (317 018 -> 291 225 bytes, docs/benchmarks.md): hold the line.
    assert page.stat().st_size < 300_000
    assert '<script type="module">' in text
    # No file or address the page would fetch: everything is inline.
    assert not re.search(r"""(src|href)=["'](?!data:)[^"'#]""", text)
    assert "connect-src 'none'" in text
    assert "@font-face" in text and "data:font/woff2;base64," in text


def test_print_path(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["web", "--print-path"]) == 0
    assert capsys.readouterr().out.strip() == str(page_path())


def test_copy_to_a_folder_and_to_a_missing_one(tmp_path, capsys) -> None:
    assert main(["web", "--copy", str(tmp_path)]) == 0
    assert (tmp_path / "evapcool.html").read_bytes() == page_path().read_bytes()
    assert main(["web", "--copy", str(tmp_path / "nope" / "x.html")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"evapcool web: error: --copy: folder {str(tmp_path / 'nope')!r} does not exist"]


def test_copy_to_a_missing_folder_written_as_one_writes_nothing(tmp_path, capsys) -> None:
    """`--copy DIR/` names a folder: one that does not exist is refused, never a file DIR."""
    assert main(["web", "--copy", f"{tmp_path / 'course'}/"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    folder = str(tmp_path / "course")
    assert err == [f"evapcool web: error: --copy: folder {folder!r} does not exist"]
    assert list(tmp_path.iterdir()) == []
    (tmp_path / "course").mkdir()
    assert main(["web", "--copy", f"{tmp_path / 'course'}/"]) == 0
    assert (tmp_path / "course" / "evapcool.html").read_bytes() == page_path().read_bytes()


def test_opens_the_file_in_the_default_browser(monkeypatch, capsys) -> None:
    opened: list[str] = []
    monkeypatch.setattr(webbrowser, "open", lambda url: opened.append(url) or True)
    assert main(["web"]) == 0
    assert opened == [page_path().as_uri()]
    monkeypatch.setattr(webbrowser, "open", lambda url: False)
    assert main(["web"]) == 1
    assert "no browser could be started" in capsys.readouterr().err


def test_bad_option_is_one_line(capsys) -> None:
    with pytest.raises(SystemExit) as exc:
        main(["web", "--bogus"])
    assert exc.value.code == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_without_javascript_the_page_says_so_in_every_language() -> None:
    from evapcool import i18n

    text = page_path().read_text(encoding="utf-8")
    noscript = re.search(r"<noscript\s*>(.*?)</noscript\s*>", text, re.S)
    assert noscript is not None
    said = dict(re.findall(r'<p[^>]* lang="([^"]+)"[^>]*>([^<]*)</p>', noscript.group(1)))
    assert set(said) == set(i18n.shipped_locales())
    for tag, line in said.items():
        assert line == i18n.load_catalog(tag)["messages"]["page.noscript"]
    assert 'lang="ar" dir="rtl"' in noscript.group(1)
