"""The limits of a hall behind one address (issue 46), without a server: what each request
is counted against, and the event streams' bounds."""

from __future__ import annotations

from dataclasses import dataclass

import pytest
from starlette.requests import Request

from evapcool.classroom.errors import RefusedError
from evapcool.classroom.halls import (
    HALL_RATE,
    KEY,
    STUDENT,
    STUDENT_RATE,
    Buckets,
    stream_refusal,
    take,
)
from evapcool.classroom.hub import Limits
from evapcool.classroom.ratelimit import Rate, RateLimiter


def request(host: str = "10.0.0.1", token: str = "", query: str = "") -> Request:
    headers = [(b"authorization", f"Bearer {token}".encode())] if token else []
    scope = {
        "type": "http",
        "method": "GET",
        "path": "/api/me",
        "query_string": query.encode(),
        "headers": headers,
        "client": (host, 5000),
    }
    return Request(scope)


def buckets(clock: list[float]) -> Buckets:
    """Buckets on a clock the test moves (nothing refills unless it does)."""
    now = lambda: clock[0]  # noqa: E731
    return Buckets(
        RateLimiter(Rate(10, 1), now),
        RateLimiter(STUDENT_RATE, now),
        RateLimiter(HALL_RATE, now),
        RateLimiter(Rate(600, 50), now),
    )


def refused_field(b: Buckets, req: Request) -> str:
    with pytest.raises(RefusedError) as caught:
        take(b, req)
    return caught.value.field


def test_a_checked_token_counts_against_itself_not_the_address() -> None:
    b = buckets([0.0])
    b.known.note("tok-a", STUDENT, 1)
    b.known.note("tok-b", STUDENT, 1)
    for _ in range(int(STUDENT_RATE.burst)):
        take(b, request(token="tok-a"))
    assert refused_field(b, request(token="tok-a")) == "token"
    take(b, request(token="tok-b"))  # another student behind the same address
    for _ in range(10):
        take(b, request())  # the address's own bucket untouched
    assert refused_field(b, request()) == "client"
    take(b, request(token="tok-b"))  # a student goes on while the address is held


def test_made_up_tokens_count_as_the_address() -> None:
    b = buckets([0.0])
    for i in range(10):
        take(b, request(token=f"made-up-{i}"))
    assert refused_field(b, request(token="made-up-x")) == "client"


def test_a_checked_key_and_the_stream_token_in_the_query() -> None:
    b = buckets([0.0])
    for _ in range(10):
        take(b, request())
    b.known.note("k" * 32, KEY, 1)
    b.known.note("tok-s", STUDENT, 1)
    take(b, request(query="key=" + "k" * 32))
    take(b, request(query="token=tok-s"))


@dataclass
class Stream:
    address: str
    keyed: bool
    room: int
    token: str | None


def test_stream_bounds() -> None:
    limits = Limits()
    hall = [Stream("10.0.0.1", False, 1, f"t{i}") for i in range(300)]
    assert stream_refusal(limits, hall, "10.0.0.1", 1, False, "t300") is None
    mine = [Stream("10.0.0.1", False, 1, "t0")] * limits.token_listeners
    refused = stream_refusal(limits, mine, "10.0.0.1", 1, False, "t0")
    assert refused is not None and refused.field == "token"
    anonymous = [Stream("10.0.0.1", False, 1, None)] * limits.address_listeners
    refused = stream_refusal(limits, anonymous, "10.0.0.1", 1, False, None)
    assert refused is not None and refused.field == "client"
    assert stream_refusal(limits, anonymous, "10.0.0.1", 1, False, "t1") is None
    assert stream_refusal(limits, anonymous + hall, "10.0.0.1", 1, True, None) is None
