"""`evapcool web`: the browser edition, one self-contained page shipped with the package.

The page (built from `web/` by `npm run build`, copied here, checked by CI to equal a
fresh build) runs the whole applet from disk or any web server, with no install and no
network: a lecturer can send the file on or put it on a course page.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import webbrowser
from importlib import resources
from pathlib import Path

from evapcool.about import APP_NAME, error_line
from evapcool.argtypes import OneLineParser

PROG = f"{APP_NAME} web"
PAGE_NAME = "evapcool.html"


def page_path() -> Path:
    """Where the bundled page is on disk."""
    return Path(str(resources.files(__name__).joinpath(PAGE_NAME)))


def build_parser() -> argparse.ArgumentParser:
    p = OneLineParser(
        "web",
        prog=PROG,
        description="Open the browser edition (one self-contained HTML file) in the default "
        "browser, or show where it is to send it on.",
    )
    p.add_argument("--print-path", action="store_true", help="print the page's path and exit")
    p.add_argument(
        "--copy",
        type=str,
        default=None,
        metavar="DEST",
        help="copy the page to DEST (file, folder)",
    )
    return p


def _copy_destination(given: str) -> Path:
    """The file --copy writes: DEST itself, or the page's name inside DEST if DEST is a
    folder or is written as one (a trailing slash: a folder, even one that does not exist)."""
    folder = given.endswith(("/", os.sep)) or Path(given).is_dir()
    return Path(given) / PAGE_NAME if folder else Path(given)


def main(argv: list[str] | None = None) -> int:
    """Open, print or copy the page; returns the exit status."""
    args = build_parser().parse_args(argv)
    page = page_path()
    if not page.is_file():
        print(error_line("web", f"the page is missing from this install ({page})"), file=sys.stderr)
        return 1
    if args.print_path:
        print(page)
        return 0
    if args.copy is not None:
        dest = _copy_destination(args.copy)
        if not dest.parent.is_dir():
            print(
                error_line("web", f"--copy: folder {str(dest.parent)!r} does not exist"),
                file=sys.stderr,
            )
            return 2
        try:
            shutil.copyfile(page, dest)
        except OSError as exc:
            print(
                error_line("web", f"cannot write {str(dest)!r}: {exc.strerror or exc}"),
                file=sys.stderr,
            )
            return 1
        print(dest)
        return 0
    if not webbrowser.open(page.as_uri()):
        print(
            error_line("web", f"no browser could be started; open this file: {page}"),
            file=sys.stderr,
        )
        return 1
    print(f"Opened {page}")
    return 0
