"""Text for every view module: pygame's bundled font, then system fonts for what it lacks.

The bundled font (the original applet's look) covers Latin only. Each character it lacks is
drawn with the first installed font of `FALLBACK_FAMILIES` that has it, so a name typed in
Chinese, Korean, Arabic or with emoji shows as typed, not as empty boxes. FreeType tells
which font has a glyph (`pygame.freetype` reports a missing one); SDL_ttf draws, with
HarfBuzz shaping, so Arabic letters join and read right to left. Nothing is shipped: the
chain is whatever of these families the system has (`fc-list` on Linux).
"""

from __future__ import annotations

import unicodedata
from dataclasses import dataclass, field
from functools import lru_cache

import pygame
import pygame.freetype

from evapcool import i18n

Color = tuple[int, int, int]

#: System font families tried in order for characters the bundled font lacks (names as
#: pygame.font.match_font spells them: lower case, no spaces). Linux, Windows and macOS names.
FALLBACK_FAMILIES = (
    # Wide Latin, Greek, Cyrillic, Arabic, Hebrew, symbols (and monochrome emoji)
    "dejavusans",
    "notosans",
    "segoeui",
    "arial",
    "liberationsans",
    "helvetica",
    "notosansarabic",
    "notonaskharabic",
    "geezapro",
    "tahoma",
    # Chinese, Japanese, Korean
    "notosanscjkjp",
    "notosanscjksc",
    "notosanscjkkr",
    "sourcehansans",
    "droidsansfallback",
    "wenquanyimicrohei",
    "microsoftyahei",
    "yugothic",
    "malgungothic",
    "pingfangsc",
    "hiraginosans",
    "applesdgothicneo",
    # Emoji and symbols
    "notocoloremoji",
    "notoemoji",
    "segoeuiemoji",
    "applecoloremoji",
    "symbola",
    "segoeuisymbol",
    # More scripts
    "notosansdevanagari",
    "notosanshebrew",
    "notosansthai",
    "nirmalaui",
    "arialunicodems",
)
#: Right-to-left scripts HarfBuzz shapes (ISO 15924 tags) by a character's Unicode name.
_RTL_SCRIPTS = {"ARABIC": "Arab", "HEBREW": "Hebr", "SYRIAC": "Syrc", "THAANA": "Thaa"}


@dataclass
class _Face:
    """One font file: its glyph coverage (FreeType) and SDL_ttf fonts by size and style."""

    path: str | None  # None: pygame's bundled font
    _covered: dict[str, bool] = field(default_factory=dict)
    _ft: pygame.freetype.Font | None = None

    def has(self, ch: str) -> bool:
        known = self._covered.get(ch)
        if known is None:
            if self._ft is None:
                if not pygame.freetype.get_init():
                    pygame.freetype.init()
                self._ft = pygame.freetype.Font(self.path, 16)
            try:
                known = self._ft.get_metrics(ch)[0] is not None
            except (pygame.error, ValueError, TypeError):
                known = False
            self._covered[ch] = known
        return known

    def forget_fonts(self) -> None:
        self._ft = None


_faces: list[_Face] | None = None
_fonts: dict[tuple[str | None, int, bool, str | None], pygame.font.Font] = {}


def _on_quit() -> None:
    # Fonts die with pygame's font modules: drop them (coverage, plain data, stays).
    _fonts.clear()
    _plain.cache_clear()
    _shaped.cache_clear()
    for face in _faces or ():
        face.forget_fonts()


def faces() -> list[_Face]:
    """The chain: the bundled font, then each installed fallback family once."""
    global _faces
    if _faces is None:
        chain, seen = [_Face(None)], set()
        for family in FALLBACK_FAMILIES:
            try:
                path = pygame.font.match_font(family)
            except Exception:  # a broken font cache must not stop the applet
                path = None
            if path and path not in seen:
                seen.add(path)
                chain.append(_Face(path))
        _faces = chain
    return _faces


def fallback_paths() -> list[str]:
    """Files of the installed fallback fonts, in the order they are tried."""
    return [f.path for f in faces() if f.path is not None]


def _sdl_font(path: str | None, size: int, bold: bool, script: str | None) -> pygame.font.Font:
    if not pygame.font.get_init():
        pygame.font.init()
    key = (path, size, bold, script)
    f = _fonts.get(key)
    if f is None:
        if not _fonts:
            pygame.register_quit(_on_quit)  # once per filling: pygame runs it once
        if path is None:
            f = pygame.font.Font(None, size)
        else:
            f = pygame.font.Font(path, _matched_size(path, size))
        f.set_bold(bold)
        if script is not None:
            f.set_script(script)
            f.set_direction(pygame.DIRECTION_RTL)
        _fonts[key] = f
    return f


def _cap_height(f: pygame.font.Font) -> int:
    """Height of a capital H above the baseline (0 if the font has no H)."""
    metrics = f.metrics("H")
    return metrics[0][3] if metrics and metrics[0] else 0


