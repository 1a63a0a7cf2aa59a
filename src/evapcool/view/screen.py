"""Where the view puts the cup in the window: trap coordinates <-> pixels.

The original's layout (SPEC 1): a 640 x 672 window, a play area inside borders of 48 px
(left, top) and 96 px (right, bottom), the cup's lowest point drawn 32 px above the play
area's bottom and in its middle. The physics knows only the room this gives (physics/room.py).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from evapcool.physics.room import Room

if TYPE_CHECKING:
    from evapcool.physics.simulation import Simulation

#: The original window (SPEC 1), px.
WINDOW = (640, 672)
BORDER_LEFT, BORDER_RIGHT, BORDER_TOP, BORDER_BOTTOM = 48, 96, 48, 96
CUP_DROP = 32  # px between the drawn cup bottom and the play-area bottom


def cup_vertex(window: tuple[int, int]) -> tuple[float, float]:
    """Screen position of the drawn cup's lowest point: (296, 544) in 640 x 672."""
    w, h = window
    play_w = w - BORDER_LEFT - BORDER_RIGHT
    return BORDER_LEFT + play_w / 2.0, float(h - BORDER_BOTTOM - CUP_DROP)


def window_room(window: tuple[int, int] = WINDOW) -> Room:
    """The room a window of this size gives the physics: its edges around the cup."""
    vx, vy = cup_vertex(window)
    w, h = window
    return Room(left=vx, right=w - vx, below=h - vy, above=vy)


@dataclass(frozen=True)
class ScreenMap:
    """Trap coordinates (y up) to window pixels (y down) and back.

    vertex: the screen position of the cup wall's lowest point; origin_lift: the trap
    origin's height above it (the first atom's radius, `Simulation.origin_lift`).
    """

    vertex: tuple[float, float]
    origin_lift: float

    @classmethod
    def of(cls, sim: Simulation) -> ScreenMap:
        """The map that shows sim's room as a window of the room's size."""
        return cls((sim.room.left, sim.room.above), sim.origin_lift)

    @property
    def origin(self) -> tuple[float, float]:
        """Screen position of the trap origin."""
        vx, vy = self.vertex
        return vx, vy - self.origin_lift

    def to_screen(self, xy: np.ndarray) -> np.ndarray:
        """Trap coordinates to window pixels (y down)."""
        ox, oy = self.origin
        xy = np.asarray(xy, dtype=float)
        out = np.empty_like(xy)
        out[..., 0] = ox + xy[..., 0]
        out[..., 1] = oy - xy[..., 1]
        return out

    def to_trap(self, px: np.ndarray) -> np.ndarray:
        """Window pixels to trap coordinates (y up)."""
        ox, oy = self.origin
        px = np.asarray(px, dtype=float)
        out = np.empty_like(px)
        out[..., 0] = px[..., 0] - ox
        out[..., 1] = oy - px[..., 1]
        return out
