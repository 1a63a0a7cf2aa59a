"""A game's path in the (N, T) plane and its trap height, sampled from its replay (issue 36).

The class's debrief draws every verified game's path at once, so the server computes it
once, at verification, and keeps it. The path is the applet's path chart's: the atoms
trapped N and the temperature T at the end of whole frames, replayed with the game's own
frame rule (`Simulation.path`: the core's `core_path`, whose oracle is the reference
engine's readable loop, as `replay.replay` plays the frames). The twin in
web/src/game/path.ts samples the same frames and rounds the same way, so a path from the
server equals the one the student's page computes for that game, point for point.

Sampling: frame k = 0 (the start) and every `stride`-th whole frame, then the last frame
played (the win's), at most MAX_POINTS points; stride = ceil(frames / (MAX_POINTS - 1)).
A point with no atom trapped, or no finite positive temperature, is left out (the chart's
rule). T is kept to T_DIGITS significant digits (the drawing needs no more).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
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
        doc = {f.name: getattr(self, f.name) for f in fields(self)}
        return {k: list(v) if isinstance(v, tuple) else v for k, v in doc.items()}


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
    runs = [(clamp_height(h), run) for h, run in rec.moves]
    t0 = float(sim.temperature)
    h0 = runs[0][0] if runs else clamp_height(sim.trap_height)
    played, rows = sim.path(runs, total, stride, h0)
    ks = tuple(int(k) for k in rows[:, 0])
    ns = tuple(int(n) for n in rows[:, 1])
    ts = tuple(round_t(float(t)) for t in rows[:, 2])
    hs = tuple(float(h) for h in rows[:, 3])
    won, score = sim.score is not None, sim.score or 0
    return GamePath(ks, ns, ts, hs, played, won, score, t0)
