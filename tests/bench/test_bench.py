"""`evapcool bench`: its arguments, and a small run that prints its figures (issue 26.5)."""

from __future__ import annotations

import re

import pytest

from evapcool import bench
from evapcool.bench.physics import frame_times


@pytest.mark.parametrize(
    ("argv", "option"),
    [(["--only", "nosuch"], "--only"), (["--engine", "warp"], "--engine"), (["--frames", "3"], "")],
)
def test_bad_arguments_exit_2_with_one_line(argv, option, capsys) -> None:
    with pytest.raises(SystemExit) as exc:
        bench.main(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and option in err and "Traceback" not in err


def test_a_quick_physics_section_prints_its_figures(capsys) -> None:
    assert bench.main(["--only", "physics", "--quick", "--engine", "reference"]) == 0
    out = capsys.readouterr().out
    assert "[physics] classic start (49 atoms, R = 12, H = 450), engine=reference" in out
    m = re.search(r"median ([\d.]+) ms, p95 ([\d.]+) ms over 300 frames", out)
    assert m and 0.0 < float(m.group(1)) <= float(m.group(2))
    assert re.search(r"collisions: \d+ in 300 frames", out)


def test_frame_times_counts_the_collisions_of_the_frames_it_times() -> None:
    times, collisions, total = frame_times("reference", 20)
    assert len(times) == 20 and collisions > 0 and total == pytest.approx(sum(times))


def test_the_help_is_timed_open_in_a_language_and_english_comes_back(own_folders) -> None:
    from evapcool import i18n
    from evapcool.bench.applet import measure_help

    t = measure_help("ja", 3)
    assert len(t["drawing"]) == len(t["cpu"]) == 3
    assert (t["drawing"] > 0).all() and (t["cpu"] >= 0).all()
    assert i18n.active().locale == "en"
