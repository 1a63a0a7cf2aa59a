"""`evapcool class admin` does everything the administrator's page does (issue 45): rename,
retire and relink a lecturer, rename, archive and bring back a class (named by its join
code or its number), each run as its own process on the data file a running department
server uses; the store and the server's administrator's page then show it. Bad input: one
line naming the parameter, exit 2, the store unchanged."""

from __future__ import annotations

import html
import os
import re
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from classhelp import SETTINGS, SRC, Server, start_server

from evapcool.classroom.server import open_store

URL = "https://class.example.edu"
ROUND = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "escape": SETTINGS.escape}


@pytest.fixture
def department(tmp_path: Path) -> Iterator[Server]:
    running = start_server(tmp_path / "department.sqlite", extra=("--department",))
    yield running
    running.stop()


def admin(data: Path | str, *argv: str) -> subprocess.CompletedProcess[str]:
    """`evapcool class admin --db data --url URL argv...` as a process of its own."""
    env = {**os.environ, "PYTHONPATH": str(SRC), "LANG": "C.UTF-8", "LANGUAGE": "en"}
    cmd = [sys.executable, "-m", "evapcool", "class", "admin", "--db", str(data), "--url", URL]
    return subprocess.run(
        [*cmd, *argv], capture_output=True, text=True, env=env, timeout=120, check=False
    )


def said(data: Path | str, *argv: str) -> str:
    """What a command that must succeed prints."""
    done = admin(data, *argv)
    assert done.returncode == 0 and not done.stderr, (argv, done.stdout, done.stderr)
    return done.stdout


def page_row(server: Server, table: str, marker: str) -> str:
    """The row of the administrator's page's table that holds `marker` (its HTML)."""
    with httpx.Client(base_url=server.base, follow_redirects=True) as browser:
        text = browser.get("/admin", params={"token": server.token}).text
    body = text[text.index(f'id="{table}"') :]
    body = body[: body.index("</table>")]
    rows = [r for r in body.split("<tr>") if marker in r]
    assert len(rows) == 1, (marker, body[:2000])
    return html.unescape(rows[0])


Rows = list[dict[str, object]]


def store_view(data: Path | str) -> tuple[Rows, Rows, set[int]]:
    """The store's lecturers, classes and archived classes, read afresh."""
    store = open_store(data, 1)
    try:
        return store.lecturers(), store.rooms(), store.archived_rooms()
    finally:
        store.close()


def test_every_page_action_from_the_command_line(department: Server) -> None:
    data = department.data
    made = said(data, "lecturer", "Ada Lovelace")
    first = re.search(r"Lecturer 1 Ada Lovelace: .* \S+/lecturer\?token=(\S+)", made)
    assert first, made
    code = re.search(r"join code (\w{6})", said(data, "class", "Optics 1", "--lecturer", "1"))
    assert code, "no join code"
    room_code = code.group(1)

    assert said(data, "rename-lecturer", "1", "  Ada   King ").strip() == (
        "Lecturer 1 is now called Ada King."
    )
    # The code as a person types it: any case, a dash.
    typed = f"{room_code[:3].lower()}-{room_code[3:]}"
    assert said(data, "rename-class", typed, "Optik 2").strip() == (
        f"Class {room_code} is now called Optik 2."
    )
    lecturers, rooms, archived = store_view(data)
    assert [(r["id"], r["name"], r["retired"]) for r in lecturers] == [(1, "Ada King", False)]
    room = next(r for r in rooms if r["code"] == room_code)
    assert room["name"] == "Optik 2" and archived == set()
    assert "Ada King" in page_row(department, "lecturer-table", 'name="lecturer" value="1"')
    row = page_row(department, "class-table", room_code)
    assert "Optik 2" in row and "Ada King" in row and 'value="archive"' in row

    said(data, "archive", str(room["id"]))  # by its number, as `list` shows it
    assert store_view(data)[2] == {room["id"]}
    row = page_row(department, "class-table", room_code)
    assert "Archived" in row and 'value="unarchive"' in row
    assert f"{room['id']}  {room_code}  Optik 2  (Ada King)  [Archived]" in said(data, "list")
    refused = httpx.post(
        f"{department.base}/c/{room_code}/api/challenge",
        json=ROUND,
        headers={"Authorization": f"Bearer {first.group(1)}"},
    )
    assert refused.status_code == 409 and refused.json()["error"]["field"] == "class"
    said(data, "unarchive", room_code)
    assert store_view(data)[2] == set()
    assert 'value="archive"' in page_row(department, "class-table", room_code)

    lecturer_page = department.base + "/lecturer"
    assert httpx.get(lecturer_page, params={"token": first.group(1)}).status_code == 303
    said(data, "retire", "1")
    assert store_view(data)[0][0]["retired"] is True
    assert httpx.get(lecturer_page, params={"token": first.group(1)}).status_code == 403
    row = page_row(department, "lecturer-table", 'name="lecturer" value="1"')
    assert "Retired" in row and 'value="retire"' not in row
    assert "Lecturer 1: Ada King (Retired)" in said(data, "list")

    again = re.search(r"Lecturer 1 Ada King: .*/lecturer\?token=(\S+)", said(data, "relink", "1"))
    assert again, "no new link"
    assert store_view(data)[0][0]["retired"] is False
    assert httpx.get(lecturer_page, params={"token": again.group(1)}).status_code == 303
    assert httpx.get(lecturer_page, params={"token": first.group(1)}).status_code == 403
    # The class and its lecturer stayed through all of it.
    assert f"{room_code}  Optik 2  (Ada King)" in said(data, "list")


@pytest.mark.parametrize(
    ("argv", "parameter"),
    [
        (["rename-lecturer", "9", "Bo"], "ID"),
        (["rename-lecturer", "1", "   "], "name"),
        (["rename-lecturer", "1", "x" * 81], "name"),
        (["retire", "\u0661"], "ID"),  # an Arabic-Indic digit: ASCII digits only
        (["retire", "0"], "ID"),
        (["relink", "-1"], "ID"),
        (["rename-class", "AAAAAA", "Optik"], "CLASS"),  # a code no class has
        (["rename-class", "ABCDE0", "Optik"], "CLASS"),  # 0 and B are no code's
        (["archive", "x"], "CLASS"),
        (["archive", "999"], "CLASS"),  # a number no class has
        (["unarchive"], "CLASS"),
        (["class", "Optics", "--lecturer", "2"], "--lecturer"),
    ],
)
def test_bad_input_is_one_line_naming_the_parameter(
    tmp_path: Path, argv: list[str], parameter: str
) -> None:
    data = tmp_path / "department.sqlite"
    said(data, "lecturer", "Ada")
    said(data, "class", "Optics", "--lecturer", "1")
    before = store_view(data)
    done = admin(data, *argv)
    err = done.stderr.strip()
    assert done.returncode == 2 and done.stdout == "", (argv, done.stdout)
    assert "\n" not in err and err.startswith("evapcool class admin: error:"), err
    assert parameter in err, err
    assert store_view(data) == before
