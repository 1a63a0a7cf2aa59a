"""MkDocs hooks for the site (mkdocs.yml): the docs' test tags and the playable page.

- Fenced blocks tagged `not-run` (tests/test_docs.py runs every other block) are shown as
  ordinary code: the tag is for the test, not for readers.
- The browser edition's page, src/evapcool/web/evapcool.html, is copied to the site's root
  as evapcool.html, so docs/play.md can embed it and the site itself plays.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "src" / "evapcool" / "web" / "evapcool.html"
_NOT_RUN = re.compile(r"^(\s*```\w+)\s+not-run\s*$", re.M)


def on_page_markdown(markdown: str, **_: object) -> str:
    return _NOT_RUN.sub(r"\1", markdown)


def on_post_build(config: dict, **_: object) -> None:
    shutil.copyfile(PAGE, Path(config["site_dir"]) / "evapcool.html")
