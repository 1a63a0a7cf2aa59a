"""Issue 18: every case the outside test found, as a regression test.

Inputs give finite, bounded work or one line naming the parameter (exit 2 / ValueError);
output paths are checked before a run; user files are set aside, never fatal or blocking.
"""

from __future__ import annotations

import json
import math
import os
import stat
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

from evapcool import Simulation
from evapcool.app import cli as app_cli
from evapcool.game.highscores import HighScoreTable
from evapcool.game.settings import DEFAULTS, load_settings
from evapcool.lab import cli as lab_cli
from evapcool.lab import experiment
from evapcool.lab.experiment import run_experiment
from evapcool.physics.room import Room

FIFO = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="POSIX FIFOs")
LINUX = pytest.mark.skipif(not Path("/proc/version").exists(), reason="Linux paths")


# -- inputs: Simulation ------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"gravity": 1e300}, "gravity"),
        ({"gravity": 1e308}, "gravity"),
        ({"mass": 1e308}, "mass"),
        ({"mass": [1.0, 1e308]}, "mass"),
        ({"n_atoms": 1_000_000_000_000}, "n_atoms"),
        ({"curvature": 1e-308}, "curvature"),
        ({"curvature": 1e308}, "curvature"),
        ({"radius": 1e-12}, "radius"),
        ({"radius": 3e-13}, "radius"),
        ({"radius": 1e308}, "radius"),
        ({"radius": 1e-300}, "radius"),
        ({"record_events": "no"}, "record_events"),
        ({"record_events": 1}, "record_events"),
        ({"win": "no"}, "win"),
        ({"engine": ["fast"]}, "engine"),
        ({"engine": np.array(["fast", "auto"])}, "engine"),
        ({"radius": "12"}, "radius"),
        ({"radius": [1, 2]}, "radius"),
        ({"seed": 2**70}, "seed"),
        ({"room": Room(296.0, 344.0, 128.0, 1e9)}, "room"),
        ({"n_atoms": 6000, "radius": 1.0, "engine": "reference"}, "n_atoms"),
    ],
)
def test_simulation_refuses_before_allocating(kwargs, name) -> None:
    with pytest.raises(ValueError, match=f"^{name}"):
        Simulation(**kwargs)


def test_a_velocity_of_1e300_is_refused() -> None:
    with pytest.raises(ValueError, match=r"^velocities"):
        Simulation(1, positions=[(0.0, 100.0)], velocities=[(1e300, 0.0)])


def test_huge_trap_heights_only_mean_no_escape() -> None:
    sim = Simulation.classic(seed=1, trap_height=1e308)
    sim.advance(30.0)
    assert sim.n_trapped == 49 and math.isfinite(sim.temperature)


@pytest.mark.parametrize("dt", [-1.0, math.nan, math.inf, 1e300, "1"])
def test_advance_is_bounded(dt) -> None:
    with pytest.raises(ValueError, match=r"^dt"):
        Simulation.classic(seed=1).advance(dt)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"checkpoint_seconds": math.nan}, "checkpoint_seconds"),
        ({"checkpoint_seconds": -1}, "checkpoint_seconds"),
        ({"progress": "yes"}, "progress"),
        ({"on_record": "print"}, "on_record"),
        ({"out": 5}, "out"),
        ({"stop_at_win": "no"}, "stop_at_win"),
        ({"gravity": 1e300}, "gravity"),
        ({"start": "thermal=1e308"}, "start"),
        ({"n_atoms": 6000, "radius": 1.0, "engine": "reference"}, "n_atoms"),
        ({"frames": 10**7, "every": 1}, "every"),
        ({"schedule": "eta=5e-324"}, "schedule"),  # found by the fuzz: a NaN height
        ({"schedule": "eta=1e308"}, "schedule"),
    ],
)
def test_run_experiment_refuses_before_simulating(kwargs, name, monkeypatch) -> None:
    monkeypatch.setattr(experiment, "_make_simulation", _never)
    with pytest.raises(ValueError, match=f"^{name}"):
        run_experiment(**{"frames": 3, **kwargs})


def _never(*args, **kwargs):
    raise AssertionError("the simulation started before the input was checked")


