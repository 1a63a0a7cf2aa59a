"""Each optional feature without its extra says in one line what to install (issue 16).

A missing package is simulated the way Python itself marks one: sys.modules[name] = None
makes importlib.util.find_spec return None and `import name` fail.
"""

from __future__ import annotations

import html
import re
import sys
import warnings

import pytest

from evapcool import Simulation
from evapcool.cli import main
from evapcool.extras import CoreMissingWarning, MissingExtraError, SlowEngineWarning, install_hint
from evapcool.lab import run_experiment


def _without(monkeypatch: pytest.MonkeyPatch, *modules: str) -> None:
    for name in modules:
        monkeypatch.setitem(sys.modules, name, None)


def _one_error_line(text: str, prefix: str, extra: str) -> None:
    lines = text.strip().splitlines()
    assert len(lines) == 1, text
    assert lines[0].startswith(prefix), text
    assert install_hint(extra) in lines[0]
    assert "Traceback" not in text


def _without_core(monkeypatch: pytest.MonkeyPatch) -> None:
    """As an sdist installed without a C compiler: no evapcool.physics._core."""
    from evapcool.physics import simulation

    _without(monkeypatch, "evapcool.physics._core")
    monkeypatch.setattr(simulation, "_said_core_missing", False)  # a fresh process


def _one_core_line(text: str, prefix: str) -> None:
    lines = text.strip().splitlines()
    assert len(lines) == 1, text
    assert lines[0].startswith(prefix), text
    assert "C compiler" in lines[0] and "Traceback" not in text


def test_lab_fast_engine_without_the_core_says_how_to_get_it(monkeypatch, capsys, tmp_path):
    _without_core(monkeypatch)
    out = tmp_path / "run.csv"
    status = main(["lab", "--engine", "fast", "--frames", "5", "--out", str(out)])
    assert status == 2
    _one_core_line(
        capsys.readouterr().err,
        "evapcool lab: error: the fast engine needs the compiled engine core",
    )
    assert not out.exists()


def test_lab_plot_without_matplotlib_is_refused_before_the_run(monkeypatch, capsys, tmp_path):
    _without(monkeypatch, "matplotlib")
    out, png = tmp_path / "run.csv", tmp_path / "run.png"
    # A run of a million frames: refused at once, so nothing is simulated or written.
    for theory in ([], ["--theory"]):
        args = ["lab", "--frames", "1000000", "--out", str(out), "--plot", str(png), *theory]
        assert main(args) == 2
        err = capsys.readouterr().err
        _one_error_line(err, "evapcool lab: error: --plot needs matplotlib", "lab")
        assert not out.exists() and not png.exists()
    with pytest.raises(
        MissingExtraError, match="^plot needs matplotlib.*" + re.escape(install_hint("lab"))
    ):
        run_experiment(frames=1_000_000, plot=png)


def test_bench_fast_without_the_core_is_one_line(monkeypatch, capsys):
    _without_core(monkeypatch)
    assert main(["bench", "--engine", "fast", "--quick"]) == 2
    _one_core_line(capsys.readouterr().err, "evapcool bench: error:")


def test_bench_section_without_the_core_is_skipped_saying_why(monkeypatch, capsys):
    _without_core(monkeypatch)
    assert main(["bench", "--only", "fast", "--quick"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("[fast] skipped: ") and "C compiler" in out
    assert len(out.strip().splitlines()) == 1


def test_many_atoms_without_the_core_warn_that_numpy_is_slow(monkeypatch):
    _without_core(monkeypatch)
    with pytest.warns(SlowEngineWarning, match=r"500 atoms without the compiled engine core"):
        sim = Simulation(n_atoms=500, radius=2.0, seed=1)
    assert sim.engine == "reference"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Simulation(n_atoms=49, radius=12.0, seed=1)  # the classic count: no word


def test_without_the_core_the_game_plays_on_the_reference_engine(monkeypatch):
    _without_core(monkeypatch)
    with pytest.warns(CoreMissingWarning, match="playing on the reference engine"):
        sim = Simulation.classic(seed=1)
    sim.advance(30.0)
    assert sim.engine == "reference" and sim.collision_count > 0


def test_without_the_core_the_applet_says_so_once_and_plays(monkeypatch, capsys, tmp_path):
    _without_core(monkeypatch)
    shot = tmp_path / "shot.png"
    folders = ["--data-dir", str(tmp_path / "d"), "--config-dir", str(tmp_path / "c")]
    assert main(["--frames", "30", "--screenshot", str(shot), *folders]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert err[0].startswith("evapcool: note: the compiled engine core is not")
    assert "reference engine" in err[0] and shot.exists()


def test_many_atoms_without_the_core_on_the_command_line_is_a_note(monkeypatch, capsys, tmp_path):
    _without_core(monkeypatch)
    out = tmp_path / "run.csv"
    args = ["lab", "--atoms", "500", "--radius", "2", "--frames", "1", "--out", str(out)]
    assert main(args) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("evapcool lab: note: the compiled engine core is not installed")
    notes = [line for line in err if "without the compiled engine core" in line]
    assert len(notes) == 1, err
    assert notes[0].startswith("evapcool lab: note: 500 atoms without the compiled engine core")
    assert out.exists()


def test_python_api_raises_missing_extra_error(monkeypatch):
    _without_core(monkeypatch)
    with pytest.raises(MissingExtraError, match=r"compiled engine core.*C compiler"):
        Simulation.classic(seed=1, engine="fast")
    assert issubclass(MissingExtraError, ImportError)


def test_result_plot_and_pandas_without_their_packages(monkeypatch):
    result = run_experiment(n_atoms=12, radius=8.0, frames=4, every=2, seed=1, engine="reference")
    _without(monkeypatch, "matplotlib", "pandas")
    with pytest.raises(MissingExtraError, match=re.escape(install_hint("lab"))):
        result.plot()
    with pytest.raises(MissingExtraError, match=r"pip install pandas"):
        result.to_pandas()
    page = result._repr_html_()  # the table still shows, with the line instead of the plot
    assert "<table>" in page and html.escape(install_hint("lab")) in page and "<img" not in page


@pytest.mark.parametrize(
    ("direct_url", "hint"),
    [
        (
            '{"url": "file:///home/mia/evapcool", "dir_info": {"editable": true}}',
            "pip install -e '/home/mia/evapcool[lab]'",
        ),
        (
            '{"url": "file:///tmp/dist/evapcool-0.9-cp311-linux_x86_64.whl", "archive_info": {}}',
            "pip install 'evapcool[lab]'",
        ),
        (
            '{"url": "file:///tmp/dist/evapcool-0.9.tar.gz", "archive_info": {}}',
            "pip install 'evapcool[lab]'",
        ),
        ('{"url": "file:///home/mia/evapcool", "dir_info": {}}', "pip install 'evapcool[lab]'"),
        (
            '{"url": "https://example.org/evapcool", "vcs_info": {"vcs": "git"}}',
            "pip install 'evapcool[lab]'",
        ),
        (None, "pip install 'evapcool[lab]'"),
    ],
)
def test_the_install_hint_follows_where_evapcool_came_from(
    monkeypatch: pytest.MonkeyPatch, direct_url: str | None, hint: str
) -> None:
    """A clone gets its folder (PEP 610's direct_url.json); a wheel, an archive or an index
    install the name, which keeps the installed evapcool (the wheel may be gone)."""
    from importlib import metadata

    class Installed:
        def read_text(self, name: str) -> str | None:
            return direct_url if name == "direct_url.json" else None

    monkeypatch.setattr(metadata, "distribution", lambda name: Installed())
    assert install_hint("lab") == hint
