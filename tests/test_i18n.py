"""Message catalogs (issue 23): completeness, placeholders, plurals, fixtures, choice."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from babel import Locale

from evapcool import i18n

ROOT = Path(__file__).resolve().parents[1]
GOLDEN = ROOT / "web" / "test" / "golden" / "i18n.json"
REAL_LOCALES = [t for t in i18n.shipped_locales()]
ENGLISH = i18n.load_catalog("en")["messages"]

# Shared with web/test/i18n.test.ts through the golden file.
MATCH_CASES = [
    (["de-AT"], "de"),
    (["pt"], "pt-BR"),
    (["pt-PT"], "pt-BR"),
    (["zh-Hans-CN"], "zh-CN"),
    (["zh"], "zh-CN"),
    (["en-US"], "en"),
    (["ja-JP"], "ja"),
    (["ar-EG"], "ar"),
    (["xx", "fr-CA"], "fr"),
    (["sv", "ko_KR.UTF-8"], "ko"),
    (["en-XA"], "en-XA"),
]
OUTPUT_CASES = [
    ("en", "win.score", {"n": 1}),
    ("en", "win.score", {"n": 12345}),
    ("de", "win.score", {"n": 12345}),
    ("de", "chart.tc_law", {"p": 0.667}),
    ("fr", "status.restart", {"height": 1234.5}),
    ("fr", "win.score", {"n": 1000000}),
    ("pl", "status.atoms", {"n": 3}),
    ("pl", "status.atoms", {"n": 5}),
    ("pl", "status.atoms", {"n": 22}),
    ("ar", "win.score", {"n": 2}),
    ("ar", "win.score", {"n": 11}),
    ("ja", "win.score", {"n": 1500}),
    ("es", "settings.max_atoms", {"n": 1200, "radius": 2.5}),
    ("es", "win.score", {"n": 12000}),
    ("pl", "win.score", {"n": 1234}),
    ("it", "status.restart", {"height": 98765.4321}),
    ("nl", "status.restart", {"height": 1200}),
    ("pt-BR", "status.slow", {"percent": 87.5}),
    ("ko", "status.atoms", {"n": 1024}),
    ("zh-CN", "chart.tc_law", {"p": 0.4}),
    ("en-XA", "win.score", {"n": 7}),
    ("de", "notice.mode", {"mode": "autopilot", "name": "Greedy"}),
    ("de", "notice.mode", {"mode": "player", "name": "Ada"}),
]


def expected_outputs() -> list[dict[str, object]]:
    """The shared key+args -> output table, formatted by the Python interpreter."""
    rows: list[dict[str, object]] = []
    for tag, key, args in OUTPUT_CASES:
        text = i18n.Catalog(tag).t(key, **args)
        rows.append({"locale": tag, "key": key, "args": args, "expected": text})
    return rows


def test_golden_fixture_is_current() -> None:
    data = {
        "outputs": expected_outputs(),
        "matches": [{"wanted": w, "expected": e} for w, e in MATCH_CASES],
    }
    text = json.dumps(data, ensure_ascii=False, indent=2) + "\n"
    if not GOLDEN.exists() or GOLDEN.read_text("utf-8") != text:
        GOLDEN.write_text(text, "utf-8")
    assert json.loads(GOLDEN.read_text("utf-8")) == data


@pytest.mark.parametrize("tag", REAL_LOCALES)
def test_catalog_complete_with_english_placeholders(tag: str) -> None:
    catalog = i18n.load_catalog(tag)
    assert set(catalog["meta"]) >= {"tag", "name", "direction", "author", "reviewed"}
    assert catalog["meta"]["direction"] == ("rtl" if tag == "ar" else "ltr")
    assert catalog["meta"]["reviewed"] is (tag == "en")
    messages = catalog["messages"]
    assert set(messages) == set(ENGLISH)
    for key, text in messages.items():
        expected = i18n.placeholders(i18n.parse_message(ENGLISH[key], key))
        assert i18n.placeholders(i18n.parse_message(text, key)) == expected, key


@pytest.mark.parametrize("tag", REAL_LOCALES)
def test_plurals_cover_cldr_categories(tag: str) -> None:
    categories = set(Locale.parse(tag, sep="-").plural_form.tags) | {"other"}
    for key, text in i18n.load_catalog(tag)["messages"].items():
        for offered in i18n.plural_selectors(i18n.parse_message(text, key)):
            assert offered >= categories, (key, categories - offered)


def test_numbers_follow_the_locale() -> None:
    assert i18n.Catalog("de").t("win.score", n=12345) == "Punkte: 12.345 Atome"
    assert i18n.Catalog("en").t("chart.tc_law", p=0.4) == "Tc law: Tc ~ N^p, p = 0.4"
    assert i18n.Catalog("de").t("chart.tc_law", p=0.4).endswith("p = 0,4")
    assert i18n.Catalog("pl").t("status.atoms", n=5) == "zostało 5 atomów"


@pytest.mark.parametrize(("wanted", "expected"), MATCH_CASES)
def test_best_match(wanted: list[str], expected: str) -> None:
    assert i18n.best_match(wanted, [*i18n.shipped_locales(), i18n.PSEUDO]) == expected


def test_choice_order(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in ("LANGUAGE", "LC_ALL", "LC_MESSAGES"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("LANG", "ja_JP.UTF-8")
    monkeypatch.setattr(i18n.system_locale, "getlocale", lambda: (None, None))
    assert i18n.choose_locale() == "ja"
    assert i18n.choose_locale(saved="de") == "de"
    assert i18n.choose_locale(cli="ar", saved="de") == "ar"
    assert i18n.choose_locale(cli="xx", saved="nl-BE") == "nl"
    monkeypatch.setenv("LANG", "C")
    assert i18n.choose_locale() == "en"


def test_unknown_locale_is_one_clear_line() -> None:
    with pytest.raises(ValueError, match=r"locale must be one of .* \(got 'tlh'\)"):
        i18n.Catalog("tlh")


def test_missing_key_falls_back_to_english_and_is_recorded() -> None:
    catalog = i18n.Catalog("de")
    del catalog.messages["lose.too_few"]
    i18n.missing_keys.clear()
    assert catalog.t("lose.too_few") == "Too few atoms left"
    assert i18n.missing_keys == {"de": {"lose.too_few"}}


SAMPLE_ARGS = {"n": 2, "p": 0.5, "height": 400, "percent": 80, "problem": "x", "radius": 3}
SAMPLE_ARGS |= {"mode": "a", "name": "B"}


#: The desktop applet's placeholders (help, charts, table, settings, notices).
DESK_ARGS = dict(speed="1/2", step=5, fast=4, slow="1/4", low=80, high=450, fps=60, physics=2.5)
DESK_ARGS |= dict(drawing=3.1, t="0.123", tc="0.2", count="16/16", time="1:23.4", max=62)
DESK_ARGS |= dict(names="radius", default="'rim'", why="not valid JSON", s=12)
DESK_ARGS |= dict(done=2, total=6)


#: An argument for every placeholder in the catalogs (the class server's too).
ARGS_IN_USE = {
    **dict(n=2, p=0.5, height=400, percent=80, problem="x", radius=3, mode="a", name="B"),
    **dict(url="http://h/", path="/p", id=1, reason="r", detail="d", got=1, wanted=2),
    **dict(allowed="1..2", score=3, frames=4, runs=5, first=6, last=7, escape="rim", seed=8),
    **DESK_ARGS,
}


def test_no_locale_misses_keys_in_use() -> None:
    # Every placeholder the catalog uses gets a value (a number unless listed above).
    names = {n for k, m in ENGLISH.items() for n in i18n.placeholders(i18n.parse_message(m, k))}
    args = {**dict.fromkeys(names, 2), **ARGS_IN_USE}
    i18n.missing_keys.clear()
    for tag in REAL_LOCALES:
        catalog = i18n.Catalog(tag)
        for key in ENGLISH:
            catalog.t(key, **args)
    assert i18n.missing_keys == {}


def test_pseudo_locale_expands_and_keeps_placeholders() -> None:
    pseudo = i18n.Catalog("en-XA")
    for key, text in ENGLISH.items():
        fake = pseudo.messages[key]
        assert fake.startswith("[") and fake.endswith("]")
        assert len(fake) >= 1.4 * len(text)
        nodes = i18n.parse_message(fake, key)
        assert i18n.placeholders(nodes) == i18n.placeholders(i18n.parse_message(text, key))
    assert pseudo.t("win.score", n=3).startswith("[Šçöré: 3 àtömš")


@pytest.mark.parametrize("bad", ["{n, plural, one {x}", "{n, date}", "a } b"])
def test_malformed_message_names_the_key(bad: str) -> None:
    with pytest.raises(i18n.MessageSyntaxError, match="'k'"):
        i18n.parse_message(bad, "k")
