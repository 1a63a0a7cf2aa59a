"""The table of link options in docs/teach.md, made from web/src/link-options.json.

    python scripts/teach_table.py          # print the table
    python scripts/teach_table.py --write  # put it into docs/teach.md between its markers

tests/test_teach.py fails when the page's table differs from what this makes.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OPTIONS = ROOT / "web" / "src" / "link-options.json"
LIMITS = ROOT / "web" / "src" / "limits.json"
ENGLISH = ROOT / "src" / "evapcool" / "locales" / "en.json"
TEACH = ROOT / "docs" / "teach.md"
BEGIN = "<!-- link-options table: made by scripts/teach_table.py, do not edit -->"
END = "<!-- end of the link-options table -->"


def _number(v: float) -> str:
    return f"{int(v)}" if float(v).is_integer() else f"{v:g}"


def allowed(option: dict, ranges: dict) -> str:
    """What an option takes, in words."""
    kind = option["kind"]
    if kind in ("whole", "number"):
        span = ranges[option["range"]] if "range" in option else option
        unit = f" {span['unit']}" if span.get("unit") else ""
        word = "whole number" if kind == "whole" else "number"
        return f"{word}, {_number(span['low'])} to {_number(span['high'])}{unit}"
    if kind == "one_of":
        return "one of " + ", ".join(f"`{v}`" for v in option["values"])
    if kind == "list":
        return "comma-separated list of " + ", ".join(f"`{v}`" for v in option["values"])
    if kind == "code":
        return "a replay code (`EC1....`)"
    if kind == "locale":
        return "a language tag (`en`, `de`, `ja`, ...)"
    raise ValueError(f"unknown kind {kind!r} of option {option['name']!r}")


def table() -> str:
    """The Markdown table: option, what it takes, what it does."""
    options = json.loads(OPTIONS.read_text("utf-8"))["options"]
    ranges = json.loads(LIMITS.read_text("utf-8"))["ranges"]
    words = json.loads(ENGLISH.read_text("utf-8"))["messages"]
    rows = ["| option | takes | what it does |", "|---|---|---|"]
    for option in options:
        rows.append(f"| `{option['name']}` | {allowed(option, ranges)} | {words[option['key']]} |")
    return "\n".join(rows)


def page_table(text: str) -> str:
    """The table as docs/teach.md has it now (between the markers)."""
    start = text.index(BEGIN) + len(BEGIN)
    return text[start : text.index(END)].strip()


def main(argv: list[str]) -> int:
    made = table()
    if argv[:1] != ["--write"]:
        print(made)
        return 0
    text = TEACH.read_text("utf-8")
    start = text.index(BEGIN) + len(BEGIN)
    TEACH.write_text(text[:start] + "\n\n" + made + "\n\n" + text[text.index(END) :], "utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
