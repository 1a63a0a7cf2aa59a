"""One word per idea in each catalog (issue 37): the glossary in docs/glossary.json.

For every term, a message whose English names it must use the language's word for it, and
no message may use a variant the glossary avoids. Chinese and Japanese use full-width
punctuation around their own text.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest

from evapcool import i18n

ROOT = Path(__file__).resolve().parents[1]
GLOSSARY: dict[str, Any] = json.loads((ROOT / "docs" / "glossary.json").read_text("utf-8"))
TERMS: dict[str, dict[str, Any]] = GLOSSARY["terms"]
ENGLISH = i18n.load_catalog(i18n.FALLBACK)["messages"]
TRANSLATED = [t for t in i18n.shipped_locales() if t != i18n.FALLBACK]


def literal_text(nodes: list[Any]) -> str:
    """A message's own words: every branch of its plurals and selects, no argument names."""
    out: list[str] = []
    for node in nodes:
        if isinstance(node, str):
            out.append(node)
        elif isinstance(node, tuple) and len(node) == 3:
            out += [literal_text(body) for body in node[2].values()]
    return " ".join(out)


def words(tag: str) -> dict[str, str]:
    """Each message of `tag` as the words a person reads."""
    messages = i18n.load_catalog(tag)["messages"]
    return {k: literal_text(i18n.parse_message(v, k)) for k, v in messages.items()}


def glossary_findings(tag: str, messages: dict[str, str], english: dict[str, str]) -> list[str]:
    """Each message missing its language's word for a term, or using an avoided one."""
    found: list[str] = []
    for term, entry in TERMS.items():
        rule = entry.get(tag)
        if rule is None:
            continue
        named = re.compile(entry["en"], re.IGNORECASE)
        use = re.compile(rule["use"], re.IGNORECASE)
        for key, text in messages.items():
            if named.search(english[key]) and not use.search(text):
                found.append(f"{key}: '{term}' is '{rule['use']}' here: {text}")
        for variant in rule.get("avoid", []):
            pattern = re.compile(variant, re.IGNORECASE)
            for key, text in messages.items():
                if key not in rule.get("except", {}) and pattern.search(text):
                    found.append(f"{key}: '{variant}' avoided for '{term}': {text}")
    return found


def test_glossary_covers_every_term_the_issue_names() -> None:
    assert {"trap height", "replay", "challenge", "class", "escape rule", "frames"} <= set(TERMS)
    for term, entry in TERMS.items():
        assert set(entry) - {"en"} <= set(TRANSLATED), term
        english_uses = [k for k, v in ENGLISH.items() if re.search(entry["en"], v, re.IGNORECASE)]
        assert english_uses, f"no English message names '{term}'"


@pytest.mark.parametrize("tag", TRANSLATED)
def test_catalog_follows_its_glossary(tag: str) -> None:
    english = {k: literal_text(i18n.parse_message(v, k)) for k, v in ENGLISH.items()}
    assert glossary_findings(tag, words(tag), english) == []


def test_glossary_check_reports_a_wrong_word() -> None:
    english = {"a": "Trap height 3", "b": "Restart"}
    assert glossary_findings("zh-CN", {"a": "阱高 3", "b": "重新开始"}, english) == []
    found = glossary_findings("zh-CN", {"a": "陷阱高度 3", "b": "重新开始"}, english)
    assert found == ["a: '陷阱' avoided for 'trap height': 陷阱高度 3"]
    found = glossary_findings("zh-CN", {"a": "高度 3", "b": "重新开始"}, english)
    assert found == ["a: 'trap height' is '阱高' here: 高度 3"]
    # An avoided word is reported wherever it stands, not only beside its English term.
    assert glossary_findings("ja", {"a": "トラップの高さ", "b": "クラス対抗戦"}, english) == [
        "b: '対抗戦' avoided for 'class': クラス対抗戦"
    ]


# ASCII punctuation that Chinese and Japanese write full width (：；（），！？).
HALF_WIDTH = re.compile(r"[:;,!?]|(?<![A-Za-z])\(|\)")
# A formula keeps its ASCII brackets: Tc(N).
FORMULA = re.compile(r"[A-Za-z]+\([A-Za-z]*\)")


@pytest.mark.parametrize("tag", ["ja", "zh-CN"])
def test_cjk_punctuation_is_full_width(tag: str) -> None:
    half = {k: t for k, t in words(tag).items() if HALF_WIDTH.search(FORMULA.sub("", t))}
    assert half == {}


# -- one register per language (issue 45): the way each catalog addresses the player --------
REGISTER: dict[str, Any] = GLOSSARY["register"]


def register_findings(tag: str, messages: dict[str, str]) -> list[str]:
    """Each message addressing the player otherwise than its language's register says."""
    rule = REGISTER[tag]
    found: list[str] = []
    for variant in rule["avoid"]:
        pattern = re.compile(variant)  # case-sensitive: German's Sie is not sie
        for key, text in messages.items():
            if key not in rule.get("except", {}) and pattern.search(text):
                found.append(f"{key}: '{variant}' is not '{rule['address']}': {text}")
    return found


def test_every_catalog_has_a_register() -> None:
    assert set(REGISTER) - {"about"} == set(TRANSLATED)
    assert all(REGISTER[tag]["address"] and REGISTER[tag]["avoid"] for tag in TRANSLATED)


@pytest.mark.parametrize("tag", TRANSLATED)
def test_catalog_keeps_one_register(tag: str) -> None:
    assert register_findings(tag, words(tag)) == []


def test_register_check_finds_the_formal_german_of_the_class_bar() -> None:
    # The class bar's line before issue 45 ("Ihr"), beside the debrief's "Dein".
    old = {"page.class_best": "Ihr bestes Spiel: 3 Atome, Platz 2.", "b": "Dein bestes Spiel"}
    found = register_findings("de", old)
    assert len(found) == 1 and found[0].startswith("page.class_best: ")
    # Sie as a pronoun of a thing at a sentence's start is German's "it", not the address.
    assert register_findings("de", {"a": "Sie gilt nur auf diesem Rechner."}) == []
    assert register_findings("de", {"a": "Drücken Sie R."}) != []
    assert register_findings("de", {"a": "Lade Dein Spiel."}) != []
    assert register_findings("zh-CN", {"a": "您的最佳"}) != []
    assert register_findings("fr", {"a": "Ta meilleure partie"}) != []
    assert register_findings("fr", {"a": "Votre meilleure partie"}) == []