@lru_cache(maxsize=256)
def _matched_size(path: str, size: int) -> int:
    """The size at which this font's capitals are as tall as the bundled font's at `size`
    (its ascent, for a font without Latin letters): letters of every script then sit
    at one visual size, as a designer pairs fonts, rather than shrunk by tall ascents."""
    primary, probe = pygame.font.Font(None, size), pygame.font.Font(path, size)
    want, have = _cap_height(primary), _cap_height(probe)
    if not (want and have):
        want, have = primary.get_ascent(), probe.get_ascent()
    return max(1, round(size * want / max(1, have)))


def font(size: int, bold: bool = False) -> pygame.font.Font:
    """pygame's bundled font (the original's look) at this pixel size."""
    return _sdl_font(None, int(size), bold, None)


def _script(ch: str) -> str | None:
    if unicodedata.bidirectional(ch) not in ("R", "AL"):
        return None
    word = unicodedata.name(ch, "").split(" ")[0]
    return _RTL_SCRIPTS.get(word, "Arab")


def _joins_previous(ch: str) -> bool:
    """Marks, joiners, variation selectors and modifiers stay with the letter before them."""
    return unicodedata.category(ch) in ("Mn", "Me", "Cf", "Sk")


def runs(text: str) -> list[tuple[int, str | None, str]]:
    """(face index, RTL script or None, text) runs in logical order, one font each.

    Spaces make runs of their own, so they stay between words when right-to-left
    runs are turned round.
    """
    chain = faces()
    out: list[tuple[int, str | None, str]] = []
    for ch in text:
        if out and _joins_previous(ch) and not out[-1][2][-1].isspace():
            k, script, s = out[-1]
            out[-1] = (k, script, s + ch)
            continue
        script = _script(ch)
        # Right-to-left letters never from the bundled font: it has some Arabic letters
        # but not all, and a word split between two fonts cannot join.
        first = 1 if script is not None and len(chain) > 1 else 0
        k = next((i for i, face in enumerate(chain) if i >= first and face.has(ch)), 0)
        prev = out[-1] if out else None
        if prev and prev[0] == k and prev[1] == script and prev[2][-1].isspace() == ch.isspace():
            out[-1] = (k, script, prev[2] + ch)
        else:
            out.append((k, script, ch))
    return out


def _kind(ch: str) -> str:
    """A character's bidirectional class, folded: "R" (Hebrew, Arabic letters), "L", "EN"
    (a digit, European or Arabic-Indic), "ES" / "ET" / "CS" (the signs and separators
    numbers carry: + - % . ,), or "N" for the other neutrals (spaces, brackets...)."""
    kind = unicodedata.bidirectional(ch)
    if kind in ("R", "AL"):
        return "R"
    if kind in ("EN", "AN"):
        return "EN"
    if kind in ("L", "ES", "ET", "CS"):
        return kind
    return "N"


def _strong(ch: str) -> str | None:
    """A letter's direction, "R" or "L"; None for digits and neutrals."""
    kind = _kind(ch)
    return kind if kind in ("R", "L") else None


def _rtl_paragraph(text: str) -> bool:
    """The line's base direction: right to left for a line with right-to-left letters in a
    right-to-left language; otherwise Unicode's rule, the first letter decides (a digit does
    not: "سارة 7" is a right-to-left line in every language)."""
    if i18n.is_rtl() and any(_strong(ch) == "R" for ch in text):
        return True
    return next((d == "R" for d in map(_strong, text) if d is not None), False)


def _resolve(text: str, rtl: bool) -> list[str]:
    """Each character's resolved direction, "R", "L" or "EN" (a number, laid out left to
    right inside a line of either direction), by UAX #9's weak and neutral rules."""
    kinds = [_kind(ch) for ch in text]
    n = len(kinds)
    for i in range(1, n - 1):  # W4: one separator between two digits is part of the number
        if kinds[i] in ("ES", "CS") and kinds[i - 1] == "EN" == kinds[i + 1]:
            kinds[i] = "EN"
    for i in range(n):  # W5: signs touching a number (4%, +5) are part of it
        if kinds[i] == "ET":
            j = i
            while j < n and kinds[j] == "ET":
                j += 1
            if (i > 0 and kinds[i - 1] == "EN") or (j < n and kinds[j] == "EN"):
                kinds[i:j] = ["EN"] * (j - i)
    for i in range(n):  # a dash or plus glued to a word ("--autopilot") leads that word
        if kinds[i] == "ES":
            j = i
            while j < n and kinds[j] == "ES":
                j += 1
            if j < n and kinds[j] == "L":
                kinds[i:j] = ["L"] * (j - i)
    last = "R" if rtl else "L"
    for i, k in enumerate(kinds):  # W7: a number after Latin letters reads as they do
        if k == "EN" and last == "L":
            kinds[i] = "L"
        elif k in ("R", "L"):
            last = k
    base = "R" if rtl else "L"
    # N1: neutrals take the direction of the strong text on both sides when it agrees
    # (numbers count as right to left here), else the line's (N2).
    side = ["R" if k == "EN" else k for k in kinds]
    before, after = [base] * n, [base] * n
    last = base
    for i in range(n):
        before[i] = last
        if side[i] in ("R", "L"):
            last = side[i]
    last = base
    for i in range(n - 1, -1, -1):
        after[i] = last
        if side[i] in ("R", "L"):
            last = side[i]
    return [
        k if k in ("R", "L", "EN") else (before[i] if before[i] == after[i] else base)
        for i, k in enumerate(kinds)
    ]


