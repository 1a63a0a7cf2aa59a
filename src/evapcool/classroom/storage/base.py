"""The store layer's common ground: the errors every store raises, the rows' keys, and the
base of the SQL stores (what a database gives: rows, a write transaction, row locks)."""

from __future__ import annotations

import threading
from collections.abc import Callable, Sequence
from typing import Any

from evapcool.classroom.ratelimit import Rate


class StoreAwayError(Exception):
    """The database does not answer (a shared store's server away): try again shortly."""


class NameTakenError(Exception):
    """A name that looks like another player's (`name`: the one it clashes with)."""

    def __init__(self, name: str) -> None:
        super().__init__(f"name: looks like {name!r}")
        self.name = name


class ClassFullError(Exception):
    """No more players: the class has its bound."""


CHALLENGE_KEYS = (
    "id",
    "settings",
    "seed",
    "max_frames",
    "attempts",
    "rejected",
    "closes_at",
    "open",
    "lost",
    "room",
)
ROOM_KEYS = ("id", "code", "name", "lecturer", "lecturer_name", "digest", "created")
ENTRY_KEYS = ("entry", "name", "score", "frames", "edition", "hidden")
#: An entry row of `_all`: id, name, score, frames, edition, player token, hidden.
EntryRow = tuple[int, str, int, int, str, str, int]
#: A statement run in a transaction: (SQL with ? placeholders, parameters) -> its cursor.
Query = Callable[[str, Sequence[Any]], Any]
#: The rows of an entry of the room: entries of its challenges only.
IN_ROOM = "JOIN challenge c ON c.id = e.challenge WHERE e.id = ? AND c.room = ?"
#: Hidden when the entry or its player is (portable: no MAX(a, b) in PostgreSQL).
HIDDEN = "CASE WHEN e.hidden > p.hidden THEN e.hidden ELSE p.hidden END"


class SqlBase:
    """What every SQL store gives its aggregates: the connection, the transaction and the
    row locks (subclasses), and the helpers reading and writing through them."""

    shared = False

    #: The exception a duplicate key raises (a join code taken).
    duplicate: tuple[type[Exception], ...] = ()

    def _rows(self, sql: str, params: Sequence[Any] = ()) -> list[Any]:
        raise NotImplementedError

    def _tx(self) -> Any:
        """A context manager: a write transaction, yielding a Query."""
        raise NotImplementedError

    def _lock(self, q: Query, table: str, key: int) -> None:
        """Hold a row's lock to the transaction's end (SQLite holds the whole file)."""

    def _lock_moves(self, q: Query, moves: str) -> None:
        """Hold a lock on a game's moves to the transaction's end (SQLite: the file's)."""

    def close(self) -> None:
        raise NotImplementedError

    def notify(self, room: int) -> None:
        """Tell every process sharing the store that a room's board changed."""

    def take(self, kind: str, key: str, rate: Rate) -> int:
        raise NotImplementedError

    def forget_buckets(self) -> None:
        """Drop rate buckets idle long enough to be full again (kept in memory: nothing)."""

    def listen(self, changed: Callable[[int | None], None], stop: threading.Event) -> None:
        """Follow the boards changed by every process sharing the store (shared ones)."""
        raise NotImplementedError

    def _one(self, sql: str, params: Sequence[Any] = ()) -> Any:
        rows = self._rows(sql, params)
        return rows[0] if rows else None

    def _write(self, sql: str, params: Sequence[Any] = ()) -> int:
        with self._tx() as q:
            return int(q(sql, params).rowcount)
