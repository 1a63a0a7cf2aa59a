"""The class server's data: classes, challenges, players and verified entries.

One interface (ClassStore), one set of SQL statements (SqlStore) and two databases: SQLite
in WAL mode here (the embedded default: standard library only) and PostgreSQL in pgstore.py
(a department's server, several processes). Every write commits before it returns: an
entry acknowledged to a student survives a kill -9.
"""

from __future__ import annotations

import csv
import io
import json
import secrets
import sqlite3
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Protocol

from evapcool.classroom.names import BIDI_CONTROLS, NAME_MAX, clean_name, skeleton
from evapcool.classroom.ratelimit import Rate, RateLimiter
from evapcool.classroom.rooms import DEFAULT_ROOM, new_code

__all__ = [
    "BIDI_CONTROLS",
    "NAME_MAX",
    "ClassStore",
    "SqlStore",
    "Store",
    "StoreAwayError",
    "clean_name",
    "csv_cell",
]


class StoreAwayError(Exception):
    """The database does not answer (a shared store's server away): try again shortly."""


#: A CSV cell starting with one of these is a formula in spreadsheets.
FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
#: One row per game sent and accepted: `rank` on each student's best shown game, `best`
#: marks each student's best game, `entry` is the game's number (the lecturer's page's).
CSV_HEADER = ("rank", "name", "score", "frames", "seed", "edition", "entry", "best", "hidden")

SCHEMA = """
CREATE TABLE IF NOT EXISTS challenge (
    id INTEGER PRIMARY KEY, settings TEXT NOT NULL, seed INTEGER NOT NULL,
    max_frames INTEGER NOT NULL, attempts INTEGER, open INTEGER NOT NULL DEFAULT 1,
    rejected INTEGER NOT NULL DEFAULT 0);
CREATE TABLE IF NOT EXISTS player (
    token TEXT PRIMARY KEY, name TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS entry (
    id INTEGER PRIMARY KEY, challenge INTEGER NOT NULL REFERENCES challenge(id),
    player TEXT NOT NULL REFERENCES player(token), score INTEGER NOT NULL,
    frames INTEGER NOT NULL, edition TEXT NOT NULL, hidden INTEGER NOT NULL DEFAULT 0);
CREATE TABLE IF NOT EXISTS secret (name TEXT PRIMARY KEY, digest TEXT NOT NULL);
"""
#: Indexes on columns that older files gain first (see ADDED_COLUMNS).
INDEXES = """
CREATE INDEX IF NOT EXISTS player_skeleton ON player(skeleton);
CREATE INDEX IF NOT EXISTS entry_moves ON entry(challenge, moves);
"""
#: Columns added after the first schema: (table, column, declaration); added when missing.
ADDED_COLUMNS = (
    ("challenge", "closes_at", "REAL"),
    ("entry", "code", "TEXT"),
    ("challenge", "lost", "INTEGER NOT NULL DEFAULT 0"),
    # The name's look (names.skeleton): no two players of one class look alike.
    ("player", "skeleton", "TEXT"),
    # Hidden by the lecturer: none of the player's entries is on the leaderboard.
    ("player", "hidden", "INTEGER NOT NULL DEFAULT 0"),
    # The game's moves up to its win (verifier.moves_key): a copy has the same.
    ("entry", "moves", "TEXT"),
    # The game's path, computed once at verification (game/path.py): JSON text.
    ("entry", "path", "TEXT"),
    # The class (room) a challenge and a player belong to: a file of one class is room 1.
    ("challenge", "room", f"INTEGER NOT NULL DEFAULT {DEFAULT_ROOM}"),
    ("player", "room", f"INTEGER NOT NULL DEFAULT {DEFAULT_ROOM}"),
)
#: Tables added with classes (rooms): the lecturers (their tokens' digests), the classes
#: (join code, name, lecturer, the replay on the projector and the debrief's state, JSON).
ROOM_SCHEMA = """
CREATE TABLE IF NOT EXISTS lecturer (
    id INTEGER PRIMARY KEY, name TEXT NOT NULL, digest TEXT NOT NULL UNIQUE);
CREATE TABLE IF NOT EXISTS room (
    id INTEGER PRIMARY KEY, code TEXT NOT NULL UNIQUE, name TEXT NOT NULL,
    lecturer INTEGER REFERENCES lecturer(id), showing TEXT, created REAL NOT NULL,
    debrief TEXT);
CREATE INDEX IF NOT EXISTS challenge_room ON challenge(room, open);
CREATE INDEX IF NOT EXISTS player_room ON player(room, skeleton);
"""
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