# -- inputs: the command lines -------------------------------------------------------------------
LAB_CASES = [
    (["--gravity", "1e300"], "--gravity"),
    (["--gravity", "1e308"], "--gravity"),
    (["--radius", "1e-12"], "--radius"),
    (["--radius", "3e-13"], "--radius"),
    (["--atoms", "1000000000000"], "--atoms"),
    (["--curvature", "1e-308"], "--curvature"),
    (["--radius", "1e308"], "--radius"),
    (["--radius", "1e-300"], "--radius"),
    (["--curvature", "1e308"], "--curvature"),
    (["--start", "thermal=1e308"], "--start"),
    (["--out", "x" * 300 + ".csv"], "--out"),
    (["--plot", "x" * 300 + ".png"], "--plot"),
    pytest.param(["--out", "/proc/version.csv"], "--out", marks=LINUX),
    pytest.param(["--plot", "/proc/version.png"], "--plot", marks=LINUX),
    (["--out", "existing.csv"], "--out"),  # a directory of that name, made below
    (["--out", "d" * 300 + "/r.csv"], "--out"),  # a folder name too long (found by the fuzz)
    (["--out", "existing.csv/sub/r.csv"], "--out"),
    (["--engine", "reference", "--atoms", "6000", "--radius", "0.5"], "--atoms"),
    (["--frames", "100000000", "--every", "1"], "--every"),
]


