"""`win=False` / `--no-win`, and `result.theory()` / `--theory` from Python and the command line."""

from __future__ import annotations

import json

import numpy as np
import pytest

from evapcool.lab import load_result, run_experiment
from evapcool.lab.cli import OPTION_OF, main

# The game's 49 atoms under a falling knife cross Tc within a few hundred frames.
CROSSING = dict(
    n_atoms=49,
    frames=400,
    every=20,
    seed=4,
    schedule="400@0,60@400",
    escape="knife",
    engine="reference",
)
# A dilute constant-eta run long enough for the model's window (about 2 s).
EVAPORATION = dict(
    n_atoms=300,
    radius=0.5,
    escape="knife",
    schedule="eta=6",
    start="thermal=60",
    win=False,
    frames=400,
    every=20,
    seed=2,
    engine="fast",
)


def test_no_win_keeps_the_gas_a_gas_below_tc():
    game = run_experiment(**CROSSING)
    gas = run_experiment(win=False, **CROSSING)
    won = game.metadata["won_frame"]
    assert won is not None and game.frame[-1] == won  # the game's rule stops the run
    assert gas.metadata["won_frame"] is None and gas.frame[-1] == 400
    assert gas.parameters["win"] is False and game.parameters["win"] is True
    assert not np.any(gas.won)
    below = gas.temperature < gas.critical_temperature
    assert below[-1]  # below Tc, and still colliding, bouncing and evaporating
    after = np.flatnonzero(below)[0]
    assert gas.pair_collisions[-1] > gas.pair_collisions[after]
    assert gas.evaporated[-1] > gas.evaporated[after]
    # Up to the win the two runs are the same gas.
    k = len(game) - 1
    assert np.array_equal(gas.total_energy[:k], game.total_energy[:k])


def test_no_win_on_the_command_line_and_from_a_file(tmp_path, capsys):
    first = tmp_path / "gas.json"
    argv = ["--atoms", "49", "--frames", "400", "--every", "20", "--seed", "4"]
    argv += ["--schedule", "400@0,60@400", "--escape", "knife", "--engine", "reference"]
    assert main([*argv, "--no-win", "--out", str(first)]) == 0
    err = capsys.readouterr().err
    assert "(win rule off)" in err and "T < Tc from frame" in err
    assert load_result(first).parameters["win"] is False
    again = tmp_path / "again.json"
    assert main(["--from", str(first), "--out", str(again)]) == 0
    assert again.read_bytes() == first.read_bytes()  # --from honours win: false
    # A file written before the option existed has no "win": the game's rule applies.
    doc = json.loads(first.read_text())
    del doc["metadata"]["parameters"]["win"]
    old = tmp_path / "old.json"
    old.write_text(json.dumps(doc))
    replay = tmp_path / "replay.json"
    assert main(["--from", str(old), "--out", str(replay)]) == 0
    assert load_result(replay).metadata["won_frame"] is not None


def test_win_must_be_a_bool():
    with pytest.raises(ValueError, match="win must be True or False"):
        run_experiment(n_atoms=3, frames=2, win="no")


@pytest.fixture(scope="module")
def evaporation():
    return run_experiment(**EVAPORATION)


def test_theory_report_from_python(evaporation):
    report = evaporation.theory()
    symbols = [r.symbol for r in report.rows]
    assert symbols == ["Gamma_pair", "Gamma_ev/gamma_el", "kappa", "alpha"]
    # The window opens after 10 collisions per atom and runs to the end.
    per_atom = 2 * evaporation.pair_collisions / 300
    first = int(np.argmax(per_atom >= 10))
    assert report.first_frame == evaporation.frame[first]
    assert report.last_frame == evaporation.frame[-1]
    assert np.all(np.abs(report.track.eta[report.window] / 6.0 - 1) < 0.02)
    pair = report["Gamma_pair"]
    assert pair.ratio == pytest.approx(1.0, abs=0.03)  # ~2 % noise with one short run
    assert report["alpha"].predicted == pytest.approx(1.77, abs=0.03)  # dilute model: 1.766
    table = str(report)
    assert "Gamma_ev/gamma_el" in table and "kappa" in table and "measured" in table
    with pytest.raises(KeyError):
        report["nothing"]


def test_theory_on_the_command_line_prints_and_draws(tmp_path, capsys):
    out, png = tmp_path / "run.csv", tmp_path / "run.png"
    argv = []
    for key, value in EVAPORATION.items():
        if key == "win":
            argv.append("--no-win")
        else:
            argv += [OPTION_OF[key], str(value)]  # the command line's own table
    assert main([*argv, "--out", str(out), "--plot", str(png), "--theory"]) == 0
    printed = capsys.readouterr().out  # the table goes to stdout when the CSV is a file
    assert "Gamma_pair" in printed and "alpha" in printed
    assert printed == str(load_result(out).theory()) + "\n"
    assert png.stat().st_size > 10000


def test_plot_with_theory_draws_the_model(evaporation):
    plain = evaporation.plot()
    drawn = evaporation.plot(theory=True)
    assert len(plain.axes) == 4 and len(drawn.axes) == 6
    labels = [line.get_label() for ax in drawn.axes for line in ax.get_lines()]
    assert any(label.startswith("model, alpha") for label in labels)
    assert labels.count("model") == 1
    assert any(label.startswith("model: 2 (Gamma_ev") for label in labels)
    # The model's collision rate is drawn where the model applies, and close to the data.
    report = evaporation.theory()
    model = drawn.axes[4].get_lines()[1].get_ydata()
    np.testing.assert_allclose(model, report.track.pair_rate[report.window])


def test_theory_of_a_short_run_is_refused_in_one_line(tmp_path, capsys):
    out = tmp_path / "short.csv"
    argv = ["--atoms", "300", "--radius", "0.5", "--escape", "knife", "--schedule", "eta=6"]
    argv += ["--start", "thermal=60", "--frames", "30", "--every", "10", "--seed", "1"]
    assert main([*argv, "--out", str(out), "--theory"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("evapcool lab: error: --theory: theory needs")
    assert load_result(out).completed  # the run itself is written


def test_theory_of_a_rim_run_says_the_model_assumes_the_knife():
    r = run_experiment(**dict(EVAPORATION, escape="rim", schedule="1000"))
    report = r.theory()
    assert "assumes the knife" in str(report)
    assert report.rows[0].symbol == "Gamma_pair"
