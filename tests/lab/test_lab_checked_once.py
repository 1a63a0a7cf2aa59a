"""The lab checks its parameters once and parses its schedule once (issue 26.2)."""

from __future__ import annotations

from evapcool import limits
from evapcool.game import autopilot
from evapcool.lab import schedule as schedule_module
from evapcool.lab.experiment import run_experiment


def test_a_named_strategy_is_read_once(monkeypatch):
    reads: list[str] = []
    load = autopilot.load_strategy

    def counting(name):
        reads.append(name)
        return load(name)

    monkeypatch.setattr(autopilot, "load_strategy", counting)
    parses: list[str] = []
    parse = schedule_module.parse_schedule

    def counting_parse(text):
        parses.append(text)
        return parse(text)

    monkeypatch.setattr("evapcool.lab.experiment.parse_schedule", counting_parse)
    run_experiment(n_atoms=20, frames=3, every=1, seed=1, schedule="demo", engine="reference")
    assert reads == ["demo"] and parses == ["demo"]


def test_each_parameter_is_range_checked_once(monkeypatch):
    calls: list[str] = []
    check = limits.Range.check

    def counting(self, name, value):
        calls.append(name)
        return check(self, name, value)

    monkeypatch.setattr(limits.Range, "check", counting)
    run_experiment(n_atoms=20, frames=2, every=1, seed=1, engine="reference")
    before_run = [c for c in calls if c != "dt" and c != "trap_height"]
    assert sorted(before_run) == sorted(set(before_run)), calls
    assert "n_atoms" in before_run and "atoms" not in before_run
