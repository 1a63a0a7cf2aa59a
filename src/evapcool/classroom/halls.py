"""A hall behind one address (issue 46): the limits follow the student's token for all a
joined student does, the client address's limits stay for what comes without one.

A campus's NAT puts a whole lecture hall behind one address, so a request carrying a
secret this process has already checked (a student's token at its join or first call, the
projector's key, a lecturer's token) is counted against that secret's own bucket and, for
students, a large ceiling per class and address; only requests with no such secret (a
page, a join, a wrong code, a token never seen) share the address's bucket. A secret is
trusted here only for counting: every route still checks it against the store, and one
never checked counts as anonymous, so made-up tokens buy a flooder nothing.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol

from starlette.requests import Request

from evapcool.classroom.errors import RefusedError
from evapcool.classroom.ratelimit import Rate, RateLimiter


class Listener(Protocol):
    """What the stream limits read of an open stream (hub.Listener)."""

    address: str
    keyed: bool
    room: int
    token: str | None


class StreamBounds(Protocol):
    """The stream bounds of hub.Limits (read only: Limits is frozen)."""

    @property
    def listeners(self) -> int: ...
    @property
    def anonymous_listeners(self) -> int: ...
    @property
    def address_listeners(self) -> int: ...
    @property
    def token_listeners(self) -> int: ...
    @property
    def hall_listeners(self) -> int: ...
    @property
    def keyed_listeners(self) -> int: ...


#: Requests per student token: the page asks a few times a game and, without its stream,
#: once every 3 s; a flood from one token stops here, alone.
STUDENT_RATE = Rate(burst=40, per_second=2)
#: Requests of one class's students behind one address: 300 students asking at once (the
#: close: the debrief and the standing), then 120 a second (300 phones polling every 3 s
#: without their streams make 100), no more than one address's flood without tokens
#: would be; a class cannot spend another class's share.
HALL_RATE = Rate(burst=2000, per_second=120)
#: Requests per projector key or lecturer token (the projector's and console's pages).
KEY_RATE = Rate(burst=600, per_second=50)
#: Secrets remembered as checked (the one unused longest is forgotten first).
KNOWN_MAX = 200_000

STUDENT, KEY, LECTURER = "student", "key", "lecturer"


@dataclass
class Known:
    """The secrets this process has checked: each one's kind and class."""

    seen: OrderedDict[str, tuple[str, int]] = field(default_factory=OrderedDict)

    def note(self, secret: str, kind: str, room: int) -> None:
        """Remember a secret the store just confirmed (its kind, its class)."""
        if not secret:
            return
        self.seen.pop(secret, None)
        self.seen[secret] = (kind, room)
        if len(self.seen) > KNOWN_MAX:
            self.seen.popitem(last=False)

    def of(self, secret: str) -> tuple[str, int] | None:
        return self.seen.get(secret) if secret else None


@dataclass
class Buckets:
    """The request buckets: per address (anonymous), per secret, per class and address."""

    anonymous: RateLimiter
    student: RateLimiter = field(default_factory=lambda: RateLimiter(STUDENT_RATE))
    hall: RateLimiter = field(default_factory=lambda: RateLimiter(HALL_RATE))
    key: RateLimiter = field(default_factory=lambda: RateLimiter(KEY_RATE))
    known: Known = field(default_factory=Known)


def client_address(request: Request) -> str:
    """The client's address (a class behind one NAT address shares it)."""
    return request.client.host if request.client else "?"


def student_token(request: Request) -> str:
    """A student's token as a request gives it: as Bearer, or in ?token= on the event
    stream (a browser's EventSource sends no header)."""
    auth = request.headers.get("authorization", "")
    given = auth[7:].strip() if auth.lower().startswith("bearer ") else ""
    return given or request.query_params.get("token", "")


def _secrets(request: Request) -> list[str]:
    """The secrets a request may carry, in the order looked at."""
    from evapcool.classroom.session import LECTURER_COOKIE

    given = [student_token(request), request.query_params.get("key", "")]
    return [*given, request.cookies.get(LECTURER_COOKIE, "")]


def take(buckets: Buckets, request: Request) -> None:
    """Count a request against its limits; RefusedError(429) naming what is over: `token`
    (one student's), `client` (the address's, or a class's students behind it), `key`."""
    address = client_address(request)
    for secret in _secrets(request):
        found = buckets.known.of(secret)
        if found is None:
            continue
        kind, room = found
        if kind != STUDENT:
            _check(buckets.key.take(secret), "key")
            return
        _check(buckets.student.take(secret), "token")
        _check(buckets.hall.take(f"{room}@{address}"), "client")
        return
    _check(buckets.anonymous.take(address), "client")


def _check(wait: int, field_name: str) -> None:
    if wait:
        raise RefusedError(429, field_name, "class.error.slow_down", retry_after=wait, n=wait)


def stream_refusal(
    limits: StreamBounds,
    listeners: Sequence[Listener],
    address: str,
    room: int,
    with_key: bool,
    token: str | None,
) -> RefusedError | None:
    """Why one more event stream is refused (429), or None. The key's holders are counted
    per class, apart; a student's (its token checked) per token and per class and
    address, so a hall behind one address follows the board live; one without a token per
    address and within a share of all, so such streams never crowd the students out."""
    if with_key:
        if sum(1 for s in listeners if s.keyed and s.room == room) >= limits.keyed_listeners:
            return _streams("key", limits.keyed_listeners)
        return None
    public = [s for s in listeners if not s.keyed]
    if len(public) >= limits.listeners:
        return RefusedError(429, "client", "class.error.slow_down", retry_after=30, n=30)
    if token is not None:
        if sum(1 for s in public if s.token == token) >= limits.token_listeners:
            return _streams("token", limits.token_listeners)
        hall = sum(1 for s in public if s.token and s.room == room and s.address == address)
        return _streams("client", limits.hall_listeners) if hall >= limits.hall_listeners else None
    anonymous = [s for s in public if s.token is None]
    if sum(1 for s in anonymous if s.address == address) >= limits.address_listeners:
        return _streams("client", limits.address_listeners)
    if len(anonymous) >= limits.anonymous_listeners:
        return RefusedError(429, "client", "class.error.slow_down", retry_after=30, n=30)
    return None


def _streams(field_name: str, bound: int) -> RefusedError:
    return RefusedError(429, field_name, "class.error.streams", retry_after=30, n=bound)
