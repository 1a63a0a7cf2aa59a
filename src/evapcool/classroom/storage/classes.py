"""The classes aggregate: the secrets' digests (the single class's lecturer, its projector,
the administrator), the lecturers, the classes (rooms) with their projector's replay and
their debrief's state."""

from __future__ import annotations

import json
import time
from collections.abc import Sequence
from typing import Any

from evapcool.classroom.rooms import DEFAULT_ROOM, new_code
from evapcool.classroom.storage.base import ROOM_KEYS, SqlBase

#: A retired lecturer's digest starts so (no SHA-256 hex digest does).
RETIRED = "retired:"
#: The mark of an archived class among the secrets: this and its id.
ARCHIVED = "archived:"


class ClassesStore(SqlBase):
    """Secrets, lecturers and classes."""

    def secret(self, name: str) -> str | None:
        row = self._one("SELECT digest FROM secret WHERE name = ?", (name,))
        return None if row is None else str(row[0])

    def set_secret(self, name: str, digest: str) -> None:
        self._write(
            "INSERT INTO secret (name, digest) VALUES (?, ?) "
            "ON CONFLICT (name) DO UPDATE SET digest = excluded.digest",
            (name, digest),
        )

    def add_lecturer(self, name: str, digest: str) -> int:
        """A new lecturer, known by their token's digest; their id."""
        with self._tx() as q:
            row = q(
                "INSERT INTO lecturer (name, digest) VALUES (?, ?) RETURNING id", (name, digest)
            )
            return int(row.fetchone()[0])

    def lecturers(self) -> list[dict[str, Any]]:
        rows = self._rows(
            "SELECT l.id, l.name, COUNT(r.id), l.digest FROM lecturer l LEFT JOIN room r "
            "ON r.lecturer = l.id GROUP BY l.id, l.name, l.digest ORDER BY l.id"
        )
        return [
            {"id": r[0], "name": r[1], "classes": r[2], "retired": r[3].startswith(RETIRED)}
            for r in rows
        ]

    def rename_lecturer(self, lecturer: int, name: str) -> bool:
        """A lecturer's new name; False if no such lecturer."""
        return self._write("UPDATE lecturer SET name = ? WHERE id = ?", (name, lecturer)) > 0

    def retire_lecturer(self, lecturer: int) -> bool:
        """A lecturer's link stops working (a digest no token has); their classes and
        records stay. A relink brings them back. False if no such lecturer."""
        return self.set_lecturer_digest(lecturer, f"{RETIRED}{lecturer}")

    def rename_room(self, room: int, name: str) -> bool:
        """A class's new name; False if no such class."""
        return self._write("UPDATE room SET name = ? WHERE id = ?", (name, room)) > 0

    def archived(self, room: int) -> bool:
        """Whether a class is archived (no new round; its records stay)."""
        return self.secret(f"{ARCHIVED}{room}") is not None

    def archived_rooms(self) -> set[int]:
        """Every archived class's id."""
        rows = self._rows("SELECT name FROM secret WHERE name LIKE ?", (ARCHIVED + "%",))
        return {int(r[0][len(ARCHIVED) :]) for r in rows}

    def set_archived(self, room: int, archived: bool) -> None:
        """Archive a class or bring it back (a mark beside the secrets: no new column)."""
        if archived:
            self.set_secret(f"{ARCHIVED}{room}", "1")
        else:
            self._write("DELETE FROM secret WHERE name = ?", (f"{ARCHIVED}{room}",))

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
