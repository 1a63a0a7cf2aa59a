"""A single-class SQLite file of the schema before classes (issue 35) opens as one class:
every challenge, player, entry and secret kept, the old links and tokens still working."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import httpx
import pytest
from classhelp import SEED, SETTINGS, code, start_server

from evapcool.classroom.server import LECTURER_SECRET, PROJECTOR_SECRET, digest, projector_key
from evapcool.classroom.store import INDEXES, SCHEMA, Store

#: The columns the single-class schema had gained (store.py's ADDED_COLUMNS before classes).
SINGLE_CLASS_COLUMNS = (
    ("challenge", "closes_at", "REAL"),
    ("entry", "code", "TEXT"),
    ("challenge", "lost", "INTEGER NOT NULL DEFAULT 0"),
    ("player", "skeleton", "TEXT"),
    ("player", "hidden", "INTEGER NOT NULL DEFAULT 0"),
    ("entry", "moves", "TEXT"),
    ("entry", "path", "TEXT"),
)
TOKEN = "the-lecturers-token-of-last-term"
#: The test game's settings as the server stored them.
SETTINGS_JSON = json.dumps(
    {"escape": "rim", "n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "tc_exponent": 2 / 3},
    sort_keys=True,
)


def single_class_file(path: Path) -> dict[str, int]:
    """A file as `evapcool class` wrote it before classes: two challenges (the last open),
    three students (one hidden), five games."""
    with sqlite3.connect(path) as db:
        db.executescript(SCHEMA)
        for table, column, decl in SINGLE_CLASS_COLUMNS:
            db.execute(f"ALTER TABLE {table} ADD COLUMN {column} {decl}")
        db.executescript(INDEXES)
        db.execute("INSERT INTO secret VALUES (?, ?)", (LECTURER_SECRET, digest(TOKEN)))
        db.execute(
            "INSERT INTO secret VALUES (?, ?)", (PROJECTOR_SECRET, digest(projector_key(TOKEN)))
        )
        for cid, is_open in ((1, 0), (2, 1)):
            db.execute(
                "INSERT INTO challenge (id, settings, seed, max_frames, attempts, open, rejected) "
                "VALUES (?, ?, ?, 20000, NULL, ?, ?)",
                (cid, SETTINGS_JSON, SEED, is_open, cid),
            )
        for token, name, hidden in (("tok-a", "Ann", 0), ("tok-b", "Ben", 1), ("tok-c", "Cat", 0)):
            db.execute(
                "INSERT INTO player (token, name, skeleton, hidden) VALUES (?, ?, ?, ?)",
                (token, name, name.lower(), hidden),
            )
        games = [
            (1, "tok-a", 30),
            (1, "tok-b", 31),
            (2, "tok-a", 20),
            (2, "tok-c", 25),
            (2, "tok-c", 26),
        ]
        for i, (cid, token, score) in enumerate(games, 1):
            db.execute(
                "INSERT INTO entry (id, challenge, player, score, frames, edition, code, moves) "
                "VALUES (?, ?, ?, ?, 900, 'web', ?, ?)",
                (i, cid, token, score, f"EC1.{i}", f"m{i}"),
            )
    return {"challenges": 2, "players": 3, "entries": len(games)}


def test_a_single_class_file_opens_as_one_class(tmp_path: Path) -> None:
    path = tmp_path / "class.sqlite"
    counts = single_class_file(path)
    store = Store(path)
    try:
        (room,) = store.rooms()
        assert room["id"] == 1 and room["lecturer"] is None and len(room["code"]) == 6
        assert [c["id"] for c in store.challenges()] == [2, 1]
        assert store.players() == counts["players"]
        assert len(store.entries(1)) + len(store.entries(2)) == counts["entries"]
        assert store.player_name("tok-b") == "Ben" and store.entry_code(3) == ("Ann", "EC1.3", 2)
        assert [r[1] for r in store.leaderboard(1)] == ["Ann"]  # Ben stays hidden
        assert store.secret(LECTURER_SECRET) == digest(TOKEN)
        assert store.open_one() is not None and store.open_one()["id"] == 2  # type: ignore[index]
    finally:
        store.close()
    again = Store(path)  # opening twice changes nothing more
    try:
        assert len(again.rooms()) == 1 and again.players() == counts["players"]
    finally:
        again.close()


@pytest.mark.parametrize("department", [False, True])
def test_the_old_links_work_on_the_migrated_file(tmp_path: Path, department: bool) -> None:
    path = tmp_path / "class.sqlite"
    single_class_file(path)
    extra = ("--department",) if department else ()
    server = start_server(path, token=TOKEN, extra=extra)
    try:
        lecturer = {"Authorization": f"Bearer {TOKEN}"}
        listed = httpx.get(server.base + "/api/entries", headers=lecturer).json()
        assert listed["challenge"]["id"] == 2 and len(listed["entries"]) == 3
        old = httpx.get(server.base + "/api/export.csv", params={"token": TOKEN, "challenge": 1})
        assert old.status_code == 200 and "Ben" in old.text
        me = httpx.get(server.base + "/api/me", headers={"Authorization": "Bearer tok-c"}).json()
        assert me["name"] == "Cat" and me["used"] == 2
        sent = httpx.post(
            server.base + "/api/submit",
            headers={"Authorization": "Bearer tok-a"},
            json={"challenge": 2, "code": code(SEED, 1)},
            timeout=60,
        )
        assert sent.status_code == 200, sent.text
    finally:
        server.stop()
