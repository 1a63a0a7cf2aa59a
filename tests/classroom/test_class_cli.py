"""`evapcool class`'s command line: bad options in one line, the missing extra named."""

from __future__ import annotations

import socket
from pathlib import Path

import pytest
from classhelp import free_port

from evapcool.classroom import class_cli
from evapcool.cli import main
from evapcool.extras import install_hint
from evapcool.i18n import Catalog


@pytest.mark.parametrize(
    ("argv", "option"),
    [
        (["--port", "0"], "--port"),
        (["--port", "http"], "--port"),
        (["--workers", "0"], "--workers"),
        (["--public-url", "class.example.edu"], "--public-url"),
        (["--public-url", "ftp://class.example.edu"], "--public-url"),
        (["--public-url", "https://class.example.edu:99999"], "--public-url"),
        (["--public-url", "https://class.example.edu/?a=1"], "--public-url"),
        (["--public-url", "https://"], "--public-url"),
        (["--public-url", "https://example.edu/physics"], "--public-url"),
    ],
)
def test_bad_option_is_one_line_naming_it(
    argv: list[str], option: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as ended:
        main(["class", *argv])
    assert ended.value.code == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and option in err


def test_port_in_use_and_folder_as_data(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        assert main(["class", "--port", str(port), "--data", str(tmp_path / "c.db")]) == 2
    assert "--port" in capsys.readouterr().err
    assert main(["class", "--data", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--data" in err
    not_a_database = tmp_path / "notes.txt"
    not_a_database.write_text("not SQLite at all, " * 100)
    assert main(["class", "--port", str(free_port()), "--data", str(not_a_database)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--data" in err


def test_missing_extra_is_named(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(class_cli, "available", lambda module: module != "segno")
    assert main(["class"]) == 2
    assert capsys.readouterr().err.strip() == (
        f"evapcool class needs the class extra: {install_hint('class')}"
    )


@pytest.mark.parametrize("given", ["https://class.example.edu", "https://class.example.edu/"])
def test_the_links_printed_show_the_public_address(given: str) -> None:
    args = class_cli.build_parser().parse_args(["--public-url", given])
    lines = class_cli.links(Catalog("en"), args.public_url, "TOKEN", "c.sqlite")
    assert "https://class.example.edu/lecturer?token=TOKEN" in lines[0]
    assert "https://class.example.edu/" in lines[1] and "//" not in lines[1].split("edu", 1)[1]


def test_the_lan_command_is_this_one_with_lan_added() -> None:
    """The projector's fix for a loopback address keeps the port, the store and the mode;
    it drops --new-link (the lecturer's link holds) and a database's password."""
    argv = ["--port", "8766", "--db", "postgresql://ada:secret@db.example/class"]
    argv += ["--department", "--new-link", "--max-students", "300"]
    assert class_cli.lan_command(argv) == (
        "evapcool class --port 8766 --db postgresql://ada@db.example/class --department "
        "--max-students 300 --lan"
    )
    assert class_cli.lan_command(["--data", "my class.sqlite", "--lan"]) == (
        "evapcool class --data 'my class.sqlite' --lan"
    )


def test_help_lists_the_admin_command(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as ended:
        main(["class", "--help"])
    assert ended.value.code == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "evapcool class admin ..." in out and "evapcool class admin --help" in out
