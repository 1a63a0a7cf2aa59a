"""What the pages show of a class, read from the store: the leaderboard of its current
challenge, the replay on its projector, the debrief's state, a challenge's time window."""

from __future__ import annotations

import time
from typing import Any

from evapcool.classroom.challenge import challenge_doc
from evapcool.classroom.debrief import Showing, without_names
from evapcool.classroom.store import ClassStore


def _replay_seen(store: ClassStore, room: int, keyed: bool) -> Any:
    """The replay on the projector as a reader may see it: without its code while its
    challenge is open, unless the reader holds the projector's key (or is the lecturer)."""
    showing = store.showing(room)
    if showing is None:
        return None
    hidden = {"player"}  # the student's token, never shown
    now_open = store.open_one(room)
    if not keyed and _is_open(now_open) and now_open and now_open["id"] == showing["challenge"]:
        hidden.add("code")
    return {k: v for k, v in showing.items() if k not in hidden}


def _leaderboard(store: ClassStore, room: int, keyed: bool) -> dict[str, Any]:
    """The leaderboard of a room's current challenge (see docs/class.md)."""
    current = store.latest(room)
    replay = _replay_seen(store, room, keyed)
    if current is None:
        return {
            "challenge": None,
            "open": False,
            "info": None,
            "entries": [],
            "rejected": 0,
            "replay": replay,
        }
    rows = store.leaderboard(int(current["id"]))  # type: ignore[call-overload]
    entries = [
        {"rank": i, "entry": r[0], "name": r[1], "score": r[2], "frames": r[3], "edition": r[4]}
        for i, r in enumerate(rows, 1)
    ]
    return {
        "challenge": current["id"],
        "open": _is_open(current),
        "info": challenge_info(current),
        "entries": entries,
        "rejected": current["rejected"],
        "replay": replay,
    }


def _board(store: ClassStore, room: int, keyed: bool) -> dict[str, Any]:
    """The leaderboard document with the debrief's state (see docs/class.md); no names
    in the debrief's anonymous mode."""
    board = _leaderboard(store, room, keyed)
    state = showing_of(store.debrief_state(room))
    board["debrief"] = state.to_json()
    return without_names(board) if state.anonymous else board


def challenge_info(row: dict[str, Any], now: float | None = None) -> dict[str, Any]:
    """What every page shows of a challenge: its API form, whether it is open, and the
    seconds left in its window (`closes_in`, counted from this answer: no clocks compared)."""
    now = time.time() if now is None else now
    closes = row.get("closes_at")
    left = None if closes is None else max(0.0, round(float(closes) - now, 3))
    return {**challenge_doc(row), "open": _is_open(row, now), "closes_in": left}


def _is_open(challenge: dict[str, Any] | None, now: float | None = None) -> bool:
    """Whether a challenge takes games now (open, and its time window not over)."""
    if challenge is None or not challenge.get("open"):
        return False
    closes = challenge.get("closes_at")
    return closes is None or (time.time() if now is None else now) < closes


def showing_of(doc: dict[str, Any] | None) -> Showing:
    """The debrief's state as the store keeps it (JSON), or the default."""
    if not doc:
        return Showing()
    pair = doc.get("pair")
    return Showing(
        bool(doc.get("anonymous")), doc.get("pick"), (pair[0], pair[1]) if pair else None
    )
