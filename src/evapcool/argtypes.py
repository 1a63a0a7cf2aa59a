"""Command-line value types shared by the `evapcool` commands: one clear line on error.

Ranges come from `evapcool.limits`, so the help text, the check and the Python API agree.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, NoReturn

from evapcool.about import error_line
from evapcool.fileio import check_writable
from evapcool.limits import ParameterError, Range


class UsageError(Exception):
    """Bad command-line input from Parser: the command prints it as one line, exit 2."""


class Parser(argparse.ArgumentParser):
    """argparse that raises UsageError on bad input, for commands that word the line."""

    def error(self, message: str) -> NoReturn:
        raise UsageError(message)


class OneLineParser(argparse.ArgumentParser):
    """argparse whose bad input is one line (about.error_line) and exit status 2,
    never the usage dump; command: 'lab', 'web'... or None for the applet."""

    def __init__(self, command: str | None, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.command = command

    def error(self, message: str) -> NoReturn:
        print(error_line(self.command, message), file=sys.stderr)
        raise SystemExit(2)


def ranged(rng: Range) -> Callable[[str], float]:
    """A number (a whole number if rng.integer) within rng."""

    def parse(text: str) -> float:
        try:
            value: float = int(text) if rng.integer else float(text)
        except (ValueError, OverflowError):
            value = math.nan
        if not rng.contains(value):
            raise argparse.ArgumentTypeError(f"must be {rng.allowed()} (got {text!r})")
        return value

    parse.range = rng  # type: ignore[attr-defined]  # for tests that fuzz the options
    return parse


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


def folder(text: str) -> Path:
    """A folder path (it need not exist yet: the program makes it, or says why it cannot)."""
    if not text or "\x00" in text:
        raise argparse.ArgumentTypeError(f"must name a folder (got {text!r})")
    return Path(text)


def output_file(suffixes: Sequence[str]) -> Callable[[str], Path]:
    """A file the program can write, ending in one of suffixes, checked before any run.

    The folder must exist and take a new file (tried with a probe that is removed at
    once); the name must fit the file system; a directory or device there is refused.
    """

    def parse(text: str) -> Path:
        path = Path(text)
        if path.suffix.lower() not in suffixes:
            raise argparse.ArgumentTypeError(
                f"must be a file name ending in {' or '.join(suffixes)} (got {text!r})"
            )
        try:
            check_writable(path, "path")
        except ParameterError as exc:
            raise argparse.ArgumentTypeError(exc.detail) from None
        return path

    parse.suffixes = tuple(suffixes)  # type: ignore[attr-defined]
    return parse