#: What a PostgreSQL store needs (the department extra), and the line saying so.
DEPARTMENT_MODULES = ("psycopg", "psycopg_pool")
NEEDS_DEPARTMENT = (
    "evapcool class --db postgresql://... needs the department extra: "
    "pip install 'evapcool[department]'"
)


def is_url(text: str) -> bool:
    """Whether a --db value names a PostgreSQL database (else a SQLite file)."""
    return text.startswith(("postgresql://", "postgres://"))


class NameTakenError(Exception):
    """A name that looks like another player's (`name`: the one it clashes with)."""

    def __init__(self, name: str) -> None:
        super().__init__(f"name: looks like {name!r}")
        self.name = name


class ClassFullError(Exception):
    """No more players: the class has its bound."""


def csv_cell(value: object) -> str:
    """A CSV cell a spreadsheet shows as text, never runs as a formula."""
    text = str(value)
    return "'" + text if text.startswith(FORMULA_START) else text


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


#: A statement run in a transaction: (SQL with ? placeholders, parameters) -> its cursor.
Query = Callable[[str, Sequence[Any]], Any]
#: The rows of an entry of the room: entries of its challenges only.
IN_ROOM = "JOIN challenge c ON c.id = e.challenge WHERE e.id = ? AND c.room = ?"
#: Hidden when the entry or its player is (portable: no MAX(a, b) in PostgreSQL).
HIDDEN = "CASE WHEN e.hidden > p.hidden THEN e.hidden ELSE p.hidden END"


