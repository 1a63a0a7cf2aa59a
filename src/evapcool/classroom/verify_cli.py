"""`evapcool verify CODE|FILE...`: rank replay codes by verified score (issue 22)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from evapcool.about import error_line
from evapcool.argtypes import OneLineParser
from evapcool.game.replay import DAMAGED, Recording, ReplayError, decode, verify

EXIT_REJECTED = 1
EXIT_USAGE = 2
MAX_INPUT_BYTES = 16 * 1024 * 1024
#: The lines printed: a verified entry and a rejected one.
VERIFIED_LINE = "{rank:>3}. {score:>3} atoms  frames {frames:>5}  seed {seed}  {source}"
REJECTED_LINE = "  -  rejected ({reason}): {detail}  {source}"
USAGE_NO_INPUT = "give at least one replay code or file"
#: An argument that is neither a code nor a readable file of them.
NOT_CODES = "argument CODE|FILE: {arg} is {what}, not a replay code or a file of them"


def _entries(arg: str) -> list[tuple[str, str | dict[str, object]]]:
    """(source, code or JSON recording) of one argument: a code, or a file of them."""
    if not arg.strip():
        raise ValueError(NOT_CODES.format(arg=repr(arg), what="empty"))
    path = Path(arg)
    if arg.startswith("EC") or len(arg) > 4096:
        return [(arg if len(arg) <= 24 else arg[:21] + "...", arg)]
    if path.is_file():
        if path.stat().st_size > MAX_INPUT_BYTES:
            raise ValueError(f"{arg}: larger than {MAX_INPUT_BYTES} bytes")
        text = path.read_text(encoding="utf-8", errors="replace")
        try:
            doc = json.loads(text)
        except ValueError:
            lines = enumerate(text.splitlines(), 1)
            return [(f"{arg}:{i}", ln.strip()) for i, ln in lines if ln.strip()]
        docs = doc if isinstance(doc, list) else [doc]
        return [(f"{arg}#{i + 1}", d) for i, d in enumerate(docs)]
    if path.exists():
        raise ValueError(NOT_CODES.format(arg=repr(arg), what="a folder or device"))
    return [(arg if len(arg) <= 24 else arg[:21] + "...", arg)]


def _check(item: str | dict[str, object] | object) -> Recording:
    if isinstance(item, str):
        return decode(item)
    if isinstance(item, dict):
        return Recording.from_json(item)
    raise ReplayError(DAMAGED, "neither a code nor a recording")


def main(argv: list[str] | None = None) -> int:
    parser = OneLineParser(
        "verify",
        prog="evapcool verify",
        description="Verify replay codes by replaying them; rank them by verified score.",
    )
    parser.add_argument("inputs", nargs="*", metavar="CODE|FILE")
    args = parser.parse_args(argv)
    if not args.inputs:
        print(error_line("verify", USAGE_NO_INPUT), file=sys.stderr)
        return EXIT_USAGE
    items: list[tuple[str, str | dict[str, object]]] = []
    for arg in args.inputs:
        try:
            items.extend(_entries(arg))
        except (OSError, ValueError) as exc:
            print(error_line("verify", str(exc)), file=sys.stderr)
            return EXIT_USAGE
    good: list[tuple[int, int, int, str]] = []
    bad: list[str] = []
    for source, item in items:
        try:
            rec = _check(item)
            got = verify(rec)
            good.append((got.score, -got.frames, rec.seed, source))
        except ReplayError as exc:
            bad.append(REJECTED_LINE.format(reason=exc.reason, detail=exc.detail, source=source))
    good.sort(key=lambda g: (-g[0], -g[1]))
    for rank, (score, neg_frames, seed, source) in enumerate(good, 1):
        print(
            VERIFIED_LINE.format(
                rank=rank, score=score, frames=-neg_frames, seed=seed, source=source
            )
        )
    for line in bad:
        print(line)
    return EXIT_REJECTED if bad else 0
