"""`evapcool open LINK`: play a setup's link on the desktop (the page's address, issue 48)."""

from __future__ import annotations

import argparse
import sys

from evapcool.about import APP_NAME
from evapcool.argtypes import OneLineParser

PROG = f"{APP_NAME} open"


def build_parser() -> argparse.ArgumentParser:
    p = OneLineParser(
        "open",
        prog=PROG,
        description="Play a setup's link on the desktop: the page's address with its options "
        "(atoms, radius, seed, speed, tc-law, escape, replay, lang, trap, lock, hide, theme, "
        "sound), as `evapcool --print-link` writes it. The same as `evapcool --link LINK`.",
    )
    p.add_argument("link", metavar="LINK", help="the address, or just its options: 'a=1&b=2'")
    p.add_argument(
        "options",
        nargs=argparse.REMAINDER,
        metavar="...",
        help="any option of the applet (evapcool --help); given here, it beats the link's",
    )
    return p


def main(argv: list[str] | None = None) -> int:
    """`evapcool --link LINK [options]` under another name."""
    args = build_parser().parse_args(sys.argv[1:] if argv is None else argv)
    from evapcool.app.cli import main as app_main

    return app_main(["--link", args.link, *args.options])
