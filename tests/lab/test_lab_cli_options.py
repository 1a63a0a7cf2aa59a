"""The lab's command line names its options from a table when the run refuses a value
(issue 26.2): exit status 2, one line naming the option."""

from __future__ import annotations

import pytest

from evapcool.lab import cli


def test_every_name_in_the_table_is_an_option():
    options = {o for a in cli.build_parser()._actions for o in a.option_strings}
    assert set(cli.OPTION_OF.values()) <= options


@pytest.mark.parametrize(
    ("argv", "start"),
    [
        (["--engine", "reference", "--atoms", "6000"], "--atoms must be at most 5000"),
        (["--frames", "1000000", "--every", "1"], "--every must be at least"),
        (["--schedule", "400@5,300@5"], "--schedule must be"),
        (["--tc-law", "cup", "--start", "thermal=0"], "--start must be"),
        (["--atoms", "100000", "--radius", "50"], "--atoms, --radius and --curvature: "),
    ],
)
def test_a_refused_value_names_its_option(argv, start, capsys):
    status = cli.main([*argv, "--frames", "2"] if "--frames" not in argv else argv)
    lines = capsys.readouterr().err.strip().splitlines()
    assert status == 2
    assert len(lines) == 1 and lines[0].startswith("evapcool lab: error: " + start), lines


def test_a_value_from_a_file_names_the_file(tmp_path, capsys):
    run = tmp_path / "run.json"
    assert cli.main(["--frames", "2", "--out", str(run)]) == 0
    capsys.readouterr()
    text = run.read_text().replace('"tc_law": "seed"', '"tc_law": "nonsense"')
    run.write_text(text)
    assert cli.main(["--from", str(run), "--frames", "2"]) == 2
    line = capsys.readouterr().err.strip()
    assert line.startswith(f"evapcool lab: error: --from {run}: tc_law must be one of"), line


def test_help_lists_the_engines(capsys):
    with pytest.raises(SystemExit):
        cli.main(["--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "physics engine: auto, reference, fast (default auto)" in text


@pytest.mark.parametrize("theory", [False, True])
def test_the_last_line_names_every_file_written(tmp_path, capsys, theory):
    """The summary comes last and names the CSV and the figure (issue 49.9)."""
    pytest.importorskip("matplotlib")
    out, plot = tmp_path / "run.csv", tmp_path / "run.png"
    argv = ["--atoms", "20", "--frames", "60", "--every", "10", "--seed", "1"]
    argv += ["--out", str(out), "--plot", str(plot)] + (["--theory"] if theory else [])
    assert cli.main(argv) in (0, cli.EXIT_NO_THEORY)
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert last.startswith("evapcool lab: 7 records, N 20 -> "), last
    assert last.endswith(f"; wrote {out} and {plot}"), last
    assert out.is_file() and plot.is_file()
