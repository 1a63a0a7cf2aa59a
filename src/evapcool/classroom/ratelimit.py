"""Token buckets per key (a client address or a player's token): 429 with Retry-After."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

#: Buckets kept at most; the one idle longest is dropped first when over.
MAX_KEYS = 100_000


@dataclass(frozen=True)
class Rate:
    """A bucket of `burst` requests refilled at `per_second`."""

    burst: float
    per_second: float


class RateLimiter:
    """Token buckets keyed by a string; `take` answers 0 (go) or seconds to wait."""

    def __init__(self, rate: Rate, clock: Callable[[], float] = time.monotonic) -> None:
        self.rate = rate
        self.clock = clock
        self.buckets: dict[str, tuple[float, float]] = {}

    def take(self, key: str) -> int:
        """0 if `key` may go now (a token spent), else whole seconds until it may."""
        now = self.clock()
        tokens, last = self.buckets.get(key, (self.rate.burst, now))
        tokens = min(self.rate.burst, tokens + (now - last) * self.rate.per_second)
        if tokens >= 1.0:
            self._put(key, tokens - 1.0, now)
            return 0
        self._put(key, tokens, now)
        return max(1, math.ceil((1.0 - tokens) / self.rate.per_second))

    def _put(self, key: str, tokens: float, now: float) -> None:
        self.buckets.pop(key, None)  # re-inserted last: the dict's order is by last use
        self.buckets[key] = (tokens, now)
        if len(self.buckets) > MAX_KEYS:
            del self.buckets[next(iter(self.buckets))]
