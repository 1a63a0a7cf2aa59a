"""The room around the cup (issue 26.3): where escaped atoms are removed, and how high the
loader may fill the cup. The model knows the cup and this room, never the window: which
window shows them, and where, is the view's business (view/screen.py)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from evapcool import limits


@dataclass(frozen=True)
class Room:
    """Distances (px) from the cup wall's lowest point to the room's edges.

    An escaped atom that leaves the room through its left, right or bottom edge is gone
    (SPEC 1: the window's edges); a trapped one never is, wherever it flies. The loader
    fills the cup row by row below the room's top.
    """

    left: float
    right: float
    below: float
    above: float

    def top(self, origin_lift: float) -> float:
        """The room's top in trap coordinates, whose origin lies origin_lift (the first
        atom's radius) above the wall's lowest point."""
        return self.above - origin_lift

    def escape_box(self, origin_lift: float) -> tuple[float, float, float]:
        """(x_left, x_right, y_bottom): the edges where escaped atoms are gone, trap
        coordinates. y_bottom is the top less the room's height, as the window gave it."""
        return -self.left, self.right, self.top(origin_lift) - (self.above + self.below)


#: The original applet's room (SPEC 1): its cup's lowest point drawn at (296, 544) in the
#: 640 x 672 window, so 296 px from its left edge, 344 from its right, 128 above its
#: bottom and 544 below its top.
CLASSIC_ROOM = Room(left=296.0, right=344.0, below=128.0, above=544.0)


def check_room(value: object) -> Room:
    """value if it is a Room of finite sides >= 0 whose width and height are within
    limits.WINDOW_SIDE (as the window was); ParameterError naming `room` otherwise."""
    side = limits.WINDOW_SIDE
    allowed = f"a Room of sides >= 0 px, {side.span()} wide and high"
    if not isinstance(value, Room):
        raise limits.bad_value("room", allowed, value)
    sides = (value.left, value.right, value.below, value.above)
    if not all(
        isinstance(s, (int, float)) and not isinstance(s, bool) and math.isfinite(s) and s >= 0
        for s in sides
    ) or not (
        side.low <= value.left + value.right <= side.high
        and side.low <= value.below + value.above <= side.high
    ):
        raise limits.bad_value("room", allowed, value)
    return value