@pytest.mark.parametrize(("argv", "option"), LAB_CASES)
def test_lab_bad_input_exits_2_before_running(argv, option, tmp_path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "existing.csv").mkdir()
    monkeypatch.setattr(experiment, "_make_simulation", _never)
    assert lab_cli.main(["--frames", "5", *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and option in err and "Traceback" not in err
    assert [p.name for p in tmp_path.iterdir()] == ["existing.csv"]  # nothing written


APPLET_CASES = [
    (["--screenshot", "x" * 300 + ".png"], "--screenshot"),
    pytest.param(["--screenshot", "/proc/version.png"], "--screenshot", marks=LINUX),
    (["--screenshot", "shots.png"], "--screenshot"),  # a directory of that name
    (["--screenshot", "missing/x.png"], "--screenshot"),
    (["--screenshot", "d" * 300 + "/x.png"], "--screenshot"),
    (["--radius", "1e308"], "--radius"),
    (["--radius", "0.5"], "--radius"),
    (["--atoms", "1000000000000"], "--atoms"),
    (["--speed", "nan"], "--speed"),
    (["--seed", "-1"], "--seed"),
    (["--config-dir", "\x00"], "--config-dir"),  # found by the fuzz: a traceback
    (["--data-dir", "\x00"], "--data-dir"),  # found by the fuzz: the option was not named
]


@pytest.mark.parametrize(("argv", "option"), APPLET_CASES)
def test_applet_bad_input_exits_2_before_its_frames(
    argv, option, tmp_path, monkeypatch, capsys
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "shots.png").mkdir()
    from evapcool.app import applet

    monkeypatch.setattr(applet, "App", _never)  # the window and its frames never come
    with pytest.raises(SystemExit) as stop:
        app_cli.main(["--frames", "3", "--config-dir", str(tmp_path / "cfg"), *argv])
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and option in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["shots.png"]


def test_help_says_the_ranges_validation_uses(capsys) -> None:
    # Issue 14.13: --help said 3 to 20 px while 1 was accepted.
    with pytest.raises(SystemExit):
        app_cli.main(["--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "atom radius, 1 to 20 px" in text
    assert app_cli.build_parser().parse_args(["--radius", "1"]).radius == 1.0
    with pytest.raises(SystemExit):
        app_cli.build_parser().parse_args(["--radius", "0.99"])


# -- files ---------------------------------------------------------------------------------------
DEEP = "[" * 100_000 + "]" * 100_000


def test_deeply_nested_settings_are_set_aside_once(tmp_path, capfd) -> None:
    path = tmp_path / "settings.json"
    path.write_text(DEEP)
    s, notices = load_settings(path)
    assert s == DEFAULTS and len(notices) == 1 and "nested too deeply" in notices[0]
    assert "nested too deeply" in capfd.readouterr().err  # headless runs see it too
    assert not path.exists() and len(list(tmp_path.glob("settings.json.corrupt-*"))) == 1
    assert load_settings(path) == (DEFAULTS, [])  # every later start is clean


def test_deeply_nested_scores_are_set_aside_once(tmp_path, capfd) -> None:
    path = tmp_path / "highscores.json"
    path.write_text('{"entries": ' + DEEP + "}")
    table = HighScoreTable(path)
    notices = table.take_notices()
    assert table.entries == [] and len(notices) == 1 and "damaged" in notices[0]
    assert "damaged" in capfd.readouterr().err
    assert HighScoreTable(path).take_notices() == []


@pytest.mark.parametrize("content", [b"\xff\xfe{}", b"[]", b'"x"', b"{" * 50_000, b" " * (2 << 20)])
def test_any_damaged_settings_or_scores_file_is_set_aside(tmp_path, content) -> None:
    for name, load in (("settings.json", load_settings), ("highscores.json", HighScoreTable)):
        path = tmp_path / name
        path.write_bytes(content)
        load(path)
        assert not path.exists(), name


def _finishes(fn, *args) -> object:
    """fn(*args) in a thread; fails (instead of hanging the suite) if it blocks."""
    out: list[object] = []
    worker = threading.Thread(target=lambda: out.append(fn(*args)), daemon=True)
    worker.start()
    worker.join(10.0)
    assert out, f"{fn.__name__} blocked"
    return out[0]


@FIFO
def test_a_fifo_named_settings_json_does_not_block_the_start(tmp_path) -> None:
    path = tmp_path / "settings.json"
    os.mkfifo(path)
    s, notices = _finishes(load_settings, path)
    assert s == DEFAULTS and "not a regular file" in notices[0]
    assert path.exists()  # left alone


@FIFO
def test_a_fifo_named_highscores_json_does_not_block_the_start(tmp_path) -> None:
    path = tmp_path / "highscores.json"
    os.mkfifo(path)
    table = _finishes(HighScoreTable, path)
    assert table.entries == [] and "not a regular file" in table.take_notices()[0]
    assert _finishes(table.add, "Ada", 5, 1.0) == 1  # kept for the session...
    assert any("could not be saved" in n for n in table.take_notices())
    assert stat.S_ISFIFO(os.stat(path).st_mode)  # ...and the FIFO is left alone


FROM_CASES = {
    "list.json": "[]",
    "string.json": '"x"',
    "deep.json": DEEP,
    "no-parameters.json": '{"metadata": {}, "columns": {}}',
    "short-row.csv": "# evapcool lab results\n"
    "frame,n_trapped,temperature,critical_temperature,trap_height,total_energy,"
    "pair_collisions,wall_collisions,escaped,phase_space_density,won\n1,2\n",
    "no-header.csv": "# evapcool lab results\n",
    "empty.json": "",
    "words.csv": "just,some,words\n",
}


@pytest.mark.parametrize("name", sorted(FROM_CASES))
def test_lab_from_a_malformed_file_is_one_line_exit_2(name, tmp_path, capsys) -> None:
    path = tmp_path / name
    path.write_text(FROM_CASES[name])
    assert lab_cli.main(["--from", str(path), "--frames", "3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--from" in err and "Traceback" not in err


@FIFO
def test_lab_from_a_fifo_is_refused_without_blocking(tmp_path, capsys) -> None:
    path = tmp_path / "run.json"
    os.mkfifo(path)
    assert _finishes(lab_cli.main, ["--from", str(path)]) == 2
    assert "not a regular file" in capsys.readouterr().err


def test_lab_from_with_bad_recorded_parameters_names_the_file(tmp_path, capsys) -> None:
    result = run_experiment(n_atoms=5, frames=2, seed=1)
    path = tmp_path / "run.json"
    result.save(path)
    doc = json.loads(path.read_text())
    doc["metadata"]["parameters"]["gravity"] = 1e300
    path.write_text(json.dumps(doc))
    assert lab_cli.main(["--from", str(path)]) == 2
    assert f"--from {path}: gravity must be" in capsys.readouterr().err
    assert lab_cli.main(["--from", str(path), "--gravity", "0.5", "--frames", "2"]) == 0


# -- memory ---------------------------------------------------------------------------------------
_BIGGEST = """
import resource
from evapcool import Simulation
from evapcool.limits import REFERENCE_MAX_ATOMS
sim = Simulation(99_999, radius=0.35, engine="fast", seed=1)
sim.advance(0.05)
del sim
Simulation(REFERENCE_MAX_ATOMS, radius=1.0, engine="reference", seed=1)
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
"""


@pytest.mark.skipif(sys.platform != "linux", reason="VmHWM from /proc, in kB on Linux")
def test_the_largest_starts_below_100000_atoms_stay_under_1_gb() -> None:
    out = subprocess.run(
        [sys.executable, "-c", _BIGGEST], capture_output=True, text=True, timeout=600
    )
    assert out.returncode == 0, out.stderr
    assert int(out.stdout) * 1024 < 1e9


# -- bounded work of the lab's thermal start ----------------------------------------------------
def _thermal_cloud_all_pairs(n, radius, kt, gravity, curvature, rng, max_tries=1000):
    """The thermal start's positions as first written: every try against every placed atom."""
    lam = kt / gravity
    pos = np.empty((n, 2))
    for i in range(n):
        for _ in range(max_tries):
            y = rng.gamma(1.5, lam)
            x = rng.uniform(-1.0, 1.0) * math.sqrt(y / curvature)
            d = pos[:i] - (x, y)
            if i == 0 or np.min(d[:, 0] ** 2 + d[:, 1] ** 2) > (2.0 * radius) ** 2 * 1.0001:
                pos[i] = (x, y)
                break
        else:
            return None
    return pos


@pytest.mark.parametrize(
    ("n", "radius", "kt"), [(49, 12.0, 20.0), (400, 3.0, 5.0), (300, 12.0, 1.0), (60, 0.01, 1e-3)]
)
def test_thermal_start_is_the_same_cloud_in_linear_time(n, radius, kt) -> None:
    from evapcool.lab.theory import thermal_cloud

    expected = _thermal_cloud_all_pairs(n, radius, kt, 1 / 3, 0.01, np.random.default_rng(7))
    try:
        got, _ = thermal_cloud(n, radius, kt, rng=np.random.default_rng(7))
    except ValueError:
        got = None
    assert (got is None and expected is None) or np.array_equal(got, expected)


def test_a_ramp_has_at_most_1000_points(monkeypatch) -> None:
    monkeypatch.setattr(experiment, "_make_simulation", _never)
    ramp = ",".join(f"{400 - i * 0.1:g}@{i}" for i in range(1001))
    with pytest.raises(ValueError, match=r"^schedule must have at most 1000 points"):
        run_experiment(schedule=ramp, frames=3)


def test_a_data_folder_name_too_long_is_a_notice_not_a_crash(tmp_path, monkeypatch, capsys):
    # Found by the fuzz: Path.exists() raised ENAMETOOLONG in storage.folder_problem.
    monkeypatch.chdir(tmp_path)
    long = "w" * 300
    code = app_cli.main(["--frames", "1", "--data-dir", long, "--config-dir", long])
    assert code == 0 and "Traceback" not in capsys.readouterr().err


def test_a_fast_atom_grazing_the_wall_is_refused_above_the_speed_cap() -> None:
    # Found by the fuzz: at 650 px/frame one atom sliding from the vertex took the reference
    # engine minutes for a third of a frame (its hops leave at v_min, ~ v / v_min a slide).
    with pytest.raises(ValueError, match=r"^velocities must be at most 100 px/frame"):
        Simulation(1, positions=[(0.0, 0.0)], velocities=[(650.0, 0.0)])
    sim = Simulation(1, positions=[(0.0, 0.0)], velocities=[(100.0, 0.0)], trap_height=math.inf)
    sim.advance(1.0)
    assert 0 < sim.wall_collision_count < 2.6e5  # (1 + pi/2) v / v_min, bounded


# -- the documentation states the ranges limits.py holds -------------------------------------------
def test_the_docs_table_of_ranges_is_limits_py() -> None:
    import re

    from evapcool import limits

    page = Path(__file__).resolve().parents[1] / "docs" / "reliability.md"
    rows = re.findall(r"^\| `([A-Z_]+)` \| [^|]* \| ([^|]*) \|", page.read_text(), re.M)
    documented = {name: allowed.strip() for name, allowed in rows}
    ranges = {n for n, v in vars(limits).items() if isinstance(v, limits.Range)}
    assert set(documented) == ranges
    for name, allowed in documented.items():
        assert allowed == getattr(limits, name).span(), name


# -- lab files within the size cap but not what a lab writes ------------------------------------
def test_a_lab_file_of_more_values_than_a_run_holds_is_refused(tmp_path, capsys) -> None:
    # Found while measuring memory: 128 MB of "0," parsed to 1.2 GB (3.1 GB as CSV rows).
    from evapcool.lab.io import COLUMNS, CSV_MAGIC, VALUES_MAX
    from evapcool.limits import RECORDS_MAX

    row = ",".join(["0"] * len(COLUMNS))
    head = f'{CSV_MAGIC}\n# parameters: {{"atoms": 5}}\n{",".join(COLUMNS)}\n'
    cases = {
        "rows.csv": (head + (row + "\n") * (RECORDS_MAX + 1), "more than 100000 records"),
        "energies.json": (
            '{"metadata": {}, "final_energies": [' + "0," * VALUES_MAX + "0]}",
            "more values than a lab result holds",
        ),
    }
    for name, (text, why) in cases.items():
        (tmp_path / name).write_text(text)
        assert lab_cli.main(["--from", str(tmp_path / name)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and why in err, err
    (tmp_path / "ok.csv").write_text(head + (row + "\n") * RECORDS_MAX)
    from evapcool.lab.io import read_result

    assert len(read_result(tmp_path / "ok.csv")[1]["frame"]) == RECORDS_MAX


# The reader's own peak (VmHWM of its address space, in kB): ru_maxrss of a child carries the
# peak of the parent it was forked from (the whole suite's pytest, over 1 GB late in a run).
_BIG_FILE = """
import sys
from evapcool.lab.io import read_result
try:
    read_result(sys.argv[1])
except ValueError:
    pass
with open("/proc/self/status") as status:
    print(next(line.split()[1] for line in status if line.startswith("VmHWM:")))
"""


@pytest.mark.skipif(sys.platform != "linux", reason="ru_maxrss in KB on Linux")
def test_reading_a_lab_file_at_its_size_cap_stays_under_1_gb(tmp_path) -> None:
    from evapcool.limits import LAB_FILE_MAX_BYTES

    path = tmp_path / "zeros.json"
    head = '{"metadata": {}, "final_energies": ['
    path.write_text(head + "0," * ((LAB_FILE_MAX_BYTES - len(head)) // 2 - 2) + "0]}")
    assert path.stat().st_size <= LAB_FILE_MAX_BYTES
    out = subprocess.run(
        [sys.executable, "-c", _BIG_FILE, str(path)], capture_output=True, text=True, timeout=600
    )
    assert out.returncode == 0, out.stderr
    assert int(out.stdout) * 1024 < 1e9  # 1187 MB before the values were counted


def test_lab_csv_lines_are_split_as_before() -> None:
    from evapcool.lab.io import _lines

    for text in ("", "a", "a\n", "a\r\nb", "\n\nx\n", "a,b\r\n\r\n#c: 1\n"):
        assert list(_lines(text)) == text.splitlines()


# -- found by the long fuzz run (session 2) -------------------------------------------------------
def _strategy_files(tmp_path: Path) -> dict[str, str]:
    (tmp_path / "deep.json").write_text(DEEP)
    out = {"long name": "1" * 1500, "deep": str(tmp_path / "deep.json")}
    if hasattr(os, "mkfifo"):
        os.mkfifo(tmp_path / "fifo.json")
        out["fifo"] = str(tmp_path / "fifo.json")
    return out


def test_a_bad_autopilot_file_is_one_line_and_exit_2(tmp_path, monkeypatch, capsys) -> None:
    # A name too long for the file system was an OSError traceback; a FIFO blocked forever.
    from evapcool.app import applet

    monkeypatch.setattr(applet, "App", _never)
    for what, spec in _strategy_files(tmp_path).items():
        assert _finishes(app_cli.main, ["--frames", "2", "--autopilot", spec]) == 2, what
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "--autopilot" in err and "Traceback" not in err, err


def test_a_bad_schedule_file_is_one_line_and_exit_2(tmp_path, monkeypatch, capsys) -> None:
    monkeypatch.setattr(experiment, "_make_simulation", _never)
    for what, spec in _strategy_files(tmp_path).items():
        assert _finishes(lab_cli.main, ["--frames", "3", "--schedule", spec]) == 2, what
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "--schedule" in err, err


def test_lab_theory_without_three_records_is_refused_before_the_run(monkeypatch, capsys) -> None:
    # Found by the fuzz: `lab --theory --frames 3` ran, then exited 1 (2 records of 30 frames).
    monkeypatch.setattr(experiment, "_make_simulation", _never)
    assert lab_cli.main(["--theory", "--frames", "3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--theory needs a run of at least 3 records" in err
    assert lab_cli.main(["--theory", "--frames", "30", "--every", "31"]) == 2  # records 0, 30
    capsys.readouterr()
    monkeypatch.undo()
    assert lab_cli.main(["--theory", "--frames", "62", "--every", "31", "--atoms", "5"]) in (0, 1)


def test_an_autopilot_ramp_longer_than_a_file_name_plays(tmp_path, capsys) -> None:
    # A valid strategy text of 517 characters was asked whether it names a file: OSError.
    ramp = ",".join(f"{400 - i * 0.1:g}@{i}" for i in range(60))
    argv = ["--frames", "2", "--autopilot", ramp, "--config-dir", str(tmp_path)]
    assert app_cli.main([*argv, "--data-dir", str(tmp_path)]) == 0
    assert "Traceback" not in capsys.readouterr().err


@pytest.mark.parametrize("command", ["sweep", "optimize"])
def test_a_control_character_in_bad_arguments_stays_on_one_line(command, capsys) -> None:
    # Found by the fuzz: `evapcool sweep -- --csv '\n' --help` printed its error on two lines.
    from evapcool.cli import main

    assert main([command, "--", "--csv", "\n", "--help"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"evapcool {command}: error: "), err
