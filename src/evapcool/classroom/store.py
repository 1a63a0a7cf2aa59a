"""The class server's data: classes, challenges, players and verified entries.

One interface (ClassStore), one set of SQL statements (SqlStore) and two databases: SQLite
in WAL mode here (the embedded default: standard library only) and PostgreSQL in pgstore.py
(a department's server, several processes). Every write commits before it returns: an
entry acknowledged to a student survives a kill -9.

The statements live by aggregate under storage/ (classes, challenges, players, entries, on
a common base), SQLite's store in storage/sqlite.py; this module is the layer's face: the
interface the server's rooms use and every name they import.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any, Protocol

from evapcool.classroom.names import BIDI_CONTROLS, NAME_MAX, clean_name, skeleton
from evapcool.classroom.ratelimit import Rate
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.storage.base import (
    CHALLENGE_KEYS,
    ENTRY_KEYS,
    HIDDEN,
    IN_ROOM,
    ROOM_KEYS,
    ClassFullError,
    EntryRow,
    NameTakenError,
    Query,
    StoreAwayError,
)
from evapcool.classroom.storage.entries import CSV_HEADER, FORMULA_START, csv_cell
from evapcool.classroom.storage.sql import SqlStore
from evapcool.classroom.storage.sqlite import ADDED_COLUMNS, INDEXES, ROOM_SCHEMA, SCHEMA, Store

__all__ = [
    "ADDED_COLUMNS",
    "BIDI_CONTROLS",
    "CHALLENGE_KEYS",
    "CSV_HEADER",
    "DEPARTMENT_MODULES",
    "ENTRY_KEYS",
    "FORMULA_START",
    "HIDDEN",
    "INDEXES",
    "IN_ROOM",
    "NAME_MAX",
    "NEEDS_DEPARTMENT",
    "ROOM_KEYS",
    "ROOM_SCHEMA",
    "SCHEMA",
    "ClassFullError",
    "ClassStore",
    "EntryRow",
    "NameTakenError",
    "Query",
    "SqlStore",
    "Store",
    "StoreAwayError",
    "clean_name",
    "csv_cell",
    "is_url",
    "skeleton",
]


#: What a PostgreSQL store needs (the department extra), and the line saying so.
DEPARTMENT_MODULES = ("psycopg", "psycopg_pool")
NEEDS_DEPARTMENT = (
    "evapcool class --db postgresql://... needs the department extra: "
    "pip install 'evapcool[department]'"
)


def is_url(text: str) -> bool:
    """Whether a --db value names a PostgreSQL database (else a SQLite file)."""
    return text.startswith(("postgresql://", "postgres://"))


class ClassStore(Protocol):
    """What the server needs of its database (SqlStore on SQLite or PostgreSQL).

    Room-scoped calls take `room` (DEFAULT_ROOM: a single-class server's one class);
    calls on an entry or a challenge id find nothing outside the room named.
    """

    #: Whether several server processes share this store (boards fan out through it).
    shared: bool

    def close(self) -> None: ...
    def secret(self, name: str) -> str | None: ...
    def set_secret(self, name: str, digest: str) -> None: ...
    def add_lecturer(self, name: str, digest: str) -> int: ...
    def lecturers(self) -> list[dict[str, Any]]: ...
    def lecturer_by_digest(self, digest: str) -> dict[str, Any] | None: ...
    def set_lecturer_digest(self, lecturer: int, digest: str) -> bool: ...
    def add_room(self, name: str, lecturer: int | None) -> dict[str, Any]: ...
    def room(self, room: int) -> dict[str, Any] | None: ...
    def room_by_code(self, code: str) -> dict[str, Any] | None: ...
    def rooms(self, lecturer: int | None = None) -> list[dict[str, Any]]: ...
    def showing(self, room: int) -> dict[str, Any] | None: ...
    def set_showing(self, room: int, shown: dict[str, Any] | None) -> None: ...
    def debrief_state(self, room: int) -> dict[str, Any] | None: ...
    def set_debrief_state(self, room: int, state: dict[str, Any] | None) -> None: ...
    def take(self, kind: str, key: str, rate: Rate) -> int: ...
    def notify(self, room: int) -> None: ...
    def forget_buckets(self) -> None: ...
    def listen(self, changed: Callable[[int | None], None], stop: threading.Event) -> None: ...
    def open_challenge(
        self,
        settings: dict[str, object],
        seed: int,
        max_frames: int,
        attempts: int | None,
        closes_at: float | None = None,
        lost: bool = False,
        room: int = DEFAULT_ROOM,
    ) -> int: ...
    def close_challenge(self, challenge: int) -> bool: ...
    def due(self, now: float) -> list[tuple[int, int]]: ...
    def open_one(self, room: int = DEFAULT_ROOM) -> dict[str, object] | None: ...
    def latest(self, room: int = DEFAULT_ROOM) -> dict[str, object] | None: ...
    def challenge(self, challenge: int, room: int = DEFAULT_ROOM) -> dict[str, object] | None: ...
    def challenges(self, room: int = DEFAULT_ROOM) -> list[dict[str, object]]: ...
    def entry_paths(self, challenge: int) -> dict[int, str | None]: ...
    def join(
        self, raw_name: object, max_players: int | None = None, room: int = DEFAULT_ROOM
    ) -> str: ...
    def players(self, room: int = DEFAULT_ROOM) -> int: ...
    def player_name(self, token: str, room: int = DEFAULT_ROOM) -> str | None: ...
    def rename(self, entry: int, raw_name: object, room: int = DEFAULT_ROOM) -> str | None: ...
    def hide(self, entry: int, hidden: bool = True, room: int = DEFAULT_ROOM) -> bool: ...
    def attempts(self, challenge: int, token: str) -> int: ...
    def add_if_allowed(
        self,
        challenge: int,
        token: str,
        result: tuple[int, int, str, str, str],
        now: float,
        path: str | None = None,
    ) -> int | str: ...
    def best_games(self, challenge: int) -> list[dict[str, object]]: ...
    def entries(self, challenge: int) -> list[dict[str, object]]: ...
    def standing(self, challenge: int, token: str) -> dict[str, int | None]: ...
    def entry_code(self, entry: int, room: int = DEFAULT_ROOM) -> tuple[str, str, int] | None: ...
    def entry_player(self, entry: int, room: int = DEFAULT_ROOM) -> str | None: ...
    def count_rejected(self, challenge: int) -> None: ...
    def leaderboard(self, challenge: int) -> list[tuple[int, str, int, int, str]]: ...
    def results_csv(self, challenge: int) -> str: ...
