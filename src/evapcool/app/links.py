"""Setups as links (issue 48): the page's address options, read and written on the desktop.

A teacher hands out one address, `...evapcool.html?atoms=100&escape=knife&trap=300&lock=trap`;
`evapcool open LINK` (or `--link LINK`) plays it here, `evapcool --print-link` writes the
address of the options given. The rules are the page's (web/src/app/params.ts) and so
are its words: one notice per bad option, naming it, what is allowed and what was typed;
the option is then ignored. The option list is the page's `web/src/link-options.json`
(a test keeps `LINK_OPTIONS` equal to it).
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from urllib.parse import parse_qsl, quote, urlsplit

from evapcool import i18n, limits
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN, SPEED_MAX, SPEED_MIN
from evapcool.game.settings import SOUNDS, THEMES
from evapcool.i18n import t
from evapcool.physics.simulation import TC_LAWS
from evapcool.physics.world import ESCAPE_RULES

#: The page the links open (the published browser edition, README).
PAGE_URL = "https://evapcool.github.io/evapcool/evapcool.html"
#: Controls a link can fix: shown, but not changeable.
LOCKABLE = ("atoms", "radius", "escape", "tc-law", "speed", "trap")
#: Panels and buttons a link can leave out.
HIDEABLE = (
    "pause",
    "restart",
    "step",
    "slower",
    "faster",
    "autopilot",
    "chart",
    "path",
    "help",
    "table",
    "settings",
    "fullscreen",
)
#: The address's options in the order the notices name them (the page's ADDRESS_OPTIONS).
LINK_OPTIONS = (
    "atoms",
    "radius",
    "seed",
    "speed",
    "tc-law",
    "escape",
    "replay",
    "lang",
    "trap",
    "lock",
    "hide",
    "theme",
    "sound",
)
#: A typed value or option name is shown up to this many characters (the page's SHOWN_CHARS).
SHOWN_CHARS = 24
_DECIMAL = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


@dataclass
class Setup:
    """What a link asks for: each option given and good, the rest None; notices for the bad."""

    atoms: int | None = None
    radius: float | None = None
    seed: int | None = None
    speed: float | None = None
    tc_law: str | None = None
    escape: str | None = None
    replay: str | None = None
    lang: str | None = None
    trap: float | None = None
    theme: str | None = None
    sound: str | None = None
    lock: tuple[str, ...] = ()
    hide: tuple[str, ...] = ()
    notices: list[str] = field(default_factory=list)


def typed(text: str) -> str:
    """What the person typed, quoted and shortened (the page's `typed`)."""
    if len(text) <= SHOWN_CHARS:
        return json.dumps(text, ensure_ascii=False)
    cut = json.dumps(text[: SHOWN_CHARS - 4] + "…", ensure_ascii=False)
    return t("page.typed_long", text=cut, n=len(text))


def _decimal(text: str) -> float | None:
    """A plain decimal number, or None (hex, words, empty, Infinity are not numbers here)."""
    s = text.strip()
    if not _DECIMAL.match(s):
        return None
    v = float(s)
    return v if v == v and abs(v) != float("inf") else None


def _refusal(option: str, allowed: str, raw: str) -> str:
    return t("page.address_refused", option=option, allowed=allowed, got=typed(raw))


def _whole(low: int, high: int) -> str:
    return t("page.allowed_whole", low=low, high=f"{high}")


def _one_of(names: tuple[str, ...] | list[str]) -> str:
    return t("page.allowed_one_of", list=", ".join(names))


def _query(link: str) -> str:
    """The query part of a link: a whole address, `?a=1&b=2`, or `a=1&b=2`."""
    text = link.strip()
    if "?" in text or "://" in text:
        return urlsplit(text).query
    return text


def parse_link(link: str, languages: list[str] | None = None) -> Setup:
    """The setup a link asks for; each bad option named in a notice and left out."""
    pairs = parse_qsl(_query(link), keep_blank_values=True)
    out = Setup()
    counts: dict[str, int] = {}
    for key, _ in pairs:
        counts[key] = counts.get(key, 0) + 1
    for key, n in counts.items():
        if key not in LINK_OPTIONS:
            known = ", ".join(LINK_OPTIONS)
            out.notices.append(t("page.address_unknown", got=typed(key), known=known))
        elif n > 1:
            out.notices.append(t("page.address_twice", option=key, n=n))
    values = {k: v for k, v in pairs if counts[k] == 1 and k in LINK_OPTIONS}
    _numbers(values, out)
    _names(values, out, languages)
    return out


def _numbers(values: dict[str, str], out: Setup) -> None:
    radius = limits.APPLET_RADIUS
    atoms = limits.APPLET_ATOMS
    if (r := values.get("radius")) is not None:
        v = _decimal(r)
        if v is not None and radius.low <= v <= radius.high:
            out.radius = v
        else:
            allowed = t("page.allowed_px", low=f"{radius.low:g}", high=f"{radius.high:g}")
            out.notices.append(_refusal("radius", allowed, r))
    if (n := values.get("atoms")) is not None:
        v = _decimal(n)
        if v is not None and v.is_integer() and atoms.low <= v <= atoms.high:
            out.atoms = int(v)
        else:
            out.notices.append(_refusal("atoms", _whole(int(atoms.low), int(atoms.high)), n))
    if (s := values.get("seed")) is not None:
        v = _decimal(s)
        if v is not None and v.is_integer() and 0 <= v <= limits.SEED.high:
            out.seed = int(v)
        else:
            out.notices.append(_refusal("seed", _whole(0, int(limits.SEED.high)), s))
    if (x := values.get("speed")) is not None:
        v = _decimal(x)
        if v is not None and SPEED_MIN <= v <= SPEED_MAX:
            out.speed = v
        else:
            allowed = t("page.allowed_number", low=f"{SPEED_MIN:g}", high=f"{SPEED_MAX:g}")
            out.notices.append(_refusal("speed", allowed, x))
    if (h := values.get("trap")) is not None:
        v = _decimal(h)
        if v is not None and HEIGHT_MIN <= v <= HEIGHT_MAX:
            out.trap = v
        else:
            allowed = t("page.allowed_px", low=f"{HEIGHT_MIN:g}", high=f"{HEIGHT_MAX:g}")
            out.notices.append(_refusal("trap", allowed, h))


def _names(values: dict[str, str], out: Setup, languages: list[str] | None) -> None:
    choices = {
        "tc-law": tuple(TC_LAWS),
        "escape": ESCAPE_RULES,
        "theme": THEMES,
        "sound": SOUNDS,
    }
    for option, names in choices.items():
        if (v := values.get(option)) is not None:
            if v in names:
                setattr(out, option.replace("-", "_"), v)
            else:
                out.notices.append(_refusal(option, _one_of(names), v))
    for option, names in (("lock", LOCKABLE), ("hide", HIDEABLE)):
        if (v := values.get(option)) is not None:
            items = tuple(dict.fromkeys(p.strip() for p in v.split(",") if p.strip()))
            if all(item in names for item in items):
                setattr(out, option, items)
            else:
                allowed = t("page.allowed_list", list=", ".join(names))
                out.notices.append(_refusal(option, allowed, v))
    if (lang := values.get("lang")) is not None:
        tags = languages if languages is not None else [*i18n.shipped_locales(), i18n.PSEUDO]
        if i18n.best_match([lang], tags) is not None:
            out.lang = lang
        else:
            out.notices.append(_refusal("lang", _one_of(tags), lang))
    out.replay = values.get("replay")


def make_link(setup: Setup, base: str = PAGE_URL) -> str:
    """The address of a setup: its options in the page's order, the ones not given left out."""
    parts: list[tuple[str, str]] = []
    numbers = {
        "atoms": setup.atoms,
        "radius": setup.radius,
        "seed": setup.seed,
        "speed": setup.speed,
    }
    for name, value in numbers.items():
        if value is not None:
            parts.append((name, f"{value:g}" if isinstance(value, float) else str(value)))
    for name, value in (
        ("tc-law", setup.tc_law),
        ("escape", setup.escape),
        ("replay", setup.replay),
        ("lang", setup.lang),
        ("trap", None if setup.trap is None else f"{setup.trap:g}"),
        ("lock", ",".join(setup.lock) or None),
        ("hide", ",".join(setup.hide) or None),
        ("theme", setup.theme),
        ("sound", setup.sound),
    ):
        if value is not None:
            parts.append((name, value))
    query = "&".join(f"{k}={quote(v, safe=',-._')}" for k, v in parts)
    return f"{base}?{query}" if query else base
