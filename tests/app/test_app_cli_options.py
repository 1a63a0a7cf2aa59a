"""The applet's command line names its options from a table when a lower layer refuses a
value (issue 26.2): exit status 2, one line naming the option."""

from __future__ import annotations

import pytest

from evapcool.app import cli


def _run(argv, capsys, tmp_path, monkeypatch) -> tuple[int, list[str]]:
    monkeypatch.setenv("EVAPCOOL_DATA_DIR", str(tmp_path / "data"))
    monkeypatch.setenv("EVAPCOOL_CONFIG_DIR", str(tmp_path / "config"))
    status = cli.main(argv)
    return status, capsys.readouterr().err.strip().splitlines()


def test_every_name_in_the_table_is_an_option():
    options = {o for a in cli.build_parser()._actions for o in a.option_strings}
    assert set(cli._OPTION_OF.values()) <= options


@pytest.mark.parametrize(
    ("argv", "start"),
    [
        # the settings' fit test: more atoms than fit at the radius
        (["--atoms", "20000", "--radius", "20"], "evapcool: error: --atoms must be a whole number"),
        # the same test at the saved radius (12), which counts what the loader fits
        (["--atoms", "5000"], "evapcool: error: --atoms must be a whole number from 1 to"),
    ],
)
def test_a_refused_value_names_its_option(argv, start, capsys, tmp_path, monkeypatch):
    status, lines = _run([*argv, "--frames", "1"], capsys, tmp_path, monkeypatch)
    assert status == 2
    assert len(lines) == 1 and lines[0].startswith(start), lines
    assert "n_atoms" not in lines[0]
