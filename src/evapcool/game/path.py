"""A game's path in the (N, T) plane and its trap height, sampled from its replay (issue 36).

The class's debrief draws every verified game's path at once, so the server computes it
once, at verification, and keeps it. The path is the applet's path chart's: the atoms
trapped N and the temperature T at the end of whole frames, replayed with the game's own
frame rule (`Simulation.frame`, as `replay.replay` plays it). The twin in
web/src/game/path.ts samples the same frames and rounds the same way, so a path from the
server equals the one the student's page computes for that game, point for point.

Sampling: frame k = 0 (the start) and every `stride`-th whole frame, then the last frame
played (the win's), at most MAX_POINTS points; stride = ceil(frames / (MAX_POINTS - 1)).
A point with no atom trapped, or no finite positive temperature, is left out (the chart's
rule). T is kept to T_DIGITS significant digits (the drawing needs no more).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

from evapcool.game.replay import Recording
from evapcool.game.rules import Game, clamp_height

#: Most points a path keeps (a few hundred: 300 games draw at once).
MAX_POINTS = 240
#: Significant digits of the temperatures kept.
T_DIGITS = 5


@dataclass(frozen=True)
class GamePath:
    """Sampled frames k, atoms n, temperature t, height h held during frame k (the first
    move's at k = 0); frames played, won, score; t0 the start's temperature (full)."""

    k: tuple[int, ...]
    n: tuple[int, ...]
    t: tuple[float, ...]
    h: tuple[float, ...]
    frames: int
    won: bool
    score: int
    t0: float

    def to_json(self) -> dict[str, Any]:
        """The stored and served form (columns of numbers as lists), fields in order."""
        return {k: list(v) if isinstance(v, tuple) else v for k, v in asdict(self).items()}


def stride_of(frames: int) -> int:
    """The sampling step of a game of `frames` whole frames."""
    return max(1, math.ceil(frames / (MAX_POINTS - 1)))


def round_t(t: float) -> float:
    """T to T_DIGITS significant digits (the decimal nearest, as JS toPrecision)."""
    return float(f"{t:.{T_DIGITS - 1}e}")


def game_path(
    rec: Recording, frames: int | None = None, engine: str = "auto", stride: int | None = None
) -> GamePath:
    """The path of a recording's game, replayed up to the win or the end of its moves (or
    `frames` whole frames: the verified length, when known); stride: 1 for every frame (two
    games played side by side), else the sampling's."""
    total = rec.n_frames if frames is None else min(frames, rec.n_frames)
    stride = stride or stride_of(total)
    sim = Game(rec.settings.game_config(rec.seed, engine)).sim
    heights = [clamp_height(h) for h, _ in rec.moves]
    ks: list[int] = []
    ns: list[int] = []
    ts: list[float] = []
    hs: list[float] = []

    def keep(k: int, h: float) -> None:
        n, t = sim.n_trapped, sim.temperature
        if n > 0 and math.isfinite(t) and t > 0:
            ks.append(k)
            ns.append(int(n))
            ts.append(round_t(t))
            hs.append(h)

    t0 = float(sim.temperature)
    keep(0, heights[0] if heights else clamp_height(sim.trap_height))
    k = 0
    for (_, run), h in zip(rec.moves, heights, strict=True):
        for _ in range(run):
            if k >= total or sim.score is not None:
                break
            sim.frame(h)
            k += 1
            if k % stride == 0 or k == total or sim.score is not None:
                keep(k, h)
    won, score = sim.score is not None, sim.score or 0
    return GamePath(tuple(ks), tuple(ns), tuple(ts), tuple(hs), k, won, score, t0)
