"""The applet's words, read from the message catalog (evapcool.i18n).

English for now: the rest of the applet still draws English text, and one screen in two
languages would be worse than one in English. The catalog holds every translation already.
"""

from __future__ import annotations

from typing import Any

from evapcool.i18n import FALLBACK, Catalog

_CATALOG: Catalog | None = None


def t(key: str, **args: Any) -> str:
    """The applet's message `key` formatted with `args`."""
    global _CATALOG
    if _CATALOG is None:  # read once, when first needed
        _CATALOG = Catalog(FALLBACK)
    return _CATALOG.t(key, **args)
