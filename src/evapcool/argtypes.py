"""Command-line value types shared by `evapcool` and `evapcool lab`: one clear line on error."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable, Sequence


def whole(low: int) -> Callable[[str], int]:
    """A whole number >= low."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            value = low - 1
        if value < low:
            raise argparse.ArgumentTypeError(f"must be a whole number >= {low} (got {text!r})")
        return value

    return parse


def positive(text: str) -> float:
    """A positive finite number."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0.0):
        raise argparse.ArgumentTypeError(f"must be a positive finite number (got {text!r})")
    return value


def choice(options: Sequence[str]) -> Callable[[str], str]:
    """One of options, named in the error."""

    def parse(text: str) -> str:
        if text not in options:
            raise argparse.ArgumentTypeError(f"must be one of {', '.join(options)} (got {text!r})")
        return text

    return parse
