"""Message catalogs: one JSON file per locale, an ICU MessageFormat subset, locale choice.

The subset: ``{name}``, ``{n, number}``, ``{n, plural, one {# atom} other {# atoms}}``
(with ``=N`` exact cases and ``#``) and ``{k, select, a {...} other {...}}``.
Plural categories and number formats come from Babel (CLDR), as ``Intl`` does in the page.
"""

from __future__ import annotations

import hashlib
import json
import locale as system_locale
import os
from collections.abc import Iterable, Mapping
from functools import lru_cache
from importlib import resources
from typing import Any

from babel import Locale
from babel import numbers as babel_numbers
from babel.numbers import format_decimal

FALLBACK = "en"
PSEUDO = "en-XA"
BAD_LOCALE = "locale must be one of {allowed} (got {value!r})"
BAD_SYNTAX = "message {key!r}: {problem} at position {position}"

# Keys asked for but missing in the chosen catalog, per locale (read by the tests).
missing_keys: dict[str, set[str]] = {}


def shipped_locales() -> list[str]:
    """The locale tags with a catalog file in the package."""
    folder = resources.files("evapcool") / "locales"
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".json"))


@lru_cache(maxsize=32)
def language_name(tag: str) -> str:
    """The language's own name (its catalog's meta name): "Deutsch", "العربية"."""
    return str(load_catalog(tag)["meta"]["name"])


def load_catalog(tag: str) -> dict[str, Any]:
    """One catalog file: ``{"meta": {...}, "messages": {...}}``."""
    if tag == PSEUDO:
        return pseudo_catalog(load_catalog(FALLBACK))
    text = (resources.files("evapcool") / "locales" / f"{tag}.json").read_text("utf-8")
    data: dict[str, Any] = json.loads(text)
    return data


#: A catalog's optional third section: per message, a hash of the English it translates
#: (written by scripts/i18n_review.py; the loaders of both editions read meta and messages only).
SOURCES = "sources"


def source_hash(english: str) -> str:
    """The short hash kept beside a translation: of the English message it was made from."""
    return hashlib.sha256(english.encode("utf-8")).hexdigest()[:10]


def stale_keys(catalog: Mapping[str, Any], english: Mapping[str, str]) -> list[str]:
    """Keys whose English changed since their translation was made (or was never recorded)."""
    sources = catalog.get(SOURCES, {})
    return sorted(k for k in catalog["messages"] if sources.get(k) != source_hash(english[k]))


def _split_tag(tag: str) -> list[str]:
    return [part.lower() for part in tag.replace("_", "-").split(".")[0].split("-") if part]


# Script subtags that pick a region when the catalog is keyed by region (zh-Hans -> zh-CN).
SCRIPT_REGION = {"hans": "cn", "hant": "tw"}


def best_match(wanted: Iterable[str], available: Iterable[str]) -> str | None:
    """The first wanted tag's best shipped catalog: exact, script->region, language only."""
    shipped = {t.lower(): t for t in available}
    for tag in wanted:
        parts = _split_tag(tag)
        if not parts:
            continue
        lang = parts[0]
        region = next((SCRIPT_REGION.get(p, p) for p in parts[1:] if len(p) in (2, 4)), None)
        if region in SCRIPT_REGION.values() or (region and len(region) == 2):
            full = f"{lang}-{region}"
            if full in shipped:
                return shipped[full]
        if lang in shipped:
            return shipped[lang]
        same_language = sorted(t for t in shipped if t.split("-")[0] == lang)
        if same_language:
            return shipped[same_language[0]]
    return None


def system_languages() -> list[str]:
    """The system locale: LANGUAGE, LC_ALL, LC_MESSAGES, LANG, then locale.getlocale()."""
    found: list[str] = []
    for name in ("LANGUAGE", "LC_ALL", "LC_MESSAGES", "LANG"):
        found += [v for v in os.environ.get(name, "").split(":") if v and v not in ("C", "POSIX")]
    current = system_locale.getlocale()[0]
    if current:
        found.append(current)
    return found


def choose_locale(cli: str | None = None, saved: str | None = None) -> str:
    """``--lang`` beats the saved setting beats the system locale; English if none match."""
    available = [*shipped_locales(), PSEUDO]
    for source in ([cli] if cli else [], [saved] if saved else [], system_languages()):
        match = best_match(source, available)
        if match:
            return match
    return FALLBACK


class MessageSyntaxError(ValueError):
    """A catalog message outside the supported MessageFormat subset."""