class SqlStore:
    """The class data, one committed transaction per call; the SQL is common to both
    databases (subclasses give the connection, the transaction and the row locks)."""

    shared = False
    #: The exception a duplicate key raises (a join code taken).
    duplicate: tuple[type[Exception], ...] = ()

    # -- what a database gives ----------------------------------------------------------------

    def _rows(self, sql: str, params: Sequence[Any] = ()) -> list[Any]:
        raise NotImplementedError

    def _tx(self) -> Any:
        """A context manager: a write transaction, yielding a Query."""
        raise NotImplementedError

    def _lock(self, q: Query, table: str, key: int) -> None:
        """Hold a row's lock to the transaction's end (SQLite holds the whole file)."""

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

    # -- helpers ---------------------------------------------------------------------------

    def _one(self, sql: str, params: Sequence[Any] = ()) -> Any:
        rows = self._rows(sql, params)
        return rows[0] if rows else None

    def _write(self, sql: str, params: Sequence[Any] = ()) -> int:
        with self._tx() as q:
            return int(q(sql, params).rowcount)

    # -- secrets (digests only): the single class's lecturer, its projector, the admin ---

    def secret(self, name: str) -> str | None:
        row = self._one("SELECT digest FROM secret WHERE name = ?", (name,))
        return None if row is None else str(row[0])

    def set_secret(self, name: str, digest: str) -> None:
        self._write(
            "INSERT INTO secret (name, digest) VALUES (?, ?) "
            "ON CONFLICT (name) DO UPDATE SET digest = excluded.digest",
            (name, digest),
        )

    # -- lecturers and classes ---------------------------------------------------------------

    def add_lecturer(self, name: str, digest: str) -> int:
        """A new lecturer, known by their token's digest; their id."""
        with self._tx() as q:
            row = q(
                "INSERT INTO lecturer (name, digest) VALUES (?, ?) RETURNING id", (name, digest)
            )
            return int(row.fetchone()[0])

    def lecturers(self) -> list[dict[str, Any]]:
        rows = self._rows(
            "SELECT l.id, l.name, COUNT(r.id) FROM lecturer l LEFT JOIN room r "
            "ON r.lecturer = l.id GROUP BY l.id, l.name ORDER BY l.id"
        )
        return [{"id": r[0], "name": r[1], "classes": r[2]} for r in rows]

    def lecturer_by_digest(self, digest: str) -> dict[str, Any] | None:
        row = self._one("SELECT id, name FROM lecturer WHERE digest = ?", (digest,))
        return None if row is None else {"id": row[0], "name": row[1]}

    def set_lecturer_digest(self, lecturer: int, digest: str) -> bool:
        """A lecturer's new token (the last one stops working); False if no such lecturer."""
        return self._write("UPDATE lecturer SET digest = ? WHERE id = ?", (digest, lecturer)) > 0

    def add_room(self, name: str, lecturer: int | None) -> dict[str, Any]:
        """A new class with a join code no other class has (the database's unique index)."""
        for _ in range(100):
            try:
                with self._tx() as q:
                    got = q(
                        "INSERT INTO room (code, name, lecturer, created) VALUES (?, ?, ?, ?) "
                        "RETURNING id",
                        (new_code(), name, lecturer, time.time()),
                    )
                    room = int(got.fetchone()[0])
                break
            except self.duplicate:
                continue
        else:  # pragma: no cover - 21**6 codes: only a nearly full server gets here
            raise RuntimeError("no free join code")
        made = self.room(room)
        assert made is not None
        return made

    def _ensure_default_room(self) -> None:
        """The single class's room (a file made before classes holds its data); two
        processes starting at once make it once."""
        with self._tx() as q:
            q(
                "INSERT INTO room (id, code, name, created) VALUES (?, ?, ?, ?) "
                "ON CONFLICT (id) DO NOTHING",
                (DEFAULT_ROOM, new_code(), "", time.time()),
            )

    def _rooms(self, where: str, params: Sequence[Any]) -> list[dict[str, Any]]:
        rows = self._rows(
            "SELECT r.id, r.code, r.name, r.lecturer, l.name, l.digest, r.created "
            f"FROM room r LEFT JOIN lecturer l ON l.id = r.lecturer {where} ORDER BY r.id",
            params,
        )
        return [dict(zip(ROOM_KEYS, row, strict=True)) for row in rows]

    def room(self, room: int) -> dict[str, Any] | None:
        found = self._rooms("WHERE r.id = ?", (room,))
        return found[0] if found else None

    def room_by_code(self, code: str) -> dict[str, Any] | None:
        found = self._rooms("WHERE r.code = ?", (code,))
        return found[0] if found else None

    def rooms(self, lecturer: int | None = None) -> list[dict[str, Any]]:
        """Every class (or a lecturer's), oldest first."""
        if lecturer is None:
            return self._rooms("", ())
        return self._rooms("WHERE r.lecturer = ?", (lecturer,))

    def showing(self, room: int) -> dict[str, Any] | None:
        """The replay on a room's projector (every process sees the same), or None."""
        return self._room_json(room, "showing")

    def set_showing(self, room: int, shown: dict[str, Any] | None) -> None:
        self._set_room_json(room, "showing", shown)

    def debrief_state(self, room: int) -> dict[str, Any] | None:
        """What a room's lecturer set the debrief to show (issue 36), or None."""
        return self._room_json(room, "debrief")

    def set_debrief_state(self, room: int, state: dict[str, Any] | None) -> None:
        self._set_room_json(room, "debrief", state)

    def _room_json(self, room: int, column: str) -> dict[str, Any] | None:
        row = self._one(f"SELECT {column} FROM room WHERE id = ?", (room,))
        if row is None or row[0] is None:
            return None
        doc: dict[str, Any] = json.loads(row[0])
        return doc

    def _set_room_json(self, room: int, column: str, doc: dict[str, Any] | None) -> None:
        text = None if doc is None else json.dumps(doc, sort_keys=True)
        self._write(f"UPDATE room SET {column} = ? WHERE id = ?", (text, room))

    # -- challenges ------------------------------------------------------------------------

    def open_challenge(
        self,
        settings: dict[str, object],
        seed: int,
        max_frames: int,
        attempts: int | None,
        closes_at: float | None = None,
        lost: bool = False,
        room: int = DEFAULT_ROOM,
    ) -> int:
        """A new open challenge (closing the room's other); closes_at in seconds since the
        epoch. lost: whether games that do not win are taken (ranked with 0 atoms)."""
        with self._tx() as q:
            self._lock(q, "room", room)
            q("UPDATE challenge SET open = 0 WHERE room = ? AND open = 1", (room,))
            got = q(
                "INSERT INTO challenge (settings, seed, max_frames, attempts, closes_at, lost, "
                "room) VALUES (?,?,?,?,?,?,?) RETURNING id",
                (
                    json.dumps(settings, sort_keys=True),
                    seed,
                    max_frames,
                    attempts,
                    closes_at,
                    int(lost),
                    room,
                ),
            )
            return int(got.fetchone()[0])

    def close_challenge(self, challenge: int) -> bool:
        """Close a challenge; whether it was open (so closing twice is harmless)."""
        return (
            self._write("UPDATE challenge SET open = 0 WHERE id = ? AND open = 1", (challenge,)) > 0
        )

    def due(self, now: float) -> list[tuple[int, int]]:
        """(room, challenge) of every open challenge whose time window has ended."""
        rows = self._rows(
            "SELECT room, id FROM challenge WHERE open = 1 AND closes_at IS NOT NULL "
            "AND closes_at <= ?",
            (now,),
        )
        return [(int(r[0]), int(r[1])) for r in rows]

    def open_one(self, room: int = DEFAULT_ROOM) -> dict[str, object] | None:
        """The room's open challenge (its time window may have passed), or None."""
        return self._challenge("WHERE room = ? AND open = 1", (room,))

    def latest(self, room: int = DEFAULT_ROOM) -> dict[str, object] | None:
        """The open challenge, else the last one opened, else None (the projector's)."""
        return self._challenge("WHERE room = ? ORDER BY open DESC, id DESC LIMIT 1", (room,))

    def challenge(self, challenge: int, room: int = DEFAULT_ROOM) -> dict[str, object] | None:
        """A challenge of the room by its id, or None."""
        return self._challenge("WHERE id = ? AND room = ?", (challenge, room))

    def challenges(self, room: int = DEFAULT_ROOM) -> list[dict[str, object]]:
        """Every challenge of the room, newest first, with its entries and players counted
        (the term's history)."""
        rows = self._rows(
            f"SELECT {', '.join('c.' + k for k in CHALLENGE_KEYS)}, COUNT(e.id), "
            "COUNT(DISTINCT e.player) FROM challenge c LEFT JOIN entry e ON e.challenge = c.id "
            f"WHERE c.room = ? GROUP BY {', '.join('c.' + k for k in CHALLENGE_KEYS)} "
            "ORDER BY c.id DESC",
            (room,),
        )
        out = []
        for row in rows:
            doc = self._challenge_doc(row[: len(CHALLENGE_KEYS)])
            out.append({**doc, "games": int(row[-2]), "students": int(row[-1])})
        return out

    def _challenge(self, where: str, params: Sequence[Any]) -> dict[str, object] | None:
        found = self._one(f"SELECT {', '.join(CHALLENGE_KEYS)} FROM challenge {where}", params)
        return None if found is None else self._challenge_doc(found)

    @staticmethod
    def _challenge_doc(found: Sequence[Any]) -> dict[str, object]:
        out = dict(zip(CHALLENGE_KEYS, found, strict=True))
        out["settings"] = json.loads(found[1])
        out["lost"] = bool(out["lost"])
        return out

    # -- players ---------------------------------------------------------------------------

    def join(
        self, raw_name: object, max_players: int | None = None, room: int = DEFAULT_ROOM
    ) -> str:
        """A new player's secret token for a cleaned name in a room.

        ValueError (no visible name), NameTakenError (looks like another player's of the
        room), ClassFullError (max_players already joined the room).
        """
        name = clean_name(raw_name)
        look = skeleton(name)
        token = secrets.token_urlsafe(16)
        with self._tx() as q:
            self._lock(q, "room", room)
            self._check_unique(q, look, None, room)
            count = q("SELECT COUNT(*) FROM player WHERE room = ?", (room,)).fetchone()[0]
            if max_players is not None and count >= max_players:
                raise ClassFullError()
            q(
                "INSERT INTO player (token, name, skeleton, room) VALUES (?, ?, ?, ?)",
                (token, name, look, room),
            )
        return token

    @staticmethod
    def _check_unique(q: Query, look: str, token: str | None, room: int) -> None:
        """NameTakenError if another player's name of the room (not `token`'s) has this look."""
        sql = "SELECT name FROM player WHERE room = ? AND skeleton = ?"
        params: tuple[Any, ...] = (room, look)
        if token is not None:
            sql, params = sql + " AND token <> ?", (*params, token)
        row = q(sql, params).fetchone()
        if row is not None:
            raise NameTakenError(str(row[0]))

    def players(self, room: int = DEFAULT_ROOM) -> int:
        return int(self._one("SELECT COUNT(*) FROM player WHERE room = ?", (room,))[0])

    def player_name(self, token: str, room: int = DEFAULT_ROOM) -> str | None:
        """The name of a player of the room (None: no such token in this room)."""
        row = self._one("SELECT name FROM player WHERE token = ? AND room = ?", (token, room))
        return None if row is None else str(row[0])

    def rename(self, entry: int, raw_name: object, room: int = DEFAULT_ROOM) -> str | None:
        """Rename the player of an entry (the lecturer's); None if there is no such entry.

        ValueError or NameTakenError as `join`.
        """
        name = clean_name(raw_name)
        look = skeleton(name)
        with self._tx() as q:
            self._lock(q, "room", room)
            row = q(f"SELECT e.player FROM entry e {IN_ROOM}", (entry, room)).fetchone()
            if row is None:
                return None
            self._check_unique(q, look, row[0], room)
            q("UPDATE player SET name = ?, skeleton = ? WHERE token = ?", (name, look, row[0]))
        return name

    def hide(self, entry: int, hidden: bool = True, room: int = DEFAULT_ROOM) -> bool:
        """Hide the player of an entry: all their entries, later ones too, leave the board
        (hidden=False: back on it, the lecturer's undo)."""
        player = self.entry_player(entry, room)
        if player is None:
            return False
        self._write("UPDATE player SET hidden = ? WHERE token = ?", (int(hidden), player))
        return True

    # -- entries ---------------------------------------------------------------------------

    def attempts(self, challenge: int, token: str) -> int:
        row = self._one(
            "SELECT COUNT(*) FROM entry WHERE challenge = ? AND player = ?", (challenge, token)
        )
        return int(row[0])

    def add_entry(
        self,
        challenge: int,
        token: str,
        score: int,
        frames: int,
        edition: str,
        code: str | None = None,
    ) -> int:
        """A verified entry, committed before this returns."""
        with self._tx() as q:
            got = q(
                "INSERT INTO entry (challenge, player, score, frames, edition, code) "
                "VALUES (?,?,?,?,?,?) RETURNING id",
                (challenge, token, score, frames, edition, code),
            )
            return int(got.fetchone()[0])

    def add_if_allowed(
        self,
        challenge: int,
        token: str,
        result: tuple[int, int, str, str, str],
        now: float,
        path: str | None = None,
    ) -> int | str:
        """The new entry's id, or the field refusing it: "challenge" (closed), "attempts",
        "code" (the same moves as another player's entry of this challenge: a copy).

        result: (score, frames, edition, code, moves key); path: the game's path (JSON text).
        One transaction holding the challenge's lock: the checks and the insert cannot
        interleave with another one's, in this process or another.
        """
        score, frames, edition, code, moves = result
        with self._tx() as q:
            self._lock(q, "challenge", challenge)
            row = q(
                "SELECT attempts FROM challenge WHERE id = ? AND open = 1 "
                "AND (closes_at IS NULL OR closes_at > ?)",
                (challenge, now),
            ).fetchone()
            if row is None:
                return "challenge"
            used = q(
                "SELECT COUNT(*) FROM entry WHERE challenge = ? AND player = ?", (challenge, token)
            ).fetchone()[0]
            if row[0] is not None and used >= row[0]:
                return "attempts"
            copied = q(
                "SELECT 1 FROM entry WHERE challenge = ? AND moves = ? AND player <> ?",
                (challenge, moves, token),
            ).fetchone()
            if copied is not None:
                return "code"
            got = q(
                "INSERT INTO entry (challenge, player, score, frames, edition, code, moves, path) "
                "VALUES (?,?,?,?,?,?,?,?) RETURNING id",
                (challenge, token, score, frames, edition, code, moves, path),
            )
            return int(got.fetchone()[0])

    def entries(self, challenge: int) -> list[dict[str, object]]:
        """Every entry of a challenge, hidden ones too, best first (the lecturer's list);
        `rank`: the place on the leaderboard of a student's best shown game, else None."""
        rows = self._all(challenge)
        places = self._places(rows)
        return [
            {
                **dict(zip(ENTRY_KEYS, (*row[:5], bool(row[6])), strict=True)),
                "rank": places.get(row[0]),
            }
            for row in rows
        ]

    def _all(self, challenge: int) -> list[EntryRow]:
        """Every entry of a challenge, best first (most atoms, fewest frames, earliest)."""
        rows: list[EntryRow] = [
            tuple(row)
            for row in self._rows(
                "SELECT e.id, p.name, e.score, e.frames, e.edition, e.player, "
                f"{HIDDEN} FROM entry e JOIN player p ON p.token = e.player "
                "WHERE e.challenge = ? ORDER BY e.score DESC, e.frames ASC, e.id ASC",
                (challenge,),
            )
        ]
        return rows

    @staticmethod
    def _places(rows: list[EntryRow]) -> dict[int, int]:
        """Entry id -> place on the leaderboard, for each student's best shown game."""
        shown = [row for row in _best(rows) if not row[6]]
        return {row[0]: place for place, row in enumerate(shown, 1)}

    def standing(self, challenge: int, token: str) -> dict[str, int | None]:
        """A student's games sent and accepted, their best score and place (None if none)."""
        rows = self._all(challenge)
        best = [row for row in _best(rows) if row[5] == token]
        places = self._places(rows)
        return {
            "used": sum(1 for row in rows if row[5] == token),
            "best": best[0][2] if best else None,
            "rank": places.get(best[0][0]) if best else None,
        }

    def entry_code(self, entry: int, room: int = DEFAULT_ROOM) -> tuple[str, str, int] | None:
        """(name, replay code, challenge) of an entry of the room, or None if there is none
        or no code."""
        row = self._one(
            "SELECT p.name, e.code, e.challenge FROM entry e JOIN player p ON p.token = e.player "
            f"{IN_ROOM} AND e.code IS NOT NULL",
            (entry, room),
        )
        return None if row is None else (str(row[0]), str(row[1]), int(row[2]))

    def best_games(self, challenge: int) -> list[dict[str, object]]:
        """Each shown student's best game, best first, with its place and its stored path
        (JSON text, None if stored before paths were): the debrief's curves."""
        shown = [row for row in _best(self._all(challenge)) if not row[6]]
        paths = dict(
            self._rows(
                "SELECT id, path FROM entry WHERE challenge = ? AND path IS NOT NULL",
                (challenge,),
            )
        )
        return [
            {
                "entry": row[0],
                "name": row[1],
                "score": row[2],
                "frames": row[3],
                "player": row[5],
                "rank": place,
                "path": paths.get(row[0]),
            }
            for place, row in enumerate(shown, 1)
        ]

    def entry_player(self, entry: int, room: int = DEFAULT_ROOM) -> str | None:
        """The token of the player of an entry of the room, or None."""
        row = self._one(f"SELECT e.player FROM entry e {IN_ROOM}", (entry, room))
        return None if row is None else str(row[0])

    def count_rejected(self, challenge: int) -> None:
        self._write("UPDATE challenge SET rejected = rejected + 1 WHERE id = ?", (challenge,))

    def leaderboard(self, challenge: int) -> list[tuple[int, str, int, int, str]]:
        """(entry id, name, best score, its frames, edition), best first, hidden left out.

        One row a player (two players may share a name), their best entry.
        """
        return [row[:5] for row in _best(self._all(challenge)) if not row[6]]

    def rank(self, challenge: int, token: str) -> int | None:
        """A player's place on the leaderboard (None if not on it)."""
        shown = [row for row in _best(self._all(challenge)) if not row[6]]
        for place, row in enumerate(shown, 1):
            if row[5] == token:
                return place
        return None

    def results_csv(self, challenge: int) -> str:
        """Every game accepted, best first, hidden ones marked: the rank on each student's
        best shown game, `best` on each student's best game (the lecturer grades from it)."""
        seed = self._one("SELECT seed FROM challenge WHERE id = ?", (challenge,))
        rows = self._all(challenge)
        places = self._places(rows)
        bests = {row[0] for row in _best(rows)}
        out = io.StringIO()
        writer = csv.writer(out)
        writer.writerow(CSV_HEADER)
        for entry, name, score, frames, edition, _, hidden in rows:
            writer.writerow(
                [
                    places.get(entry, ""),
                    csv_cell(name),
                    score,
                    frames,
                    seed[0] if seed else "",
                    edition,
                    entry,
                    "best" if entry in bests else "",
                    "hidden" if hidden else "",
                ]
            )
        return out.getvalue()


