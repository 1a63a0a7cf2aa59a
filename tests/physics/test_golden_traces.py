"""The golden traces the web engine replays (web/test/golden/) still match the Python engines.

A physics change on one side cannot be forgotten on the other: if the engines' events change,
these tests fail until `python scripts/golden_traces.py write` is run and the web engine
replays the new traces bit for bit (`npm test` in web/).
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

from evapcool.physics.trace import read_trace, replay, trace_text

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "web" / "test" / "golden"


def _script():
    path = ROOT / "scripts" / "golden_traces.py"
    spec = importlib.util.spec_from_file_location("golden_traces", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


# The golden cases are test fixtures: they live with the script that writes their traces.
golden_trace = _script().golden_trace
CASES = {case.name: case for case in _script().GOLDEN_CASES}


def _is_trace(path: Path) -> bool:
    """Golden files of other kinds (starts, wins, messages) share the folder."""
    return '"format": "evapcool-trace"' in path.read_text(encoding="utf-8")[:200]


def test_the_committed_traces_are_the_cases() -> None:
    assert sorted(p.stem for p in GOLDEN.glob("*.json") if _is_trace(p)) == sorted(CASES)
    assert len(CASES) >= 8


@pytest.mark.parametrize("name", sorted(CASES))
def test_reference_engine_writes_the_committed_trace(name: str) -> None:
    committed = (GOLDEN / f"{name}.json").read_text(encoding="utf-8")
    fresh = trace_text(golden_trace(CASES[name]))
    assert fresh == committed, f"{name}: run `python scripts/golden_traces.py write {name}`"
    trace = read_trace(committed)
    assert len(trace["events"]) >= trace["events_requested"] == 2000


@pytest.mark.parametrize("name", sorted(CASES))
def test_fast_engine_replays_the_committed_trace(name: str) -> None:
    committed = (GOLDEN / f"{name}.json").read_text(encoding="utf-8")
    assert trace_text(replay(read_trace(committed), "fast")) == committed


def test_script_prints_the_trace_of_any_state(tmp_path, capsys) -> None:
    state = read_trace((GOLDEN / "two-atoms.json").read_text(encoding="utf-8"))["start"]
    from evapcool.physics.state import json_text

    path = tmp_path / "two.json"
    path.write_text(json_text(state), encoding="utf-8")
    assert _script().main(["run", str(path), "--events", "50"]) == 0
    trace = read_trace(capsys.readouterr().out)
    assert len(trace["events"]) == 50
    assert trace["case"] == "two"
    committed = read_trace((GOLDEN / "two-atoms.json").read_text(encoding="utf-8"))
    assert trace["events"] == committed["events"][:50]


def test_script_check_passes_and_reports_a_changed_trace(tmp_path, capsys) -> None:
    script = _script()
    for name in ("resting", "grazing"):
        (tmp_path / f"{name}.json").write_bytes((GOLDEN / f"{name}.json").read_bytes())
    assert script.main(["check", "--out", str(tmp_path), "resting", "grazing"]) == 0
    said = capsys.readouterr().out.strip().splitlines()
    assert said == [f"golden_traces: all 2 traces in {tmp_path} match the engines"]
    victim = tmp_path / "resting.json"
    victim.write_text(victim.read_text(encoding="utf-8").replace('"wall", 0', '"wall", 1', 1))
    assert script.main(["check", "--out", str(tmp_path), "resting", "grazing"]) == 1
    err = capsys.readouterr().err
    assert "resting" in err and "grazing" not in err


def test_script_bad_state_is_one_line(tmp_path, capsys) -> None:
    path = tmp_path / "bad.json"
    path.write_text('{"atoms": {"x": [0], "y": [-5], "vx": [0], "vy": [0]}}', encoding="utf-8")
    assert _script().main(["run", str(path), "--events", "5"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "outside the cup" in err
