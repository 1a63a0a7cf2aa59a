"""Every validation message prints plain numbers, never NumPy's reprs (issue 25.2)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from evapcool import limits
from evapcool.game.highscores import HighScoreTable
from evapcool.game.settings import Settings, validate
from evapcool.physics.simulation import Simulation
from evapcool.physics.state import check_placement
from evapcool.physics.validation import check_bounds, check_start

f64, i64 = np.float64, np.int64
#: The high-score table refuses before it touches its file: any path does.
_TMP = Path("no-such-folder-evapcool")


def _message(call) -> str:
    with pytest.raises(ValueError) as info:
        call()
    return str(info.value)


def _state(x: list, y: list) -> dict:
    return {"atoms": {"x": x, "y": y, "vx": [0.0] * len(x), "vy": [0.0] * len(x)}}


CASES = {
    "Range.check float": lambda: limits.RADIUS.check("radius", f64(-1.5)),
    "Range.check integer": lambda: limits.N_ATOMS.check("n_atoms", i64(0)),
    "Range.check list": lambda: limits.RADIUS.check("radius", [f64(1.5), f64(2.5)]),
    "Simulation n_atoms": lambda: Simulation(n_atoms=i64(0)),
    "Simulation radius": lambda: Simulation(n_atoms=2, radius=f64(5000.0)),
    "Simulation per-atom mass": lambda: Simulation(
        n_atoms=2, positions=[[0, 10], [50, 30]], velocities=[[0, 0], [0, 0]], mass=[f64(1), -1]
    ),
    "Simulation trap_height": lambda: setattr(Simulation.classic(seed=1), "trap_height", f64(-4)),
    "Simulation advance": lambda: Simulation.classic(seed=1).advance(f64(-1.0)),
    "check_start outside": lambda: check_start(
        np.array([[f64(147.88399862804744), f64(69.10505)]]),
        np.zeros((1, 2)),
        np.array([12.0]),
        0.01,
    ),
    "check_start overlap": lambda: check_start(
        np.array([[0.0, 50.0], [f64(3.3), 51.0]]), np.zeros((2, 2)), np.array([12.0, 12.0]), 0.01
    ),
    "check_bounds speed": lambda: check_bounds(np.zeros((1, 2)), np.array([[f64(120.5), 0.0]])),
    "check_placement": lambda: check_placement(
        "state.atoms",
        np.array([100.0]),
        np.array([f64(1.5)]),
        np.array([12.0]),
        np.array([True]),
        f64(0.01),
        1e-9,
    ),
    "from_state outside": lambda: Simulation.from_state(_state([100.0], [1.5])),
    "from_state overlap": lambda: Simulation.from_state(_state([0.0, 1.0], [50.0, 50.5])),
    "from_state numpy value": lambda: Simulation.from_state(_state([f64(0.0)], [f64(-3.5)])),
    "settings n_atoms": lambda: validate(Settings(n_atoms=i64(10**6))),
    "settings radius": lambda: validate(Settings(radius=f64(0.5))),
    "high score": lambda: HighScoreTable(_TMP / "scores.json").add("x", i64(-1), 1.0),
    "high score seconds": lambda: HighScoreTable(_TMP / "scores.json").add("x", 3, f64(-1.0)),
}


@pytest.mark.parametrize("name", list(CASES))
def test_messages_print_plain_numbers(name):
    text = _message(CASES[name])
    assert "np." not in text and "float64" not in text and "int64" not in text, text
    assert len(text.splitlines()) == 1


def test_shown_numbers_as_python_prints_them():
    assert limits.shown(f64(1.5)) == "1.5"
    assert limits.shown(i64(7)) == "7"
    assert limits.shown(np.bool_(True)) == "True"
    assert limits.shown([f64(1.5), i64(2)]) == "[1.5, 2]"
    assert limits.shown(f64(147.88399862804744)) == "147.88399862804744"