def _best(rows: list[EntryRow]) -> list[EntryRow]:
    """Each player's best entry, best first: (..., the player's token, hidden)."""
    best: dict[str, EntryRow] = {}
    for row in rows:  # a player's best shown entry, else their best hidden one
        have = best.get(row[5])
        if have is None or (have[6] and not row[6]):
            best[row[5]] = row
    return sorted(best.values(), key=lambda r: (-r[2], r[3], r[0]))


class Store(SqlStore):
    """One SQLite file in WAL mode, served by one process (rate buckets in its memory)."""

    duplicate = (sqlite3.IntegrityError,)

    def __init__(self, path: Path) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        self.db = sqlite3.connect(path, isolation_level=None, check_same_thread=False)
        self.db.execute("PRAGMA journal_mode=WAL")
        self.db.execute("PRAGMA synchronous=FULL")
        self.db.executescript(SCHEMA)
        self._add_columns()
        self.db.executescript(INDEXES)
        self.db.executescript(ROOM_SCHEMA)
        self._fill_skeletons()
        self._ensure_default_room()
        self.limiters: dict[str, RateLimiter] = {}

    def _add_columns(self) -> None:
        """Bring a file of an older schema up to this one (new columns only)."""
        for table, column, decl in ADDED_COLUMNS:
            have = {row[1] for row in self.db.execute(f"PRAGMA table_info({table})")}
            if column not in have:
                self.db.execute(f"ALTER TABLE {table} ADD COLUMN {column} {decl}")

    def _fill_skeletons(self) -> None:
        """The look of names stored before skeletons were (older files)."""
        rows = self.db.execute("SELECT token, name FROM player WHERE skeleton IS NULL")
        with self._tx() as q:
            for token, name in rows.fetchall():
                q("UPDATE player SET skeleton = ? WHERE token = ?", (skeleton(name), token))

    def close(self) -> None:
        self.db.close()

    def _rows(self, sql: str, params: Sequence[Any] = ()) -> list[Any]:
        return self.db.execute(sql, params).fetchall()

    @contextmanager
    def _tx(self) -> Iterator[Query]:
        """BEGIN IMMEDIATE: the file's write lock from the start (no upgrade deadlock)."""
        self.db.execute("BEGIN IMMEDIATE")
        try:
            yield self.db.execute
        except BaseException:
            self.db.execute("ROLLBACK")
            raise
        self.db.execute("COMMIT")

    def take(self, kind: str, key: str, rate: Rate) -> int:
        """0 if `key` may go now, else seconds to wait (buckets in memory: one process)."""
        limiter = self.limiters.get(kind)
        if limiter is None or limiter.rate != rate:
            limiter = self.limiters[kind] = RateLimiter(rate)
        return limiter.take(key)
