"""Write evapsans-bold.woff2: Liberation Sans Bold (SIL OFL 1.1) cut to the characters the
page draws (Latin, Latin-1, a little punctuation), renamed EvapSans as the OFL asks of a
modified font. Run once when the character set changes:

    python web/fonts/subset_font.py /usr/share/fonts/truetype/liberation2/LiberationSans-Bold.ttf

(needs `pip install fonttools brotli`; Debian's fonts-liberation2 has the source font).
Player names in other scripts are drawn with the browser's own fonts.
"""

from __future__ import annotations

import sys
from pathlib import Path

from fontTools import subset
from fontTools.ttLib import TTFont

HERE = Path(__file__).resolve().parent
UNICODES = [*range(0x20, 0x7F), *range(0xA0, 0x180), 0x2013, 0x2014, 0x2018, 0x2019]
UNICODES += [0x201C, 0x201D, 0x2022, 0x2026, 0x2190, 0x2192, 0x2212, 0x00D7]
FAMILY = "EvapSans"
SOURCE = "/usr/share/fonts/truetype/liberation2/LiberationSans-Bold.ttf"


def main(source: str) -> None:
    options = subset.Options()
    options.flavor = "woff2"
    options.layout_features = ["kern", "liga"]
    options.name_IDs = [0, 1, 2, 3, 4, 5, 6, 13, 14]
    options.notdef_outline = True
    font = TTFont(source)
    subsetter = subset.Subsetter(options)
    subsetter.populate(unicodes=UNICODES)
    subsetter.subset(font)
    names = font["name"]
    for record in names.names:
        if record.nameID in (1, 4, 16):
            record.string = FAMILY if record.nameID != 4 else f"{FAMILY} Bold"
        elif record.nameID == 3:
            record.string = f"{FAMILY}-Bold-subset"
        elif record.nameID == 6:
            record.string = f"{FAMILY}-Bold"
    font.flavor = "woff2"
    # No timestamps: the same source font gives the same bytes.
    font["head"].modified = font["head"].created
    out = HERE / "evapsans-bold.woff2"
    font.save(out, reorderTables=True)
    print(f"wrote {out} ({out.stat().st_size} bytes)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else SOURCE)
