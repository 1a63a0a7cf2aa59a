"""The command line every case-file script shares: write its fixture, or with --check say
whether the committed one is stale (the tests run the check)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

from evapcool.fileio import atomic_write_text


def fixture_main(
    doc: str | None,
    script: str,
    fixture: Path,
    text: Callable[[], str],
    argv: list[str] | None = None,
) -> int:
    """Write `fixture` from `text()` (atomically), or --check it: 1 and one line if stale.
    doc, script: the calling script's docstring (its first line the help) and file."""
    parser = argparse.ArgumentParser(description=(doc or "").split("\n", 1)[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if the fixture is stale")
    args = parser.parse_args(argv)
    fresh = text()
    if args.check:
        if not fixture.exists() or fixture.read_text(encoding="utf-8") != fresh:
            print(f"{fixture} is stale: run python scripts/{Path(script).name}", file=sys.stderr)
            return 1
        return 0
    atomic_write_text(fixture, fresh)
    print(f"wrote {fixture}")
    return 0
