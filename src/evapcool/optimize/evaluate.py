"""What the optimizer's Dask tasks run: a strategy played on a list of seeds, and the summary.

Tasks take and return plain values (strategy text, seeds, numbers), so they run the same
on any worker: a game depends only on the strategy, the seed and the game's setup.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

from evapcool.game.autopilot import GameSetup, parse_strategy, play
from evapcool.physics.simulation import FPS


def play_seeds(
    strategy_text: str, seeds: Sequence[int], budget: int, setup: dict
) -> tuple[list[tuple[int, int, int]], float]:
    """[(seed, score, won frame or -1)] for each seed, and the CPU seconds it took."""
    strategy = parse_strategy(strategy_text)
    game = GameSetup(**setup)
    start = time.process_time()
    rows = []
    for seed in seeds:
        o = play(strategy, int(seed), budget, game)
        rows.append((int(seed), o.score, -1 if o.won_frame is None else o.won_frame))
    return rows, time.process_time() - start


def chunks(seeds: Sequence[int], size: int) -> list[list[int]]:
    return [list(seeds[i : i + size]) for i in range(0, len(seeds), size)]


@dataclass(frozen=True)
class Summary:
    """Scores of one strategy on a set of seeds (no win = score 0, time = the budget)."""

    seeds: tuple[int, ...]
    scores: tuple[int, ...]
    won_frames: tuple[int, ...]  # -1: no win within the budget
    budget: int

    @classmethod
    def of(cls, rows: Sequence[tuple[int, int, int]], budget: int) -> Summary:
        rows = sorted(rows)
        return cls(
            tuple(r[0] for r in rows), tuple(r[1] for r in rows), tuple(r[2] for r in rows), budget
        )

    @property
    def n(self) -> int:
        return len(self.scores)

    @property
    def mean(self) -> float:
        return sum(self.scores) / self.n

    @property
    def se(self) -> float:
        return standard_error(self.scores)

    @property
    def no_wins(self) -> int:
        return sum(1 for f in self.won_frames if f < 0)

    @property
    def times(self) -> list[float]:
        """Seconds to the win, the budget for a run without one."""
        return [(f if f >= 0 else self.budget) / FPS for f in self.won_frames]

    @property
    def time_mean(self) -> float:
        return sum(self.times) / self.n

    @property
    def time_se(self) -> float:
        return standard_error(self.times)


def standard_error(values: Sequence[float]) -> float:
    n = len(values)
    if n < 2:
        return math.nan
    m = sum(values) / n
    return math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1) / n)


@dataclass(frozen=True)
class Paired:
    """Strategy A against B on the same seeds: the mean difference and its error."""

    a: Summary
    b: Summary

    def __post_init__(self) -> None:
        if self.a.seeds != self.b.seeds:
            raise ValueError("a paired comparison needs the same seeds for both")

    @property
    def differences(self) -> list[int]:
        return [x - y for x, y in zip(self.a.scores, self.b.scores, strict=True)]

    @property
    def mean(self) -> float:
        d = self.differences
        return sum(d) / len(d)

    @property
    def se(self) -> float:
        return standard_error(self.differences)

    def interval(self, z: float = 1.96) -> tuple[float, float]:
        """Normal-approximation 95 % interval of the mean difference (n >= 100 here)."""
        return self.mean - z * self.se, self.mean + z * self.se

    @property
    def wins_losses_ties(self) -> tuple[int, int, int]:
        d = self.differences
        return sum(x > 0 for x in d), sum(x < 0 for x in d), sum(x == 0 for x in d)