def bidi_runs(text: str, rtl: bool) -> list[tuple[bool, str]]:
    """(right to left?, text) runs in visual order, left to right on the screen.

    The bidirectional algorithm without explicit embeddings (UAX #9): each character's
    level from its resolved direction (a number one above the text around it, so its digits
    stay in order), then every run at or above each odd level turned round, highest first.
    A right-to-left run keeps its logical order here: HarfBuzz draws it right to left and
    mirrors brackets.
    """
    if not text:
        return []
    base = 1 if rtl else 0
    levels = []
    for d in _resolve(text, rtl):
        if d == "R":
            levels.append(base | 1)
        elif d == "L":
            levels.append(base + (base & 1))
        else:  # a number (after right-to-left text, or in such a line): even, above it
            levels.append(2)
    runs_: list[tuple[int, str]] = []
    for ch, level in zip(text, levels, strict=True):
        if runs_ and runs_[-1][0] == level:
            runs_[-1] = (level, runs_[-1][1] + ch)
        else:
            runs_.append((level, ch))
    lowest_odd = min((lv for lv, _ in runs_), default=0) | 1
    for level in range(max(lv for lv, _ in runs_), lowest_odd - 1, -1):
        k = 0
        while k < len(runs_):
            if runs_[k][0] < level:
                k += 1
                continue
            j = k
            while j < len(runs_) and runs_[j][0] >= level:
                j += 1
            runs_[k:j] = runs_[k:j][::-1]
            k = j
    merged: list[tuple[bool, str]] = []
    for level, s in runs_:
        odd = bool(level & 1)
        if merged and merged[-1][0] == odd and not odd:
            merged[-1] = (odd, merged[-1][1] + s)
        else:
            merged.append((odd, s))
    return merged


def text_image(text: str, size: int, color: Color, bold: bool = False) -> pygame.Surface:
    """The text rendered (antialiased, transparent background) at this pixel size."""
    if text.isascii():  # the common case: the bundled font alone, as the original
        return _plain(text, size, color, bold)
    # The line's direction depends on the language in use: part of the cache's key.
    return _shaped(text, size, color, bold, _rtl_paragraph(text))[0]


def baseline(text: str, size: int, bold: bool = False) -> int:
    """How far below the top of `text_image(text, size, ...)` its baseline is: lines of
    different fonts (a Latin key name beside a Japanese description) line up on it."""
    if text.isascii():
        return int(font(size, bold).get_ascent())
    return _shaped(text, size, (255, 255, 255), bold, _rtl_paragraph(text))[1]


@lru_cache(maxsize=4096)
def _plain(text: str, size: int, color: Color, bold: bool) -> pygame.Surface:
    return font(size, bold).render(text, True, color)


@lru_cache(maxsize=4096)
def _shaped(
    text: str, size: int, color: Color, bold: bool, rtl: bool
) -> tuple[pygame.Surface, int]:
    """Runs in visual order, each drawn by the font that has its letters; and the baseline."""
    chain = faces()
    parts = []
    for right_to_left, run in bidi_runs(text, rtl):
        pieces = runs(run)
        # A right-to-left run's spaces and brackets are drawn right to left too (mirrored).
        script = next((sc for _, sc, _ in pieces if sc is not None), "Arab")
        for k, own, s in pieces[::-1] if right_to_left else pieces:
            if not any(unicodedata.category(ch) not in ("Cf", "Mn") for ch in s):
                continue  # marks alone (a direction mark after a space) draw nothing
            f = _sdl_font(chain[k].path, size, bold, script if right_to_left else own)
            parts.append((f.render(s, True, color), f.get_ascent()))
    if not parts:
        return font(size, bold).render("", True, color), int(font(size, bold).get_ascent())
    ascent = max(a for _, a in parts)
    height = max(ascent - a + img.get_height() for img, a in parts)
    out = pygame.Surface((sum(img.get_width() for img, _ in parts), height), pygame.SRCALPHA)
    x = 0
    for img, a in parts:
        out.blit(img, (x, ascent - a))
        x += img.get_width()
    return out, ascent


def text_size(text: str, size: int, bold: bool = False) -> tuple[int, int]:
    """Width and height of `text_image(text, size, ...)`."""
    return text_image(text, size, (255, 255, 255), bold).get_size()


def missing(text: str) -> list[str]:
    """Characters of text that no font of the chain has (they would show as boxes)."""
    chain = faces()
    return [ch for ch in text if not ch.isspace() and not any(f.has(ch) for f in chain)]
