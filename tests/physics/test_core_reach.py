"""The reach rule written once in the core (core_out_of_reach, core/game.c) against its oracle,
the reference engine's readable `out_of_reach` (physics/reference.py), natively: the same
answer on random states near every threshold, and the page's shared cases fresh
(web/test/cases/reach.json, scripts/reach_cases.py).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scripthelp import load_script

from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN
from evapcool.physics.core import compiled
from evapcool.physics.model import REACH_NAMES, REACH_STUCK, REACH_STUCK_HERE, REACH_WITHIN
from evapcool.physics.reference import out_of_reach
from evapcool.physics.simulation import Simulation

ROOT = Path(__file__).resolve().parents[2]
pytestmark = pytest.mark.skipif(compiled() is None, reason="the compiled core is not built")


cases = load_script("reach_cases")
NEAR = st.sampled_from(cases.SCALES) | st.floats(0.3, 3.0)


@settings(max_examples=300, deadline=None)
@given(
    masses=st.lists(st.floats(0.5, 2.0), min_size=0, max_size=7),
    n_gone=st.integers(0, 60),
    aim=st.sampled_from(cases.AIMS),
    scale=NEAR,
    tc_scale=NEAR,
    height=st.floats(HEIGHT_MIN, HEIGHT_MAX),
    win=st.booleans(),
    won=st.booleans(),
)
def test_the_core_answers_as_the_readable_rule(
    masses, n_gone, aim, scale, tc_scale, height, win, won
) -> None:
    if not masses and not n_gone:
        n_gone = 1
    state = cases.reach_state(masses, n_gone, aim, scale, tc_scale, height, win, won)
    fast = Simulation.from_state(state, engine="fast")
    reference = Simulation.from_state(state, engine="reference")
    code = fast.out_of_reach(HEIGHT_MIN, height)
    assert code == reference.out_of_reach(HEIGHT_MIN, height)
    if won or not win:
        assert code == REACH_WITHIN
        return
    # The rule from the simulation's public numbers, with and without the trap's energy.
    n, energy, g = fast.n_trapped, fast.total_energy(), fast.gravity
    m = float(fast.masses.min()) if n else 1.0
    args = (n, energy, fast.critical_temperature, m * g * HEIGHT_MIN)
    assert code == out_of_reach(*args, trap_energy=m * g * height)
    # Without it (Game.lost): the same answer, but for "lower the trap", not a loss yet.
    assert out_of_reach(*args) == (REACH_WITHIN if code == REACH_STUCK_HERE else code)
    assert fast.out_of_reach(HEIGHT_MIN, HEIGHT_MIN) == out_of_reach(*args)


@settings(max_examples=200, deadline=None)
@given(masses=st.lists(st.floats(0.5, 2.0), min_size=2, max_size=7), n_gone=st.integers(0, 60))
def test_a_tie_to_the_last_bit_is_stuck_as_the_readable_rule_says(masses, n_gone) -> None:
    """E == m g H: no atom can leave (the rule's <=), in the core as in its oracle."""
    state = cases.reach_state(masses, n_gone, "escape", 1.0, 1.5, HEIGHT_MIN)
    fast = Simulation.from_state(state, engine="fast")
    reference = Simulation.from_state(state, engine="reference")
    n, energy, g = fast.n_trapped, fast.total_energy(), fast.gravity
    h = cases.tie(energy, float(fast.masses.min()), g)
    if h is None or energy / n < fast.critical_temperature:
        return
    for lowest, height, want in ((h, h, REACH_STUCK), (0.5 * h, h, REACH_STUCK_HERE)):
        assert fast.out_of_reach(lowest, height) == want
        assert reference.out_of_reach(lowest, height) == want


def test_the_shared_cases_are_the_readable_rules_and_the_cores() -> None:
    """web/test/cases/reach.json: fresh, every answer met, and the core gives each."""
    committed = cases.FIXTURE.read_text(encoding="utf-8")
    assert committed == cases.fixture_text(), "run python scripts/reach_cases.py"
    found = cases.cases()
    assert {c["reason"] for c in found} == set(REACH_NAMES)
    for c in found:
        fast = Simulation.from_state(c["state"], engine="fast")
        assert fast.out_of_reach(HEIGHT_MIN, c["height"]) == c["code"], c["case"]
