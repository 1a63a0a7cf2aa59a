"""`evapcool open LINK`: play a setup's link on the desktop (the page's address, issue 48)."""

from __future__ import annotations

import sys

from evapcool.about import error_line

USAGE = "usage: evapcool open LINK [applet options]"


def main(argv: list[str] | None = None) -> int:
    """`evapcool --link LINK` under another name: the link first, then any applet option."""
    args = sys.argv[1:] if argv is None else list(argv)
    if args[:1] in (["-h"], ["--help"]):
        print(USAGE)
        print(
            "  LINK: the page's address with its options, e.g. 'evapcool.html?atoms=100&trap=300'"
        )
        return 0
    if not args or args[0].startswith("-"):
        print(
            error_line("open", "needs a LINK: the page's address with its options"), file=sys.stderr
        )
        return 2
    from evapcool.app.cli import main as app_main

    return app_main(["--link", args[0], *args[1:]])
