"""Which translations are older than their English, and recording a translator's review.

Each catalog but English keeps, beside its messages, a `sources` section: for every message
a short hash of the English it was translated from. When an English message changes, its
translations become stale until someone translates them again (tests/test_i18n_stale.py).

    python scripts/i18n_review.py check            # every locale's stale messages (exit 1 if any)
    python scripts/i18n_review.py check de fr      # only these locales
    python scripts/i18n_review.py record de        # a translator reviewed all of de.json
    python scripts/i18n_review.py record de --keys replay.copied help.lower
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from evapcool.fileio import atomic_write_text
from evapcool.i18n import FALLBACK, SOURCES, source_hash, stale_keys

LOCALES = Path(__file__).resolve().parents[1] / "src" / "evapcool" / "locales"


def read(folder: Path, tag: str) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((folder / f"{tag}.json").read_text("utf-8"))
    return data


def translated_tags(folder: Path) -> list[str]:
    """Every catalog's tag but English's (English is its own source)."""
    return sorted(p.stem for p in folder.glob("*.json") if p.stem != FALLBACK)


def record(folder: Path, tag: str, keys: list[str] | None) -> int:
    """Mark `keys` (all by default) of `tag` as translated from today's English."""
    english = read(folder, FALLBACK)["messages"]
    catalog = read(folder, tag)
    unknown = [k for k in keys or [] if k not in catalog["messages"]]
    if unknown:
        print(
            f"--keys must name messages of {tag}.json (got {', '.join(unknown)})", file=sys.stderr
        )
        return 2
    sources = dict(catalog.get(SOURCES, {}))
    for key in keys or catalog["messages"]:
        sources[key] = source_hash(english[key])
    # In the messages' order, so a review's diff reads alongside them.
    catalog[SOURCES] = {k: sources[k] for k in catalog["messages"] if k in sources}
    atomic_write_text(
        folder / f"{tag}.json", json.dumps(catalog, ensure_ascii=False, indent=2) + "\n"
    )
    count = len(keys or catalog["messages"])
    print(f"{tag}: {count} messages recorded as translated from today's English")
    return 0


def check(folder: Path, tags: list[str]) -> int:
    """Print each stale translation with the English it should now say; 1 if any."""
    english = read(folder, FALLBACK)["messages"]
    found = 0
    for tag in tags:
        for key in stale_keys(read(folder, tag), english):
            print(f"{tag} {key}: translate again from: {english[key]}")
            found += 1
    noun = "translation" if found == 1 else "translations"
    print(f"{found} stale {noun} in {len(tags)} catalogs")
    return 1 if found else 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--folder", type=Path, default=LOCALES, help="the catalogs' folder")
    sub = parser.add_subparsers(dest="command", required=True)
    check_cmd = sub.add_parser("check", help="list translations older than their English")
    check_cmd.add_argument("tags", nargs="*", help="locales to check (default: all)")
    record_cmd = sub.add_parser("record", help="record a review: translated from today's English")
    record_cmd.add_argument("tag")
    record_cmd.add_argument("--keys", nargs="+", help="only these messages (default: all)")
    args = parser.parse_args(argv)
    shipped = translated_tags(args.folder)
    wanted = args.tags if args.command == "check" else [args.tag]
    bad = [t for t in wanted if t not in shipped]
    if bad:
        print(f"locale must be one of {', '.join(shipped)} (got {', '.join(bad)})", file=sys.stderr)
        return 2
    if args.command == "check":
        return check(args.folder, args.tags or shipped)
    return record(args.folder, args.tag, args.keys)


if __name__ == "__main__":
    sys.exit(main())
