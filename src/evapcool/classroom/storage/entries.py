"""The entries aggregate: the verified games (attempts), each student's best, the
leaderboard, a student's standing, the debrief's games, and the CSV of a challenge's games."""

from __future__ import annotations

import csv
import io

from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.storage.base import ENTRY_KEYS, HIDDEN, IN_ROOM, EntryRow, SqlBase
from evapcool.classroom.storage.copies import is_copy

#: A CSV cell starting with one of these is a formula in spreadsheets.
FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
#: One row per game sent and accepted: `rank` on each student's best shown game, `best`
#: marks each student's best game, `entry` is the game's number (the lecturer's page's).
CSV_HEADER = ("rank", "name", "score", "frames", "seed", "edition", "entry", "best", "hidden")


def csv_cell(value: object) -> str:
    """A CSV cell a spreadsheet shows as text, never runs as a formula."""
    text = str(value)
    return "'" + text if text.startswith(FORMULA_START) else text


class EntriesStore(SqlBase):
    """A challenge's entries and their rankings."""

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
        "code" (a win with the same moves as a verified game from the same start: a copy,
        copies.py; lost games, 0 atoms, are never copies).

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
            # A lost game (0 atoms) gains nothing copied, and two students may well lose
            # alike (the trap dropped at once): only wins are checked for copies.
            self._lock_moves(q, moves)  # two classes' same copy at once: one waits
            if score > 0 and is_copy(q, challenge, token, moves):
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
        """A student's games sent and accepted, their best score, its entry (the board's
        row the page finds itself by, names shown or not) and place (None if none)."""
        rows = self._all(challenge)
        best = [row for row in _best(rows) if row[5] == token]
        places = self._places(rows)
        return {
            "used": sum(1 for row in rows if row[5] == token),
            "best": best[0][2] if best else None,
            "best_entry": best[0][0] if best else None,
            "rank": places.get(best[0][0]) if best else None,
            "count": len(places),
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

    def count_rejected(self, challenge: int) -> None:
        self._write("UPDATE challenge SET rejected = rejected + 1 WHERE id = ?", (challenge,))

    def leaderboard(self, challenge: int) -> list[tuple[int, str, int, int, str]]:
        """(entry id, name, best score, its frames, edition), best first, hidden left out.

        One row a player (two players may share a name), their best entry.
        """
        return [row[:5] for row in _best(self._all(challenge)) if not row[6]]

    def leaderboard_players(self, challenge: int) -> list[tuple[int, str, int, int, str, str]]:
        """The leaderboard's rows with each one's player (their token) last."""
        return [row[:6] for row in _best(self._all(challenge)) if not row[6]]

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
