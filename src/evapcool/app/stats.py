"""Frame timing for the help overlay: frames per second, physics and drawing time.

Times come in from the app (measured around its own calls), so this is testable
with made-up numbers; figures are over the last `window` seconds of wall clock.
"""

from __future__ import annotations

from collections import deque

from evapcool.app.words import t


class FrameStats:
    """Rolling frame rate, mean physics and drawing time, and the game's pace."""

    def __init__(self, window: float = 1.0) -> None:
        self.window = float(window)
        #: (wall seconds of the frame, physics s, drawing s, game seconds advanced)
        self._frames: deque[tuple[float, float, float, float]] = deque()
        self._span = 0.0

    def add(self, wall: float, physics: float, drawing: float, played: float) -> None:
        """One frame: its wall time, the time spent in physics and in drawing (s), and
        the seconds of game time it advanced (less than wall when frames fall behind)."""
        self._frames.append((wall, physics, drawing, played))
        self._span += wall
        while len(self._frames) > 1 and self._span - self._frames[0][0] >= self.window:
            self._span -= self._frames.popleft()[0]

    def _mean(self, k: int) -> float:
        n = len(self._frames)
        return sum(f[k] for f in self._frames) / n if n else 0.0

    @property
    def fps(self) -> float:
        return len(self._frames) / self._span if self._span > 0 else 0.0

    @property
    def physics_ms(self) -> float:
        return 1e3 * self._mean(1)

    @property
    def drawing_ms(self) -> float:
        return 1e3 * self._mean(2)

    @property
    def pace(self) -> float | None:
        """Game time per wall time while playing (1 = real time), None while paused."""
        wall = sum(f[0] for f in self._frames if f[3] > 0)
        played = sum(f[3] for f in self._frames)
        return played / wall if wall > 0 else None

    def lines(self) -> list[str]:
        """The readout for the help overlay."""
        lines = [
            t(
                "help.frame_rate",
                fps=round(self.fps),
                physics=round(self.physics_ms, 1),
                drawing=round(self.drawing_ms, 1),
            )
        ]
        pace = self.pace
        if pace is not None and pace < 0.97:
            lines.append(t("status.slow", percent=round(100 * pace)))
        return lines
