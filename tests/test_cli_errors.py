"""Every command words its errors alike: one line 'evapcool[ COMMAND]: error: ...' on stderr,
exit status 2, no traceback (issue 16). The format lives in evapcool.about.error_line."""

from __future__ import annotations

import re

import pytest

from evapcool.about import error_line, note_line
from evapcool.cli import SUBCOMMANDS, main

#: One bad input per command (bad values, unknown options, impossible combinations).
BAD = {
    None: [["--atoms", "-3"], ["--bogus"], ["--screenshot", "x.png"], ["--speed", "9"]],
    "lab": [["--atoms", "0"], ["--bogus"], ["--schedule", "nonsense"], ["--out", "x.txt"]],
    "bench": [["--only", "nothing"], ["--bogus"]],
    "web": [["--bogus"], ["--copy", "{tmp}/no/such/folder/x.html"]],
    "sweep": [["--bogus"]],
    "optimize": [["--bogus"]],
    "verify": [["--bogus"], [], ["{tmp}"]],
    "class": [["--bogus"], ["--port", "0"], ["--workers", "x"], ["--data", "{tmp}"]],
}


def test_the_format():
    assert error_line(None, "x") == "evapcool: error: x"
    assert error_line("lab", "x") == "evapcool lab: error: x"
    assert note_line("bench", "x") == "evapcool bench: note: x"


def _cases():
    for command, argvs in BAD.items():
        if command is not None and command not in SUBCOMMANDS:
            continue
        for argv in argvs:
            yield pytest.param(command, argv, id=f"{command or 'evapcool'} {' '.join(argv)}")


@pytest.mark.parametrize(("command", "argv"), list(_cases()))
def test_bad_input_is_one_error_line(command, argv, capsys, tmp_path, monkeypatch):
    monkeypatch.setenv("EVAPCOOL_DATA_DIR", str(tmp_path / "data"))
    monkeypatch.setenv("EVAPCOOL_CONFIG_DIR", str(tmp_path / "config"))
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    full = ([command] if command else []) + argv
    try:
        status = main(full)
    except SystemExit as stop:  # argparse-based commands may exit from their parser
        status = stop.code
    assert status == 2
    lines = capsys.readouterr().err.strip().splitlines()
    prefix = f"evapcool {command}: error: " if command else "evapcool: error: "
    assert len(lines) == 1 and lines[0].startswith(prefix), lines
    assert re.search(r"\w", lines[0][len(prefix) :])
