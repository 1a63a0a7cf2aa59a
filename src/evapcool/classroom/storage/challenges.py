"""The challenges aggregate: opening and closing a class's challenges, their time windows,
the open, the latest and the past ones."""

from __future__ import annotations

import json
import time
from collections.abc import Sequence
from typing import Any

from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.storage.base import CHALLENGE_KEYS, SqlBase

#: A round closed before its window's end (or without one) keeps the time it closed: the
#: history says when each round ended.
_CLOSED_NOW = "closes_at = CASE WHEN closes_at IS NULL OR closes_at > ? THEN ? ELSE closes_at END"


class ChallengesStore(SqlBase):
    """A class's challenges."""

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
            now = time.time()
            q(
                f"UPDATE challenge SET open = 0, {_CLOSED_NOW} WHERE room = ? AND open = 1",
                (now, now, room),
            )
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
        """Close a challenge; whether it was open (so closing twice is harmless). Its
        closes_at becomes the time it closed, when that is before its window's end."""
        now = time.time()
        sql = f"UPDATE challenge SET open = 0, {_CLOSED_NOW} WHERE id = ? AND open = 1"
        return self._write(sql, (now, now, challenge)) > 0

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

    def entry_paths(self, challenge: int) -> dict[int, str | None]:
        """Every entry of a challenge -> its stored path (JSON text, None if stored before
        paths were): the round's exports."""
        rows = self._rows("SELECT id, path FROM entry WHERE challenge = ?", (challenge,))
        return {int(r[0]): r[1] for r in rows}

    def _challenge(self, where: str, params: Sequence[Any]) -> dict[str, object] | None:
        found = self._one(f"SELECT {', '.join(CHALLENGE_KEYS)} FROM challenge {where}", params)
        return None if found is None else self._challenge_doc(found)

    @staticmethod
    def _challenge_doc(found: Sequence[Any]) -> dict[str, object]:
        out = dict(zip(CHALLENGE_KEYS, found, strict=True))
        out["settings"] = json.loads(found[1])
        out["lost"] = bool(out["lost"])
        return out
