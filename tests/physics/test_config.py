"""SimulationConfig: each parameter checked once, at the boundary; below it, trusted
(issue 26.2)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from evapcool import limits
from evapcool.limits import ParameterError
from evapcool.physics import config as config_module
from evapcool.physics.config import SimulationConfig
from evapcool.physics.room import CLASSIC_ROOM
from evapcool.physics.simulation import Simulation

GOOD = dict(
    n_atoms=20,
    radius=12.0,
    mass=1.0,
    curvature=0.01,
    gravity=1 / 3,
    trap_height=400.0,
    room=CLASSIC_ROOM,
    seed=1,
    engine="reference",
    tc_exponent=2 / 3,
    escape="rim",
    record_events=False,
    win=True,
)

#: One bad value per parameter, and the name the refusal must carry.
BAD = [
    ("n_atoms", 0),
    ("radius", -1.0),
    ("mass", 1e9),
    ("curvature", 0.0),
    ("gravity", 100.0),
    ("trap_height", -5.0),
    ("room", (640, 672)),
    ("seed", -1),
    ("engine", "warp"),
    ("tc_exponent", 0.0),
    ("escape", "teleport"),
    ("record_events", "no"),
    ("win", 1),
]


@pytest.mark.parametrize(("name", "value"), BAD)
def test_a_bad_value_is_refused_once_with_its_name(name, value, monkeypatch):
    calls: list[str] = []
    check = limits.Range.check

    def counting(self, what, v):
        calls.append(what)
        return check(self, what, v)

    monkeypatch.setattr(limits.Range, "check", counting)
    with pytest.raises(ParameterError) as info:
        SimulationConfig.checked(**{**GOOD, name: value})
    assert info.value.parameter == name
    assert str(info.value).startswith(name + " ")
    assert calls.count(name) <= 1  # each range asked once


def test_every_parameter_is_checked_once_on_the_way_to_the_engine(monkeypatch):
    calls: list[str] = []
    check = limits.Range.check

    def counting(self, what, v):
        calls.append(what)
        return check(self, what, v)

    monkeypatch.setattr(limits.Range, "check", counting)
    sim = Simulation(**GOOD)
    assert sorted(calls) == sorted(set(calls))  # no name twice
    assert {"n_atoms", "radius", "trap_height"} <= set(calls)
    calls.clear()
    sim.advance(1.0)
    assert calls == ["dt"]


def test_from_config_trusts_the_config_it_is_given(monkeypatch):
    config = SimulationConfig.checked(**GOOD)
    # the engine-size check and the ranges are not asked again
    monkeypatch.setattr(config_module, "check_engine_size", _never)
    monkeypatch.setattr(limits.Range, "check", _never)
    sim = Simulation.from_config(config)
    assert sim.n_atoms == 20


def test_from_config_gives_the_same_start_as_the_keywords():
    a = Simulation.from_config(SimulationConfig.checked(**GOOD))
    b = Simulation(**GOOD)
    np.testing.assert_array_equal(a.positions, b.positions)
    a.advance(20.0)
    b.advance(20.0)
    assert a.to_state() == b.to_state()


def test_a_given_start_is_checked_as_it_joins():
    config = SimulationConfig.checked(**{**GOOD, "n_atoms": 2})
    with pytest.raises(ParameterError, match=r"^positions"):
        config.with_start([[0.0, 10.0]], [[0.0, 0.0]])
    with pytest.raises(ValueError, match=r"^positions must not overlap"):
        config.with_start([[0.0, 20.0], [1.0, 20.0]], np.zeros((2, 2)))
    ok = config.with_start([[0.0, 20.0], [40.0, 30.0]], np.zeros((2, 2)))
    assert Simulation.from_config(ok).n_trapped == 2
    fallback = replace(ok, engine="reference")
    assert Simulation.from_config(fallback).engine == "reference"


def _never(*args, **kwargs):
    raise AssertionError("checked again below the boundary")
