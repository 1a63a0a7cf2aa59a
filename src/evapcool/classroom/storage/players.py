"""The players aggregate: a class's students, joined by a name unlike the others', renamed
and hidden by the lecturer."""

from __future__ import annotations

import secrets
from typing import Any

from evapcool.classroom.names import clean_name, skeleton
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.storage.base import IN_ROOM, ClassFullError, NameTakenError, Query, SqlBase


class PlayersStore(SqlBase):
    """A class's players."""

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

    def entry_player(self, entry: int, room: int = DEFAULT_ROOM) -> str | None:
        """The token of the player of an entry of the room, or None."""
        row = self._one(f"SELECT e.player FROM entry e {IN_ROOM}", (entry, room))
        return None if row is None else str(row[0])
