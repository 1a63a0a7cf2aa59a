"""The bundled demo keeps lowering the rim after its ramp until the gas condenses (issue 25.3).

Figures on 1 000 fresh seeds: scripts/demo_check.py, docs/benchmarks.md.
"""

from __future__ import annotations

import itertools

import pytest

from evapcool.game.autopilot import Policy, Reading, load_strategy, play
from evapcool.game.rules import HEIGHT_MIN

#: Seeds the demo without its guard did not win within 60 s (found in development, issue 25).
LOST_IN_60_S = (3000012, 3000021, 3000022)
#: The applet has no time limit; two minutes bound the games here.
NO_LIMIT = 3600


def _heights(policy: Policy, frames: range) -> list[float]:
    control = policy.controller()
    # A gas well above Tc all along: the guard's case.
    return [control(Reading(float(f), 60.0, 30.0, 25)) for f in frames]


def test_after_its_ramp_the_demo_lowers_the_rim_until_the_floor() -> None:
    demo = load_strategy("demo")
    assert isinstance(demo, Policy) and demo.params["rescue_rate"] > 0.0
    start = int(demo.params["rescue_from"]) + 1
    hs = _heights(demo, range(start, start + 3000))
    steps = [a - b for a, b in itertools.pairwise(hs) if b > HEIGHT_MIN]
    assert min(steps) >= demo.params["rescue_rate"] - 1e-9
    assert hs[-1] == HEIGHT_MIN
    unguarded = Policy("guarded", {**demo.params, "rescue_rate": 0.0})
    held = _heights(unguarded, range(start, start + 300))
    assert max(held) == min(held) > HEIGHT_MIN  # without the guard it would hold there


def test_before_its_frame_the_guard_changes_nothing() -> None:
    demo = load_strategy("demo")
    unguarded = Policy("guarded", {**demo.params, "rescue_rate": 0.0})
    early = range(0, int(demo.params["rescue_from"]))
    assert _heights(demo, early) == _heights(unguarded, early)


@pytest.mark.parametrize("seed", LOST_IN_60_S)
def test_the_demo_wins_where_it_used_to_run_out_of_time(seed: int) -> None:
    o = play(load_strategy("demo"), seed, NO_LIMIT)
    assert o.won and o.score > 0


@pytest.mark.slow
def test_the_demo_wins_on_200_fresh_seeds() -> None:
    demo = load_strategy("demo")
    lost = [s for s in range(5_000_000, 5_000_200) if not play(demo, s, NO_LIMIT).won]
    assert lost == []
