"""A one-line progress bar with ETA, drawn only when the stream is a terminal."""

from __future__ import annotations

import sys
import time
from typing import TextIO


def _clock(seconds: float) -> str:
    s = round(seconds)
    h, rem = divmod(s, 3600)
    m, s = divmod(rem, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


class Progress:
    """Progress over a known number of frames; silent unless enabled (default: stream is a tty)."""

    def __init__(
        self,
        total: int,
        stream: TextIO | None = None,
        enabled: bool | None = None,
        min_interval: float = 0.2,
    ) -> None:
        self.total = max(int(total), 1)
        self.stream = sys.stderr if stream is None else stream
        if enabled is None:
            isatty = getattr(self.stream, "isatty", None)
            enabled = bool(isatty and isatty())
        self.enabled = enabled
        self.min_interval = min_interval
        self.start = time.monotonic()
        self._last = -1e9
        self._drawn = False

    def update(self, done: int, note: str = "", force: bool = False) -> None:
        """Redraw the bar for `done` frames if enough wall time passed since the last draw."""
        if not self.enabled:
            return
        now = time.monotonic()
        if not force and now - self._last < self.min_interval:
            return
        self._last = now
        frac = min(max(done / self.total, 0.0), 1.0)
        width = 30
        filled = int(frac * width)
        elapsed = now - self.start
        eta = elapsed * (1.0 - frac) / frac if frac > 0 else float("nan")
        eta_text = _clock(eta) if eta == eta else "?"
        bar = "#" * filled + "." * (width - filled)
        line = f"\r[{bar}] {100 * frac:5.1f}% {done}/{self.total} frames  ETA {eta_text}  {note}"
        self.stream.write(line.ljust(79))
        self.stream.flush()
        self._drawn = True

    def close(self) -> None:
        """End the bar's line (only if one was drawn)."""
        if self.enabled and self._drawn:
            self.stream.write("\n")
            self.stream.flush()
