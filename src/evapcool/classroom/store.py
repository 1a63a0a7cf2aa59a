"""The class server's data: challenges, players and verified entries in SQLite (WAL).

Standard library only, so the server (a later session) and its tests stand on it. Every
write commits before it returns: an entry acknowledged to a student survives a kill -9.
"""

from __future__ import annotations

import csv
import io
import json
import secrets
import sqlite3
import unicodedata
from pathlib import Path

NAME_MAX = 24
#: Bidirectional overrides and isolates: they can make a name read as another one.
BIDI_CONTROLS = frozenset("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069\u200e\u200f")
#: A CSV cell starting with one of these is a formula in spreadsheets.
FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
CSV_HEADER = ("rank", "name", "score", "frames", "seed", "edition")
NAME_EMPTY = "name: give 1 to {max} visible characters"

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
"""
#: Columns added after the first schema: (table, column, declaration); added when missing.
ADDED_COLUMNS = (
    ("challenge", "closes_at", "REAL"),
    ("entry", "code", "TEXT"),
)
CHALLENGE_KEYS = (
    "id",
    "settings",
    "seed",
    "max_frames",
    "attempts",
    "rejected",
    "closes_at",
    "open",
)
ENTRY_KEYS = ("entry", "name", "score", "frames", "edition", "hidden")


def clean_name(raw: object) -> str:
    """A display name: NFC, no control/format/bidi characters, 1..NAME_MAX; else ValueError."""
    if not isinstance(raw, str):
        raise ValueError(NAME_EMPTY.format(max=NAME_MAX))
    text = unicodedata.normalize("NFC", raw[: 4 * NAME_MAX])
    kept = "".join(
        ch for ch in text if ch not in BIDI_CONTROLS and unicodedata.category(ch)[0] != "C"
    )
    # Cut to NAME_MAX, then drop a space the cut left at the end (found by hypothesis).
    name = " ".join(kept.split())[:NAME_MAX].rstrip()
    if not name:
        raise ValueError(NAME_EMPTY.format(max=NAME_MAX))
    return name


def csv_cell(value: object) -> str:
    """A CSV cell a spreadsheet shows as text, never runs as a formula."""
    text = str(value)
    return "'" + text if text.startswith(FORMULA_START) else text


class Store:
    """One SQLite file in WAL mode; each method one committed transaction."""

    def __init__(self, path: Path) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        self.db = sqlite3.connect(path, isolation_level=None, check_same_thread=False)
        self.db.execute("PRAGMA journal_mode=WAL")
        self.db.execute("PRAGMA synchronous=FULL")
        self.db.executescript(SCHEMA)
        self._add_columns()

    def _add_columns(self) -> None:
        """Bring a file of an older schema up to this one (new columns only)."""
        for table, column, decl in ADDED_COLUMNS:
            have = {row[1] for row in self.db.execute(f"PRAGMA table_info({table})")}
            if column not in have:
                self.db.execute(f"ALTER TABLE {table} ADD COLUMN {column} {decl}")

    def close(self) -> None:
        self.db.close()

    def open_challenge(
        self,
        settings: dict[str, object],
        seed: int,
        max_frames: int,
        attempts: int | None,
        closes_at: float | None = None,
    ) -> int:
        """A new open challenge (closing any other); closes_at in seconds since the epoch."""
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            self.db.execute("UPDATE challenge SET open = 0")
            cur = self.db.execute(
                "INSERT INTO challenge (settings, seed, max_frames, attempts, closes_at) "
                "VALUES (?,?,?,?,?)",
                (json.dumps(settings, sort_keys=True), seed, max_frames, attempts, closes_at),
            )
        return int(cur.lastrowid or 0)

    def close_challenge(self, challenge: int) -> None:
        with self.db:
            self.db.execute("UPDATE challenge SET open = 0 WHERE id = ?", (challenge,))

    def open_one(self) -> dict[str, object] | None:
        """The open challenge (its time window may have passed), or None."""
        return self._challenge("WHERE open = 1")

    def latest(self) -> dict[str, object] | None:
        """The open challenge, else the last one opened, else None (the projector's)."""
        return self._challenge("ORDER BY open DESC, id DESC LIMIT 1")

    def _challenge(self, where: str) -> dict[str, object] | None:
        row = self.db.execute(f"SELECT {', '.join(CHALLENGE_KEYS)} FROM challenge {where}")
        found = row.fetchone()
        if found is None:
            return None
        out = dict(zip(CHALLENGE_KEYS, found, strict=True))
        out["settings"] = json.loads(found[1])
        return out

    def join(self, raw_name: object) -> str:
        """A new player's secret token for a cleaned name."""
        token = secrets.token_urlsafe(16)
        with self.db:
            self.db.execute("INSERT INTO player VALUES (?, ?)", (token, clean_name(raw_name)))
        return token

    def player_name(self, token: str) -> str | None:
        row = self.db.execute("SELECT name FROM player WHERE token = ?", (token,)).fetchone()
        return None if row is None else str(row[0])

    def attempts(self, challenge: int, token: str) -> int:
        row = self.db.execute(
            "SELECT COUNT(*) FROM entry WHERE challenge = ? AND player = ?", (challenge, token)
        ).fetchone()
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
        with self.db:
            cur = self.db.execute(
                "INSERT INTO entry (challenge, player, score, frames, edition, code) "
                "VALUES (?,?,?,?,?,?)",
                (challenge, token, score, frames, edition, code),
            )
        return int(cur.lastrowid or 0)

    def add_if_allowed(
        self, challenge: int, token: str, result: tuple[int, int, str, str], now: float
    ) -> int | str:
        """The new entry's id, or the field refusing it: "challenge" (closed), "attempts".

        One transaction: the check and the insert cannot interleave with another one.
        """
        score, frames, edition, code = result
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            row = self.db.execute(
                "SELECT attempts FROM challenge WHERE id = ? AND open = 1 "
                "AND (closes_at IS NULL OR closes_at > ?)",
                (challenge, now),
            ).fetchone()
            if row is None:
                return "challenge"
            if row[0] is not None and self.attempts(challenge, token) >= row[0]:
                return "attempts"
            cur = self.db.execute(
                "INSERT INTO entry (challenge, player, score, frames, edition, code) "
                "VALUES (?,?,?,?,?,?)",
                (challenge, token, score, frames, edition, code),
            )
        return int(cur.lastrowid or 0)

    def entries(self, challenge: int) -> list[dict[str, object]]:
        """Every entry of a challenge, hidden ones too, best first (the lecturer's list)."""
        rows = self.db.execute(
            "SELECT e.id, p.name, e.score, e.frames, e.edition, e.hidden FROM entry e "
            "JOIN player p ON p.token = e.player WHERE e.challenge = ? "
            "ORDER BY e.score DESC, e.frames ASC, e.id ASC",
            (challenge,),
        ).fetchall()
        return [dict(zip(ENTRY_KEYS, row, strict=True)) for row in rows]

    def entry_code(self, entry: int) -> tuple[str, str] | None:
        """(name, replay code) of an entry, or None if there is none or no code."""
        row = self.db.execute(
            "SELECT p.name, e.code FROM entry e JOIN player p ON p.token = e.player "
            "WHERE e.id = ? AND e.code IS NOT NULL",
            (entry,),
        ).fetchone()
        return None if row is None else (str(row[0]), str(row[1]))

    def count_rejected(self, challenge: int) -> None:
        with self.db:
            self.db.execute(
                "UPDATE challenge SET rejected = rejected + 1 WHERE id = ?", (challenge,)
            )

    def hide(self, entry: int) -> bool:
        """Hide an entry from the leaderboard; False if there is no such entry."""
        with self.db:
            cur = self.db.execute("UPDATE entry SET hidden = 1 WHERE id = ?", (entry,))
        return cur.rowcount > 0

    def leaderboard(self, challenge: int) -> list[tuple[int, str, int, int, str]]:
        """(entry id, name, best score, its frames, edition), best first, hidden left out.

        One row a player (two players may share a name), their best entry.
        """
        return [row[:5] for row in self._best(challenge)]

    def rank(self, challenge: int, token: str) -> int | None:
        """A player's place on the leaderboard (None if not on it)."""
        for place, row in enumerate(self._best(challenge), 1):
            if row[5] == token:
                return place
        return None

    def _best(self, challenge: int) -> list[tuple[int, str, int, int, str, str]]:
        """Each player's best visible entry, best first, with the player's token last."""
        rows = self.db.execute(
            "SELECT e.id, p.name, e.score, e.frames, e.edition, e.player FROM entry e "
            "JOIN player p ON p.token = e.player WHERE e.challenge = ? AND e.hidden = 0 "
            "ORDER BY e.score DESC, e.frames ASC, e.id ASC",
            (challenge,),
        ).fetchall()
        best: dict[str, tuple[int, str, int, int, str, str]] = {}
        for row in rows:
            best.setdefault(row[5], row)
        return list(best.values())

    def results_csv(self, challenge: int) -> str:
        seed = self.db.execute("SELECT seed FROM challenge WHERE id = ?", (challenge,)).fetchone()
        out = io.StringIO()
        writer = csv.writer(out)
        writer.writerow(CSV_HEADER)
        for rank, (_, name, score, frames, edition) in enumerate(self.leaderboard(challenge), 1):
            writer.writerow([rank, csv_cell(name), score, frames, seed[0] if seed else "", edition])
        return out.getvalue()
