"""Wrong join codes limited per client address: a hall typing its code with typos never
notices, a guesser needs years for a hit. With 21^6 codes and 500 classes a hit takes
about 171,000 guesses; after WRONG_CODES' burst an address may miss once every 300 s
(288 a day): about 1.6 years per hit. Counted in the store (across processes). Codes an
address already reached stay open to it while it is held back (its hall keeps playing)."""

from __future__ import annotations

import time
from collections import OrderedDict
from typing import Any

from starlette.requests import Request

from evapcool.classroom.errors import RefusedError
from evapcool.classroom.hub import Hub
from evapcool.classroom.ratelimit import Rate
from evapcool.classroom.rooms import normal_code

#: Wrong codes per client address: 60 at once, then one every 300 s.
WRONG_CODES = Rate(burst=60, per_second=1 / 300)
#: Addresses remembered (held back, or with the codes they reached).
KEPT = 20_000


class Guesses:
    """This process's view: addresses held back until a time, and codes each reached."""

    def __init__(self) -> None:
        self.held: dict[str, float] = {}
        self.reached: OrderedDict[str, set[str]] = OrderedDict()

    def note_reached(self, who: str, code: str) -> None:
        codes = self.reached.pop(who, set())
        if len(codes) < 16:
            codes.add(code)
        self.reached[who] = codes
        if len(self.reached) > KEPT:
            self.reached.popitem(last=False)


def _guesses(hub: Hub) -> Guesses:
    found = getattr(hub, "guesses", None)
    if found is None:
        found = Guesses()
        hub.guesses = found  # type: ignore[attr-defined]
    return found


def _slow_down(wait: float) -> RefusedError:
    seconds = max(1, int(wait))
    return RefusedError(429, "code", "class.error.slow_down", retry_after=seconds, n=seconds)


async def room_by_given_code(hub: Hub, who: str, given: str) -> dict[str, Any] | None:
    """The class a typed code names, or None; 429 `code` while the address is held back
    for too many wrong ones (a code it reached before still works)."""
    guesses = _guesses(hub)
    code = normal_code(given)
    now = time.monotonic()
    if guesses.held.get(who, 0.0) > now and code not in guesses.reached.get(who, ()):
        raise _slow_down(guesses.held[who] - now)
    room = await hub.db(hub.store.room_by_code, code) if code else None
    if room is not None:
        guesses.note_reached(who, str(room["code"]))
        return room
    wait = await hub.db(hub.store.take, "wrong_code", who, WRONG_CODES)
    if wait:
        guesses.held[who] = now + wait
        if len(guesses.held) > KEPT:
            guesses.held = {k: t for k, t in guesses.held.items() if t > now}
        raise _slow_down(wait)
    return None


async def room_for(request: Request, hub: Hub, given: str) -> dict[str, Any] | None:
    """`room_by_given_code` for a request's client address (a hall behind one NAT address
    shares it)."""
    client = request.client.host if request.client else "?"
    return await room_by_given_code(hub, client, given)
