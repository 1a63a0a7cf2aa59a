"""The lab's files, command line and schedules: round trips, reproducibility, bad input."""

from __future__ import annotations

import io
import itertools
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool import limits
from evapcool.lab import COLUMNS, load_result, parse_schedule, run_experiment
from evapcool.lab.cli import main
from evapcool.lab.progress import Progress
from evapcool.physics.simulation import Simulation

# Small and quick: the game's 49 atoms, a falling rim, a few hundred frames.
SMALL = dict(n_atoms=49, frames=240, every=20, seed=7, schedule="400@0,150@240", engine="reference")


def _same(a, b) -> None:
    assert a.metadata == b.metadata
    assert set(a.columns) == set(COLUMNS) == set(b.columns)
    for c in COLUMNS:
        assert a.columns[c].dtype == b.columns[c].dtype, c
        assert np.array_equal(a.columns[c], b.columns[c]), c
    assert np.array_equal(a.final_energies, b.final_energies)


@pytest.fixture(scope="module")
def small_run():
    return run_experiment(**SMALL)


@pytest.mark.parametrize("ext", [".csv", ".json"])
def test_file_round_trip_is_exact(small_run, tmp_path, ext):
    path = tmp_path / f"run{ext}"
    small_run.save(path)
    _same(small_run, load_result(path))


def test_same_seed_reproduces_files_bit_for_bit(small_run, tmp_path):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    small_run.save(a)
    run_experiment(out=b, **SMALL)
    assert a.read_bytes() == b.read_bytes()
    ja, jb = tmp_path / "a.json", tmp_path / "b.json"
    small_run.save(ja)
    run_experiment(out=jb, **SMALL)
    assert ja.read_bytes() == jb.read_bytes()
    json.loads(ja.read_text())  # strict JSON, no NaN/Infinity tokens


def test_parameters_in_file_repeat_the_run(small_run, tmp_path):
    path = tmp_path / "run.json"
    small_run.save(path)
    again = run_experiment(**load_result(path).parameters)
    _same(small_run, again)
    # The command line can do the same from the file alone.
    out = tmp_path / "again.json"
    assert main(["--from", str(path), "--out", str(out)]) == 0
    assert out.read_bytes() == path.read_bytes()


def test_columns_are_consistent(small_run):
    r = small_run
    assert r.completed and r.metadata["version"] and r.parameters["seed"] == 7
    assert list(r.frame) == list(range(0, 241, 20))
    assert r.phase_space_density[0] == 1.0
    assert np.all(r.n_trapped + r.escaped == 49)
    assert np.all(np.diff(r.pair_collisions) >= 0) and np.all(np.diff(r.wall_collisions) >= 0)
    np.testing.assert_allclose(r.temperature * r.n_trapped, r.total_energy, rtol=1e-12)
    np.testing.assert_allclose(r.trap_height, 400.0 - 250.0 * r.frame / 240.0, rtol=1e-12)
    psd = r.n_trapped * r.temperature**-2.5
    np.testing.assert_allclose(r.phase_space_density, psd / psd[0], rtol=1e-12)
    assert len(r.final_energies) == r.n_trapped[-1]


def test_seed_is_drawn_and_recorded_when_not_given():
    r = run_experiment(n_atoms=3, radius=12.0, frames=2, every=1, engine="reference")
    again = run_experiment(**r.parameters)
    assert isinstance(r.parameters["seed"], int)
    assert np.array_equal(r.total_energy, again.total_energy)


def test_ctrl_c_leaves_a_valid_file_with_the_rows_so_far(tmp_path, monkeypatch):
    calls = {"n": 0}
    real = Simulation.advance

    def advance(self, dt):
        calls["n"] += 1
        if calls["n"] == 95:
            raise KeyboardInterrupt
        real(self, dt)

    monkeypatch.setattr(Simulation, "advance", advance)
    out = tmp_path / "partial.csv"
    status = main(
        [
            "--atoms",
            "49",
            "--frames",
            "300",
            "--every",
            "10",
            "--seed",
            "3",
            "--engine",
            "reference",
            "--out",
            str(out),
        ]
    )
    assert status == 130
    r = load_result(out)
    assert not r.completed and r.metadata["frames_done"] == 94
    assert list(r.frame) == list(range(0, 91, 10))


def test_checkpoints_and_callback_see_growing_results(tmp_path):
    seen = []
    out = tmp_path / "c.json"

    def on_record(res):
        seen.append(len(res))
        if len(seen) == 2:
            assert load_result(out).metadata["completed"] is False  # checkpoint on disk

    run_experiment(
        out=out,
        checkpoint_seconds=0.0,
        on_record=on_record,
        n_atoms=4,
        frames=6,
        every=2,
        seed=1,
        engine="reference",
    )
    assert seen == [2, 3, 4]
    assert load_result(out).completed


