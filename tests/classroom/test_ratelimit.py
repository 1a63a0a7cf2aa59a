"""Token buckets (issue 22.3): a burst goes, then one request per refill, with the wait told."""

from __future__ import annotations

from evapcool.classroom.ratelimit import Rate, RateLimiter


def test_burst_then_refill_and_keys_apart() -> None:
    now = [0.0]
    limiter = RateLimiter(Rate(burst=3, per_second=0.5), clock=lambda: now[0])
    assert [limiter.take("a") for _ in range(4)] == [0, 0, 0, 2]
    assert limiter.take("b") == 0
    now[0] = 1.0
    assert limiter.take("a") == 1
    now[0] = 2.0
    assert limiter.take("a") == 0 and limiter.take("a") == 2
