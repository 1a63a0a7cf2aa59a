"""Write web/src/limits.json: every range and bound of src/evapcool/limits.py for the web edition.

    python scripts/web_limits.py          # (re)write the table after editing limits.py
    python scripts/web_limits.py --check  # exit 1 if the committed table is stale

The browser edition reads its limits from that file only (web/src/limits.ts), so both
editions refuse the same values with the same words (issue 25.1); tests/web/test_web_limits.py
fails when the committed table no longer matches limits.py.
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

TABLE = Path(__file__).resolve().parents[1] / "web" / "src" / "limits.json"


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


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if the table is stale")
    args = parser.parse_args(argv)
    text = table_text()
    if args.check:
        current = TABLE.read_text(encoding="utf-8") if TABLE.exists() else ""
        if current != text:
            print(f"{TABLE} is stale: run python scripts/web_limits.py", file=sys.stderr)
            return 1
        return 0
    atomic_write_text(TABLE, text)
    print(f"wrote {TABLE}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
