"""Stale translations (issue 37): each translation keeps a hash of the English it was made from.

A message whose English changed after it was translated fails here until it is translated
again and recorded (`python scripts/i18n_review.py record <tag> --keys <key>`).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from evapcool import i18n

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "scripts" / "i18n_review.py"
LOCALES = ROOT / "src" / "evapcool" / "locales"
ENGLISH = i18n.load_catalog(i18n.FALLBACK)["messages"]
TRANSLATED = [t for t in i18n.shipped_locales() if t != i18n.FALLBACK]


@pytest.mark.parametrize("tag", TRANSLATED)
def test_no_translation_is_older_than_its_english(tag: str) -> None:
    stale = i18n.stale_keys(i18n.load_catalog(tag), ENGLISH)
    changed = {key: ENGLISH[key] for key in stale}
    assert changed == {}, f"{tag}: translate these again from today's English, then record them"


@pytest.mark.parametrize("tag", TRANSLATED)
def test_sources_name_only_messages_of_the_catalog(tag: str) -> None:
    catalog = i18n.load_catalog(tag)
    assert list(catalog[i18n.SOURCES]) == list(catalog["messages"])


def test_changed_english_makes_its_translations_stale() -> None:
    catalog = {"messages": {"a": "Eins", "b": "Zwei"}}
    english = {"a": "One", "b": "Two"}
    catalog[i18n.SOURCES] = {k: i18n.source_hash(v) for k, v in english.items()}
    assert i18n.stale_keys(catalog, english) == []
    assert i18n.stale_keys(catalog, {**english, "b": "Two atoms"}) == ["b"]
    del catalog[i18n.SOURCES]["a"]  # never recorded: stale too
    assert i18n.stale_keys(catalog, english) == ["a"]


def test_the_loaders_read_the_messages_not_the_sources() -> None:
    catalog = i18n.Catalog("de")
    assert set(i18n.load_catalog("de")) == {"meta", "messages", i18n.SOURCES}
    assert catalog.messages == i18n.load_catalog("de")["messages"]
    assert i18n.SOURCES not in catalog.meta


def run_script(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, str(SCRIPT), *args], capture_output=True, text=True, timeout=60
    )


def test_review_script_finds_and_records_a_changed_message(tmp_path: Path) -> None:
    for tag in ("en", "de", "fr"):
        shutil.copy(LOCALES / f"{tag}.json", tmp_path / f"{tag}.json")
    folder = ("--folder", str(tmp_path))
    for tag in ("de", "fr"):  # a review of the whole catalog: nothing stale
        assert run_script(*folder, "record", tag).returncode == 0
    assert run_script(*folder, "check").stdout == "0 stale translations in 2 catalogs\n"
    english = json.loads((tmp_path / "en.json").read_text("utf-8"))
    english["messages"]["lose.too_few"] = "Too few atoms are left"
    (tmp_path / "en.json").write_text(json.dumps(english), "utf-8")

    found = run_script(*folder, "check")
    assert found.returncode == 1
    assert "de lose.too_few: translate again from: Too few atoms are left" in found.stdout
    assert "fr lose.too_few" in found.stdout

    recorded = run_script(*folder, "record", "de", "--keys", "lose.too_few")
    assert recorded.returncode == 0, recorded.stderr
    assert run_script(*folder, "check", "de").returncode == 0
    assert run_script(*folder, "check", "fr").returncode == 1
    saved = json.loads((tmp_path / "de.json").read_text("utf-8"))
    assert saved[i18n.SOURCES]["lose.too_few"] == i18n.source_hash("Too few atoms are left")


@pytest.mark.parametrize(
    ("args", "named"),
    [
        (("check", "tlh"), "locale must be one of"),
        (("record", "de", "--keys", "no.such"), "--keys"),
    ],
)
def test_review_script_refuses_in_one_line(args: tuple[str, ...], named: str) -> None:
    result = run_script(*args)
    assert result.returncode == 2
    assert result.stderr.startswith(named) and result.stderr.count("\n") == 1
    assert result.stdout == ""
