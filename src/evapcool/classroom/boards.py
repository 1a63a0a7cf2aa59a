"""What the pages show of a class, read from the store: the leaderboard of its current
challenge, the replay on its projector, the debrief's state, a challenge's time window."""

from __future__ import annotations

import json
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


def _leaderboard(
    store: ClassStore, room: int, keyed: bool, past: int | None = None
) -> dict[str, Any]:
    """The leaderboard of a room's current challenge, or of its past round `past` (kept with
    its board: issue 45; no replay playing in it) (see docs/class.md)."""
    current = store.latest(room) if past is None else store.challenge(past, room)
    replay = _replay_seen(store, room, keyed) if past is None else None
    if current is None:
        return {
            "challenge": None,
            "open": False,
            "info": None,
            "entries": [],
            "players": 0,
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
        "players": len(entries),  # one row a student: how many played (the board says it)
        "rejected": current["rejected"],
        "replay": replay,
    }


def _phones_board(store: ClassStore, room: int) -> tuple[dict[str, Any], dict[str, dict[str, Any]]]:
    """The board as joined students' streams get it (issue 46): the board without its rows
    or replay (`players` counts the rows), and each player's row's place by token. A hall's
    300 phones each get their own row alone, not the whole board four times a second."""
    board = _board(store, room, keyed=False)
    rows = board.pop("entries")
    board.pop("replay")
    at = {row["entry"]: k for k, row in enumerate(rows)}
    mine = {}
    if board["challenge"] is not None:
        for token, entry in store.board_entries(int(board["challenge"])).items():
            if entry in at:
                mine[token] = rows[at[entry]]
    return board, mine


def phone_text(board: dict[str, Any], row: dict[str, Any] | None) -> str:
    """A joined student's stream event: the board with their own row alone (if ranked)."""
    return json.dumps({**board, "entries": [row] if row else []})


def _board(store: ClassStore, room: int, keyed: bool, past: int | None = None) -> dict[str, Any]:
    """The leaderboard document with the debrief's state (see docs/class.md); no names
    in the debrief's anonymous mode. past: a past round's (its debrief with no game picked
    nor paired: those are the current round's)."""
    board = _leaderboard(store, room, keyed, past)
    state = showing_of(store.debrief_state(room))
    if past is not None and board["challenge"] != _latest_id(store, room):
        state = Showing(state.anonymous)
    board["debrief"] = state.to_json()
    return without_names(board) if state.anonymous else board


def _latest_id(store: ClassStore, room: int) -> object:
    latest = store.latest(room)
    return None if latest is None else latest["id"]


def rounds_of(store: ClassStore, room: int) -> list[dict[str, Any]]:
    """The class's closed rounds, newest first: id, settings, seed, students and games
    (the history the projector reopens)."""
    keep = ("id", "settings", "seed", "lost", "students", "games", "closes_at")
    return [{k: c.get(k) for k in keep} for c in store.challenges(room) if not _is_open(c)]


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
