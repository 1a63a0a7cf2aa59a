"""The web edition's limits and refusals come from the Python edition (issue 25.1).

web/src/limits.json is limits.py's table (scripts/web_limits.py); web/test/cases/refusals.json
holds the Python edition's exact refusal of out-of-range states and parameters
(scripts/refusals.py), which web/test/refusals.test.ts demands word for word of the web engine.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from scripthelp import load_script

from evapcool import limits

ROOT = Path(__file__).resolve().parents[2]


def test_the_committed_limits_table_is_limits_py() -> None:
    web_limits = load_script("web_limits")
    committed = (ROOT / "web" / "src" / "limits.json").read_text(encoding="utf-8")
    assert committed == web_limits.table_text(), "run python scripts/web_limits.py"


def test_every_range_of_limits_py_is_in_the_table_entry_by_entry() -> None:
    table = json.loads((ROOT / "web" / "src" / "limits.json").read_text(encoding="utf-8"))
    ranges = {k: v for k, v in vars(limits).items() if isinstance(v, limits.Range)}
    assert set(table["ranges"]) == set(ranges)
    for name, rng in ranges.items():
        row = table["ranges"][name]
        high = math.inf if row["high"] == "inf" else row["high"]
        assert (row["low"], high, row["unit"], row["integer"]) == (
            rng.low, rng.high, rng.unit, rng.integer
        ), name  # fmt: skip
        assert (row["low_open"], row["inf_ok"]) == (rng.low_open, rng.inf_ok), name
    assert table["bounds"]["VELOCITY_MAX"] == limits.VELOCITY_MAX
    assert table["bounds"]["POSITION_MAX"] == limits.POSITION_MAX


def test_the_committed_refusals_are_the_python_editions() -> None:
    refusals = load_script("refusals")
    committed = (ROOT / "web" / "test" / "cases" / "refusals.json").read_text(encoding="utf-8")
    assert committed == refusals.fixture_text(), "run python scripts/refusals.py"


def test_the_refusals_name_the_limits_they_break() -> None:
    cases = json.loads((ROOT / "web" / "test" / "cases" / "refusals.json").read_text("utf-8"))
    messages = [c["message"] for c in cases["states"]]
    assert any(m.startswith("velocities must be at most 100 px/frame") for m in messages)
    assert any(m.startswith("positions must be within 1e+08 px") for m in messages)
    assert all("np." not in m and "float64" not in m for m in messages)
