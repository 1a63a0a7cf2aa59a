"""`evapcool class admin` and `evapcool class --db` (issue 35): lecturers and classes from the
command line, bad input in one line naming the parameter, the missing extra named."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from classhelp import free_port

from evapcool.classroom import class_admin, class_cli
from evapcool.classroom.server import digest, open_store
from evapcool.classroom.store import NEEDS_DEPARTMENT
from evapcool.cli import main


def test_lecturers_and_classes_from_the_command_line(
    store_at: Path | str, capsys: pytest.CaptureFixture[str]
) -> None:
    db = ["class", "admin", "--db", str(store_at), "--url", "https://class.example.edu/"]
    assert main([*db, "token"]) == 0
    admin = re.search(r"https://class\.example\.edu/admin\?token=(\S+)", capsys.readouterr().out)
    assert main([*db, "lecturer", "Ada  Lovelace"]) == 0
    said = capsys.readouterr().out
    link = re.search(r"Lecturer (\d+) Ada Lovelace: .* (https://\S+/lecturer\?token=(\S+))", said)
    assert admin and link, said
    assert main([*db, "class", "Optics 1", "--lecturer", link.group(1)]) == 0
    made = re.search(
        r"join code (\w{6}), students join at https://class.example.edu/c/\1/",
        capsys.readouterr().out,
    )
    assert made
    assert main([*db, "list"]) == 0
    assert f"{made.group(1)}  Optics 1  (Ada Lovelace)" in capsys.readouterr().out
    store = open_store(store_at, 1)
    try:  # only digests are kept
        assert store.lecturer_by_digest(digest(link.group(3)))["name"] == "Ada Lovelace"  # type: ignore[index]
        assert store.secret("admin") == digest(admin.group(1))
    finally:
        store.close()
    assert main([*db, "relink", link.group(1)]) == 0
    capsys.readouterr()
    store = open_store(store_at, 1)
    try:
        assert store.lecturer_by_digest(digest(link.group(3))) is None  # the old link stopped
    finally:
        store.close()


@pytest.mark.parametrize(
    ("argv", "parameter"),
    [
        (["class", "Optics", "--lecturer", "9"], "--lecturer"),
        (["class", "Optics", "--lecturer", "x"], "--lecturer"),
        (["lecturer", "   "], "name"),
        (["relink", "9"], "ID"),
        (["frobnicate"], "COMMAND"),
    ],
)
def test_bad_admin_input_is_one_line_naming_it(
    tmp_path: Path, argv: list[str], parameter: str, capsys: pytest.CaptureFixture[str]
) -> None:
    try:
        status = main(["class", "admin", "--db", str(tmp_path / "d.sqlite"), *argv])
    except SystemExit as ended:
        status = int(ended.code or 0)
    assert status == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and parameter in err and err.startswith("evapcool class admin: error:")


def test_postgresql_without_the_extra_is_named(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(class_cli, "available", lambda module: not module.startswith("psycopg"))
    url = "postgresql://nobody@/nothing?host=/nonexistent"
    assert main(["class", "--port", str(free_port()), "--db", url]) == 2
    assert capsys.readouterr().err.strip() == NEEDS_DEPARTMENT
    monkeypatch.setattr(
        "evapcool.extras.available", lambda module: not module.startswith("psycopg")
    )
    assert class_admin.main(["--db", url, "list"]) == 2
    assert capsys.readouterr().err.strip() == NEEDS_DEPARTMENT


def test_an_unreachable_database_is_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("psycopg")
    url = "postgresql://nobody@/nothing?host=/nonexistent"
    assert main(["class", "--port", str(free_port()), "--db", url]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--db" in err
    # libpq's own reason (no socket there), not the pool's timeout after retrying
    assert '"/nonexistent/.s.PGSQL.5432"' in err and "pool" not in err