def _parse(text: str, pos: int, key: str, in_plural: bool) -> tuple[list[Any], int]:
    """Parse until an unmatched ``}``; nodes are str, ('#',) or (name, kind, options)."""
    nodes: list[Any] = []
    buf: list[str] = []
    while pos < len(text):
        ch = text[pos]
        if ch == "'" and pos + 1 < len(text) and text[pos + 1] in "{}#'":
            end = text.find("'", pos + 1)
            if text[pos + 1] == "'":
                buf.append("'")
                pos += 2
                continue
            if end < 0:
                end = len(text)
            buf.append(text[pos + 1 : end])
            pos = end + 1
            continue
        if ch == "}":
            break
        if ch == "#" and in_plural:
            nodes += ["".join(buf), ("#",)]
            buf = []
            pos += 1
            continue
        if ch != "{":
            buf.append(ch)
            pos += 1
            continue
        nodes.append("".join(buf))
        buf = []
        node, pos = _parse_argument(text, pos + 1, key, in_plural)
        nodes.append(node)
    nodes.append("".join(buf))
    return [n for n in nodes if n != ""], pos


def _parse_argument(text: str, pos: int, key: str, in_plural: bool) -> tuple[Any, int]:
    close = text.find("}", pos)
    comma = text.find(",", pos)
    if close < 0:
        raise MessageSyntaxError(BAD_SYNTAX.format(key=key, problem="unclosed {", position=pos))
    if comma < 0 or comma > close:
        return (text[pos:close].strip(), "text", {}), close + 1
    name = text[pos:comma].strip()
    rest = comma + 1
    comma2 = text.find(",", rest)
    if comma2 < 0 or comma2 > close:
        kind = text[rest:close].strip()
        if kind != "number":
            raise MessageSyntaxError(BAD_SYNTAX.format(key=key, problem=kind, position=rest))
        return (name, "number", {}), close + 1
    kind = text[rest:comma2].strip()
    if kind not in ("plural", "select"):
        raise MessageSyntaxError(BAD_SYNTAX.format(key=key, problem=kind, position=rest))
    options: dict[str, list[Any]] = {}
    pos = comma2 + 1
    while True:
        while pos < len(text) and text[pos].isspace():
            pos += 1
        if pos >= len(text):
            raise MessageSyntaxError(BAD_SYNTAX.format(key=key, problem="unclosed", position=pos))
        if text[pos] == "}":
            return (name, kind, options), pos + 1
        brace = text.find("{", pos)
        selector = text[pos:brace].strip()
        body, pos = _parse(text, brace + 1, key, kind == "plural" or in_plural)
        options[selector] = body
        pos += 1


def parse_message(text: str, key: str = "?") -> list[Any]:
    """The node list of one message; MessageSyntaxError names the key and position."""
    nodes, pos = _parse(text, 0, key, False)
    if pos != len(text):
        raise MessageSyntaxError(BAD_SYNTAX.format(key=key, problem="stray }", position=pos))
    return nodes


def placeholders(nodes: list[Any]) -> set[str]:
    """The argument names a message uses."""
    names: set[str] = set()
    for node in nodes:
        if isinstance(node, tuple) and len(node) == 3:
            names.add(node[0])
            for body in node[2].values():
                names |= placeholders(body)
    return names


def plural_selectors(nodes: list[Any]) -> list[set[str]]:
    """For each plural argument, the category keywords it offers (``=N`` excluded)."""
    found: list[set[str]] = []
    for node in nodes:
        if isinstance(node, tuple) and len(node) == 3:
            if node[1] == "plural":
                found.append({k for k in node[2] if not k.startswith("=")})
            for body in node[2].values():
                found += plural_selectors(body)
    return found


class Catalog:
    """Translated messages of one locale, English behind every missing key."""

    def __init__(self, locale: str = FALLBACK) -> None:
        available = [*shipped_locales(), PSEUDO]
        tag = best_match([locale], available)
        if tag is None:
            raise ValueError(BAD_LOCALE.format(allowed=", ".join(available), value=locale))
        self.locale = tag
        data = load_catalog(tag)
        self.meta: dict[str, Any] = data["meta"]
        self.messages: dict[str, str] = data["messages"]
        self.english: dict[str, str] = load_catalog(FALLBACK)["messages"]
        self.babel_locale = Locale.parse("en" if tag == PSEUDO else tag, sep="-")
        # Messages are drawn every frame: each is parsed once per catalog.
        self._parsed: dict[str, list[Any]] = {}

    def t(self, key: str, **args: Any) -> str:
        """The message ``key`` formatted with ``args``; English if this locale lacks it."""
        text = self.messages.get(key)
        babel_locale = self.babel_locale
        if text is None:
            missing_keys.setdefault(self.locale, set()).add(key)
            text = self.english[key]
            babel_locale = Locale.parse(FALLBACK)
        nodes = self._parsed.get(text)
        if nodes is None:
            nodes = self._parsed[text] = parse_message(text, key)
        return _render(nodes, args, babel_locale, None)

    def format_number(self, value: float) -> str:
        """A number with the locale's decimal mark and grouping."""
        return _number(value, self.babel_locale)


