"""Keys checked for the life of an event stream: a projector's stream opened with a key
that a relink (or a retired lecturer) made stale is closed at once, before it is sent
another board, and within KEY_CHECK seconds when nothing changes."""

from __future__ import annotations

import asyncio
import secrets
from typing import Any

from evapcool.classroom.store import StoreAwayError
from evapcool.classroom.tokens import PROJECTOR_SECRET, matches_digest, room_projector_key

#: Seconds between looks at the keys of the open keyed streams (a relink by
#: `evapcool class admin` in another process tells no one).
KEY_CHECK = 1.0


def key_holds(store: object, room_id: int, key: str) -> bool:
    """Whether `key` is still the projector key of a room (run on a store thread)."""
    room = store.room(room_id)  # type: ignore[attr-defined]
    if room is None:
        return False
    if room["lecturer"] is None:
        return matches_digest(key, store.secret(PROJECTOR_SECRET))  # type: ignore[attr-defined]
    if not room["digest"]:
        return False
    return secrets.compare_digest(key, room_projector_key(room["digest"], room["code"]))


async def drop_stale(hub: Any, listeners: list[Any]) -> None:  # hub.Hub: it imports us
    """Close the keyed streams among `listeners` whose key no longer holds (one store
    look per room and key)."""
    verdicts: dict[tuple[int, str], bool] = {}
    for listener in listeners:
        if not listener.keyed or listener.key is None or listener.closed:
            continue
        seen = (listener.room, listener.key)
        if seen not in verdicts:
            verdicts[seen] = await hub.db(key_holds, hub.store, *seen)
        if not verdicts[seen]:
            listener.close()


async def watch_keys(hub: Any) -> None:
    """Every KEY_CHECK seconds, close the keyed streams whose key went stale."""
    while True:
        await asyncio.sleep(KEY_CHECK)
        try:
            await drop_stale(hub, list(hub.listeners))
        except StoreAwayError:
            continue
