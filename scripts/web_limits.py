"""Write the table of limits generated from the Python edition for the browser edition.

    python scripts/web_limits.py          # (re)write it after editing limits.py
    python scripts/web_limits.py --check  # exit 1 if the committed table is stale

web/src/limits.json: every range and bound of src/evapcool/limits.py; the browser edition
reads its limits from that file only (web/src/limits.ts), so both editions refuse the same
values with the same words (issue 25.1). The model's fixed numbers and codes flow the other
way, down from the core's header (scripts/core_api.py, issue 47).
tests/web/test_web_limits.py fails when the committed table no longer matches its source.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path
from typing import Any

from evapcool import limits
from evapcool.fileio import atomic_write_text

ROOT = Path(__file__).resolve().parents[1]
TABLE = ROOT / "web" / "src" / "limits.json"


def _number(v: float) -> float | str:
    """JSON has no infinity: +inf is written as the string "inf"."""
    return "inf" if math.isinf(v) and v > 0 else v


def web_table() -> dict[str, Any]:
    """limits.py's Range entries and numeric bounds, by their Python names."""
    ranges: dict[str, Any] = {}
    bounds: dict[str, float | str] = {}
    for name, value in sorted(vars(limits).items()):
        if not name.isupper() or name.startswith("_"):
            continue
        if isinstance(value, limits.Range):
            ranges[name] = {
                "low": _number(value.low),
                "high": _number(value.high),
                "unit": value.unit,
                "integer": value.integer,
                "low_open": value.low_open,
                "inf_ok": value.inf_ok,
            }
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            bounds[name] = _number(value)
    return {
        "generated_by": "scripts/web_limits.py from src/evapcool/limits.py: do not edit",
        "ranges": ranges,
        "bounds": bounds,
    }


def table_text() -> str:
    return json.dumps(web_table(), indent=2) + "\n"


def _outputs() -> list[tuple[Path, str]]:
    return [(TABLE, table_text())]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if the table is stale")
    args = parser.parse_args(argv)
    stale = 0
    for path, text in _outputs():
        current = path.read_text(encoding="utf-8") if path.exists() else ""
        if args.check:
            if current != text:
                print(f"{path} is stale: run python scripts/web_limits.py", file=sys.stderr)
                stale = 1
        else:
            atomic_write_text(path, text)
            print(f"wrote {path}")
    return stale


if __name__ == "__main__":
    sys.exit(main())