# CLDR minimumGroupingDigits (Babel does not apply it; Intl does): 1200 but 12 345.
MIN_GROUPING_DIGITS = {"es": 2, "it": 2, "pl": 2}


def _number(value: Any, babel_locale: Locale) -> str:
    """Up to three decimals, the locale's marks, grouping only from the CLDR minimum."""
    min_grouping = MIN_GROUPING_DIGITS.get(babel_locale.language, 1)
    grouped = abs(value) >= 10 ** (2 + min_grouping)
    pattern = "#,##0.###" if grouped else "0.###"
    return str(format_decimal(value, format=pattern, locale=babel_locale))


def _render(nodes: list[Any], args: Mapping[str, Any], loc: Locale, count: Any) -> str:
    out: list[str] = []
    for node in nodes:
        if isinstance(node, str):
            out.append(node)
        elif node == ("#",):
            out.append(_number(count, loc))
        else:
            name, kind, options = node
            value = args[name]
            if kind == "text":
                out.append(str(value))
            elif kind == "number":
                out.append(_number(value, loc))
            elif kind == "select":
                body = options.get(str(value), options["other"])
                out.append(_render(body, args, loc, count))
            else:
                exact = f"={value}"
                category = loc.plural_form(value)
                body = options.get(exact) or options.get(category) or options["other"]
                out.append(_render(body, args, loc, value))
    return "".join(out)


PSEUDO_MAP = str.maketrans("aceinosuyACEINOSUY", "àçéîñöšüýÀÇÉÎÑÖŠÜÝ")


def _pseudo_nodes(nodes: list[Any]) -> str:
    out: list[str] = []
    for node in nodes:
        if isinstance(node, str):
            out.append(node.translate(PSEUDO_MAP))
        elif node == ("#",):
            out.append("#")
        else:
            name, kind, options = node
            if kind == "text":
                out.append(f"{{{name}}}")
            elif kind == "number":
                out.append(f"{{{name}, number}}")
            else:
                body = " ".join(f"{k} {{{_pseudo_nodes(v)}}}" for k, v in options.items())
                out.append(f"{{{name}, {kind}, {body}}}")
    return "".join(out)


def pseudo_message(text: str) -> str:
    """Accented, bracketed and 40 % longer; placeholders untouched."""
    body = _pseudo_nodes(parse_message(text))
    padding = "~" * max(1, round(len(text) * 0.4) - 2)
    return f"[{body} {padding}]"


def pseudo_catalog(english: dict[str, Any]) -> dict[str, Any]:
    """The en-XA pseudo-locale, generated from English (never written by hand)."""
    meta = dict(english["meta"], tag=PSEUDO, name="English (pseudo)", author="generated")
    messages = {k: pseudo_message(v) for k, v in english["messages"].items()}
    return {"meta": meta, "messages": messages}


# -- the desktop's language: one catalog for the process (the applet is one window) ----------
_active: Catalog | None = None


def use(locale: str) -> Catalog:
    """Make `locale` (a shipped tag, or en-XA) the language of `t` and `number`."""
    global _active
    _active = Catalog(locale)
    return _active


def active() -> Catalog:
    """The catalog `t` reads (English until `use` picks another)."""
    global _active
    if _active is None:
        _active = Catalog(FALLBACK)
    return _active


def t(key: str, **args: Any) -> str:
    """The message `key` of the active language, formatted with `args`."""
    return active().t(key, **args)


def number(value: float) -> str:
    """`value` written the active language's way (decimal mark, grouping)."""
    return active().format_number(value)


def decimal_mark() -> str:
    """The active language's decimal mark (CLDR): "." in English, "," in German."""
    return str(babel_numbers.get_decimal_symbol(active().babel_locale))


def is_rtl() -> bool:
    """The active language is written right to left."""
    return active().meta.get("direction") == "rtl"
