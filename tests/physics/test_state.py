"""The state JSON (physics/state.py, docs/state.md): exact resumption, defaults, bad states."""

from __future__ import annotations

import math

import numpy as np
import pytest

from evapcool import Simulation
from evapcool.physics.state import (
    json_text,
    number_text,
    parse_state,
    read_json,
    state_text,
    to_state,
)


@pytest.mark.parametrize("escape", ["rim", "knife"])
def test_save_load_go_on_is_going_on(engine: str, escape: str) -> None:
    straight = Simulation.classic(seed=4, engine=engine, escape=escape, record_events=True)
    saved = Simulation.classic(seed=4, engine=engine, escape=escape, record_events=True)
    straight.advance(12.5)
    saved.advance(12.5)
    resumed = Simulation.from_state(state_text(saved), engine=engine, record_events=True)
    assert state_text(resumed) == state_text(saved)
    for sim in (straight, resumed):
        sim.trap_height = 80.0
        sim.advance(300.0)
    assert resumed.event_log == straight.event_log[-len(resumed.event_log) :]
    assert state_text(resumed) == state_text(straight)
    assert resumed.won == straight.won


def test_mid_run_state_keeps_the_win_and_its_temperatures() -> None:
    sim = Simulation.classic(seed=1, engine="reference")
    sim.advance(5.0)
    sim.force_win()
    back = Simulation.from_state(sim.to_state(), engine="reference")
    assert back.won
    assert back.initial_temperature == sim.initial_temperature
    assert back.critical_temperature == sim.critical_temperature
    assert back.n_atoms == 49 and back.time == sim.time


def test_numbers_are_exact_text() -> None:
    for x in (0.1, 1 / 3, 1e-300, 5e-324, 1e17, -2.5, 400.0):
        assert float(number_text(x)) == x
    assert number_text(-0.0) == "-0" and math.copysign(1.0, read_json("-0")) == -1.0
    assert number_text(400.0) == "400" and number_text(1e-5) == "1.0000000000000001e-05"
    assert json_text({"a": [1.0, 2.5], "b": {"c": "x"}}) == (
        '{\n  "a": [1, 2.5],\n  "b": {\n    "c": "x"\n  }\n}'
    )
    with pytest.raises(ValueError, match="finite"):
        number_text(math.nan)


def test_infinite_rim_and_negative_zero_survive() -> None:
    sim = Simulation(1, positions=[[0.0, 50.0]], velocities=[[-0.0, 0.0]], trap_height=math.inf)
    state = read_json(state_text(sim))
    assert state["trap_height"] == "inf"
    back = Simulation.from_state(state)
    assert back.trap_height == math.inf
    assert math.copysign(1.0, back.velocities[0, 0]) == -1.0


def test_minimal_state_gets_defaults() -> None:
    sim = Simulation.from_state(
        {"atoms": {"x": [0, 30], "y": [10, 40], "vx": [1, 0], "vy": [0, 0]}}
    )
    assert sim.n_atoms == 2 and sim.trap_height == 400.0 and sim.escape_rule == "rim"
    assert list(sim.radii) == [12.0, 12.0] and sim.win_rule
    assert sim.initial_temperature == pytest.approx(sim.temperature)


def test_escaped_and_gone_atoms_keep_their_indices() -> None:
    sim = Simulation.classic(seed=5, engine="reference")
    sim.trap_height = 40.0
    sim.advance(60.0)
    state = to_state(sim)
    assert "escaped" in state["atoms"]["status"] or "gone" in state["atoms"]["status"]
    back = Simulation.from_state(state)
    assert back.n_atoms == 49 and back.n_trapped == sim.n_trapped
    assert back.n_escaped == sim.n_escaped
    np.testing.assert_array_equal(back.trapped_indices, sim.trapped_indices)


GOOD = {"x": [0.0], "y": [10.0], "vx": [0.0], "vy": [0.0]}


@pytest.mark.parametrize(
    "state, name",
    [
        ({"atoms": {"x": [0], "y": [10], "vx": [0]}}, "state.atoms.vy"),
        ({"atoms": {**GOOD, "vy": [math.nan]}}, r"state.atoms.vy\[0\]"),
        ({"atoms": {**GOOD, "y": [-1.0]}}, "atom 0 .* outside the cup"),
        ({"atoms": {"x": [0, 5], "y": [10, 10], "vx": [0, 0], "vy": [0, 0]}}, "atoms 0 and 1"),
        ({"time": 1.0, "atoms": {**GOOD, "t": [2.0]}}, r"state.atoms.t\[0\]"),
        ({"escape": "net", "atoms": GOOD}, "state.escape"),
        ({"format": "other", "atoms": GOOD}, "state.format"),
        ({"colour": 1, "atoms": GOOD}, "free of unknown fields"),
        ({"energy_sum": 5.0, "atoms": GOOD}, "state.energy_sum"),
        ({"window": [100, 100], "atoms": GOOD}, "state.window"),
        ({"atoms": {**GOOD, "radius": [-1.0]}}, r"state.atoms.radius\[0\]"),
        ({"atoms": {**GOOD, "status": ["lost"]}}, r"state.atoms.status\[0\]"),
        ({"pair_collisions": 1.5, "atoms": GOOD}, "state.pair_collisions"),
        ("{not json", "state must be JSON"),
        ([], "state must be"),
    ],
)
def test_bad_state_is_a_value_error_naming_the_field(state: object, name: str) -> None:
    with pytest.raises(ValueError, match=name):
        Simulation.from_state(state)


def test_overlap_names_the_first_offending_atoms() -> None:
    atoms = {
        "x": [-100.0, 0.0, 10.0, -90.0],
        "y": [200.0, 50.0, 55.0, 205.0],
        "vx": [0.0] * 4,
        "vy": [0.0] * 4,
    }
    with pytest.raises(ValueError, match="atoms 0 and 3 overlap"):
        parse_state({"atoms": atoms}) and Simulation.from_state({"atoms": atoms})
    # escaped atoms may be anywhere; touching atoms and centres on the wall are fine
    atoms["status"] = ["escaped", "trapped", "escaped", "trapped"]
    assert Simulation.from_state({"atoms": atoms}).n_trapped == 2


def test_a_condensate_may_overlap() -> None:
    # after the win, atoms no longer collide with each other: a won state may overlap
    atoms = {"x": [0.0, 5.0], "y": [10.0, 10.0], "vx": [0.0, 0.0], "vy": [0.0, 0.0]}
    with pytest.raises(ValueError, match="atoms 0 and 1 overlap"):
        Simulation.from_state({"atoms": atoms})
    sim = Simulation.from_state({"won": True, "atoms": atoms}, engine="reference")
    sim.advance(30.0)
    assert sim.won and sim.pair_collision_count == 0
    with pytest.raises(ValueError, match=r"atom 0 .* outside the cup"):
        Simulation.from_state({"won": True, "atoms": {**atoms, "y": [-1.0, 10.0]}})
