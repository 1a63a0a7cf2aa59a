"""What the pages show of a class, read from the store: the leaderboard of its current
challenge, the replay on its projector, the debrief's state, a challenge's time window."""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from typing import Any

from evapcool.classroom.challenge import challenge_doc
from evapcool.classroom.debrief import Showing, without_names
from evapcool.classroom.store import ClassStore


@dataclass
class _Read:
    """What a room's boards are made of, read from the store once (every board of a send:
    the projector's, a page's, the joined students' own rows)."""

    current: dict[str, Any] | None
    showing: dict[str, Any] | None
    now_open: dict[str, Any] | None
    rows: list[tuple[int, str, int, int, str, str]]  # entry, name, score, frames, edition, token
    state: Showing


def _read(store: ClassStore, room: int, past: int | None = None) -> _Read:
    current = store.latest(room) if past is None else store.challenge(past, room)
    showing = store.showing(room) if past is None else None
    now_open = store.open_one(room) if showing is not None else None
    rows = [] if current is None else store.leaderboard_players(_id(current))
    state = showing_of(store.debrief_state(room))
    if past is not None and (current or {}).get("id") != _latest_id(store, room):
        state = Showing(state.anonymous)  # a past round: no game picked nor paired
    return _Read(current, showing, now_open, rows, state)


def keyed_replay(store: ClassStore, room: int) -> dict[str, Any] | None:
    """The replay on a room's projector as its key's holders (and the lecturer) see it."""
    shown: dict[str, Any] | None = _replay_seen(
        _Read(None, store.showing(room), None, [], Showing()), keyed=True
    )
    return shown


def _id(row: dict[str, Any]) -> int:
    return int(row["id"])


def _replay_seen(read: _Read, keyed: bool) -> Any:
    """The replay on the projector as a reader may see it: without its code while its
    challenge is open, unless the reader holds the projector's key (or is the lecturer)."""
    showing, now_open = read.showing, read.now_open
    if showing is None:
        return None
    hidden = {"player"}  # the student's token, never shown
    if not keyed and _is_open(now_open) and now_open and now_open["id"] == showing["challenge"]:
        hidden.add("code")
    return {k: v for k, v in showing.items() if k not in hidden}


def _shaped(read: _Read, keyed: bool) -> dict[str, Any]:
    """The leaderboard document (see docs/class.md) with the debrief's state; no names in
    the debrief's anonymous mode."""
    current = read.current
    entries = [
        {"rank": i, "entry": r[0], "name": r[1], "score": r[2], "frames": r[3], "edition": r[4]}
        for i, r in enumerate(read.rows, 1)
    ]
    board = {
        "challenge": None if current is None else current["id"],
        "open": _is_open(current),
        "info": None if current is None else challenge_info(current),
        "entries": entries,
        "players": len(entries),  # one row a student: how many played (the board says it)
        "rejected": 0 if current is None else current["rejected"],
        "replay": _replay_seen(read, keyed),
        "debrief": read.state.to_json(),
    }
    return without_names(board) if read.state.anonymous else board


def _board(store: ClassStore, room: int, keyed: bool, past: int | None = None) -> dict[str, Any]:
    """The leaderboard of a room's current challenge, or of its past round `past` (kept with
    its board: issue 45; no replay playing in it)."""
    return _shaped(_read(store, room, past), keyed)


def _send_boards(
    store: ClassStore, room: int, kinds: set[bool], phones: bool
) -> tuple[dict[bool, str], dict[str, Any], dict[str, dict[str, Any]]]:
    """Every board one send needs, from one read of the store: the text for each kind of
    reader (keyed or not), and for joined students' streams (issue 46) the board without
    its rows or replay (`players` counts them) and each student's own row by token: a
    hall's 300 phones get their own row, not the whole board four times a second each."""
    read = _read(store, room)
    texts = {keyed: json.dumps(_shaped(read, keyed)) for keyed in kinds}
    if not phones:
        return texts, {}, {}
    board = _shaped(read, keyed=False)
    rows = board.pop("entries")
    board.pop("replay")
    mine = {r[5]: row for r, row in zip(read.rows, rows, strict=True)}
    return texts, board, mine


def phone_text(board: dict[str, Any], row: dict[str, Any] | None) -> str:
    """A joined student's stream event: the board with their own row alone (if ranked)."""
    return json.dumps({**board, "entries": [row] if row else []})


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
