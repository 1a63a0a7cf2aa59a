"""The class data in one SQLite file in WAL mode (the embedded default: standard library
only): its schema, its migrations of older files, and its transactions."""

from __future__ import annotations

import sqlite3
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from evapcool.classroom.names import skeleton
from evapcool.classroom.ratelimit import Rate, RateLimiter
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.storage.base import Query
from evapcool.classroom.storage.sql import SqlStore

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
CREATE INDEX IF NOT EXISTS entry_moves_any ON entry(moves);
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
