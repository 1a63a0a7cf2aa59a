"""The scene's colour sets: today's dark one and a light, high-contrast one for projectors.

Every text and line is at a contrast of at least 7:1 (WCAG's AAA for text) against what is
behind it, in both themes (tests measure it from the pixels of a rendered window).
Projectors wash out dark greys, so the projector theme is light, with thicker lines and
larger letters and numbers. Nothing of the game in here.
"""

from __future__ import annotations

from dataclasses import dataclass

Color = tuple[int, int, int]
Shade = tuple[int, int, int, int]


@dataclass(frozen=True)
class Theme:
    """The colours, line widths and text sizes the scene draws with."""

    name: str
    background: Color  # the play area
    border: Color  # the frame around it (title, buttons, thermometer)
    text: Color  # on the border and on message bands
    shadow: Color
    cup: Color
    cup_width: float  # logical px
    atom: Color
    #: Drawn around each atom (None: the sphere's own dark edge is enough).
    atom_rim: Color | None
    glass: Color
    glass_edge: Color | None
    mercury: Color
    ticks: Color
    tc_line: Color
    #: A band behind messages over the play area (start hint, score, too few atoms).
    message_band: Shade
    #: Texts and numbers on the border grow by this much (a hall's back row reads them).
    text_scale: float
    slider_bar: Color
    slider_outline: Color


DARK = Theme(
    name="dark",
    background=(159, 159, 159),
    border=(79, 79, 79),
    text=(255, 255, 255),
    shadow=(30, 30, 30),
    cup=(0, 0, 0),
    cup_width=6.0,
    atom=(30, 215, 245),
    atom_rim=None,
    glass=(255, 255, 255),
    glass_edge=None,
    mercury=(220, 20, 20),
    ticks=(50, 50, 50),
    tc_line=(0, 0, 0),
    message_band=(10, 10, 30, 200),
    text_scale=1.0,
    slider_bar=(255, 255, 255),
    slider_outline=(0, 0, 0),
)

PROJECTOR = Theme(
    name="projector",
    background=(255, 255, 255),
    border=(232, 234, 240),
    text=(0, 0, 0),
    shadow=(255, 255, 255),
    cup=(0, 0, 0),
    cup_width=10.0,
    atom=(0, 90, 215),
    atom_rim=(0, 20, 70),
    glass=(255, 255, 255),
    glass_edge=(0, 0, 0),
    mercury=(190, 0, 0),
    ticks=(0, 0, 0),
    tc_line=(0, 0, 0),
    message_band=(255, 255, 255, 235),
    text_scale=1.25,
    slider_bar=(255, 255, 255),
    slider_outline=(0, 0, 0),
)

THEMES = {theme.name: theme for theme in (DARK, PROJECTOR)}


def theme_named(name: str) -> Theme:
    """The theme of this name; ValueError naming the allowed ones."""
    try:
        return THEMES[name]
    except KeyError:
        raise ValueError(f"theme must be one of {', '.join(THEMES)} (got {name!r})") from None


def luminance(rgb: tuple[int, ...]) -> float:
    """Relative luminance of an sRGB colour (WCAG 2.x)."""

    def channel(c: int) -> float:
        v = c / 255.0
        return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4

    r, g, b = (channel(c) for c in rgb[:3])
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def contrast(a: tuple[int, ...], b: tuple[int, ...]) -> float:
    """WCAG contrast ratio of two colours, 1 to 21."""
    la, lb = sorted((luminance(a), luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)