def test_cli_writes_csv_to_stdout_without_out(capsys):
    assert main(["--atoms", "5", "--frames", "3", "--every", "1", "--seed", "2"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("# evapcool lab results")
    assert ",".join(COLUMNS) in out.splitlines()


BAD = [
    (["--schedule", "-5"], "--schedule"),
    (["--schedule", "400@0,60@0"], "--schedule"),
    (["--schedule", "eta=-1"], "--schedule"),
    (["--schedule", "warm"], "--schedule"),
    (["--escape", "tunnel"], "--escape"),
    (["--tc-law", "box"], "--tc-law"),
    (["--atoms", "-3"], "--atoms"),
    (["--radius", "nan"], "--radius"),
    (["--every", "0"], "--every"),
    (["--engine", "warp"], "--engine"),
    (["--start", "thermal=-2"], "--start"),
    (["--atoms", "5000"], "--atoms"),
    (["--out", "/nonexistent-dir/x.csv"], "--out"),
    (["--out", "results.txt"], "--out"),
    (["--plot", "figure.pdf"], "--plot"),
    (["--bogus"], "--bogus"),
]


@pytest.mark.parametrize(("argv", "name"), BAD)
def test_bad_input_is_one_line_and_exit_2(argv, name, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main([*argv, "--frames", "5"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert name in err
    assert not list(tmp_path.iterdir())  # nothing written


def test_unwritable_directory_is_refused_before_running(tmp_path, capsys):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        probe = locked / "probe"
        try:
            probe.write_text("")
        except PermissionError:
            pass
        else:
            pytest.skip("running with permissions that ignore directory modes")
        assert main(["--out", str(locked / "r.csv"), "--frames", "5"]) == 2
        assert "--out" in capsys.readouterr().err
    finally:
        locked.chmod(0o700)


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(schedule="-1"),
        dict(escape="up"),
        dict(tc_law="3d"),
        dict(n_atoms=0),
        dict(frames=1.5),
        dict(gravity=-1.0),
        dict(warp=9),
    ],
)
def test_python_api_raises_value_error(kwargs):
    with pytest.raises(ValueError):
        run_experiment(**kwargs)


def test_progress_bar_only_on_a_terminal():
    class Tty(io.StringIO):
        def isatty(self):
            return True

    quiet = io.StringIO()
    p = Progress(10, stream=quiet)
    p.update(5, force=True)
    p.close()
    assert quiet.getvalue() == ""
    tty = Tty()
    p = Progress(10, stream=tty)
    p.update(5, force=True)
    p.close()
    assert "50.0%" in tty.getvalue() and "ETA" in tty.getvalue()


# -- schedules ----------------------------------------------------------------------

heights = st.floats(min_value=1e-3, max_value=1e6, allow_nan=False, allow_infinity=False)


@given(
    st.lists(
        st.tuples(heights, st.integers(0, 10**6)), min_size=1, max_size=8, unique_by=lambda p: p[1]
    )
)
@settings(max_examples=200, deadline=None)
def test_ramp_parses_and_interpolates(points):
    points = sorted(points, key=lambda p: p[1])
    s = parse_schedule(",".join(f"{h!r}@{f}" for h, f in points))
    assert s.kind == "ramp"
    for h, f in points:
        assert s.fixed_height(f) == pytest.approx(h, rel=1e-12)
    assert s.fixed_height(-1.0) == points[0][0]
    assert s.fixed_height(points[-1][1] + 5) == points[-1][0]
    lo, hi = min(h for h, _ in points), max(h for h, _ in points)
    for f in np.linspace(0, points[-1][1], 7):
        assert lo * (1 - 1e-12) <= s.fixed_height(f) <= hi * (1 + 1e-12)


@given(heights)
def test_constant_and_eta_parse(h):
    assert parse_schedule(repr(h)).fixed_height(123.0) == h
    if not limits.ETA.contains(h):  # the truncated law underflows below 1e-50 or so
        with pytest.raises(ValueError, match=r"^schedule"):
            parse_schedule(f"eta={h!r}")
        return
    s = parse_schedule(f"eta={h!r}")
    assert s.kind == "eta" and s.eta == h


@given(st.text(max_size=20))
@settings(max_examples=300)
def test_parser_accepts_or_raises_value_error_only(text):
    try:
        s = parse_schedule(text)
    except ValueError as exc:
        assert str(exc).startswith("schedule")  # names the parameter
    else:
        assert s.kind in ("ramp", "eta", "autopilot")  # autopilot: a strategy ('demo', a file)
        if s.kind == "ramp":
            assert all(h > 0 for _, h in s.points)
            assert all(f1 > f0 for (f0, _), (f1, _) in itertools.pairwise(s.points))
        elif s.kind == "eta":
            assert math.isfinite(s.eta) and s.eta > 0


@pytest.mark.parametrize(
    "text",
    [
        "400@10,300@5",
        "0",
        "-1@0",
        "400@-1",
        "eta=0",
        "eta=inf",
        "nan",
        "400@0,,60@9",
        "",
        "400 @ 0; 60 @ 9",
    ],
)
def test_malformed_schedules(text):
    with pytest.raises(ValueError, match="schedule must be"):
        parse_schedule(text)
