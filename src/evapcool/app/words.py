"""The applet's words, read from the message catalog of the chosen language (evapcool.i18n).

The language is chosen once at start (`--lang`, the saved setting, the system locale) and
again when the settings screen saves another; every layer reads it through `evapcool.i18n`.
"""

from __future__ import annotations

from evapcool.i18n import choose_locale, number, t, use

__all__ = ["choose", "number", "t"]


def choose(cli: str | None = None, saved: str | None = None) -> str:
    """Pick and use the language: --lang, then the saved setting ("auto": none), then the system."""
    tag = choose_locale(cli, None if saved in (None, "auto") else saved)
    use(tag)
    return tag
