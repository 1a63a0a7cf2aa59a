"""The game's clock: how far each frame moves the physics, the animations and the notices.

Frames come on the wall clock (each advances its elapsed time x 30 x speed physics frames,
at most MAX_WALL_STEP of wall time) or, headless, one physics frame each. `FrameStats`
keeps the timings the help shows.
"""

from __future__ import annotations

from evapcool.app.stats import FrameStats
from evapcool.game.rules import MAX_WALL_STEP, Game
from evapcool.physics.simulation import FPS


class GameClock:
    """Advances a game frame by frame; the seconds of animation so far; the frame times."""

    def __init__(self) -> None:
        #: Seconds of animation (wall clock, or 1/30 per headless frame): fades, toasts.
        self.anim_time = 0.0
        self.stats = FrameStats()

    def advance(self, game: Game, wall_seconds: float | None) -> tuple[float, float]:
        """The physics for one frame: (seconds it animated, seconds of play at 1x; 0 while
        paused). wall_seconds None: exactly one physics frame x speed (headless)."""
        paused = game.paused
        if wall_seconds is None:
            game.run_frames(1)
            dt = 1.0 / FPS
            played = 0.0 if paused else dt
        else:
            game.update(wall_seconds)
            dt = max(0.0, wall_seconds)
            played = 0.0 if paused else min(dt, MAX_WALL_STEP)
        self.anim_time += dt
        return dt, played

    def record(self, wall: float, physics: float, drawing: float, played: float) -> None:
        self.stats.add(wall, physics, drawing, played)
