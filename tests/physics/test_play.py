"""The game's clock written once in the core (core/play.c) against its readable oracle
(physics/play.py, the reference engine's): the same moves, win, score, heights, event log
and atoms, bit for bit, for any mix of display steps, heights asked, pauses and scripts.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.physics import core as core_module
from evapcool.physics.core import compiled
from evapcool.physics.model import CORE_MOVES_CAPACITY
from evapcool.physics.simulation import Simulation

pytestmark = pytest.mark.skipif(compiled() is None, reason="the compiled core is not built")

STEP = st.tuples(st.just("play"), st.sampled_from([0.25, 0.5, 0.7, 1.0, 1.5, 2.0, 3.3, 8.0]))
ASK = st.tuples(st.just("ask"), st.sampled_from([25.0, 60.0, 90.0, 150.0, 300.0, 450.0]))
NOW = st.tuples(st.just("now"), st.sampled_from([40.0, 120.0, 380.0]))
FINISH = st.tuples(st.just("finish"), st.just(0.0))
HOLD = st.tuples(
    st.just("hold"),
    st.lists(st.tuples(st.sampled_from([70.0, 200.0, 420.0]), st.integers(0, 4)), max_size=4),
)
WIN = st.tuples(st.just("win"), st.just(0.0))


def _sim(engine: str, seed: int, knife: bool) -> Simulation:
    escape = "knife" if knife else "rim"
    # The core's log as small as it goes (n + 8 lines): it fills within frames, and before a
    # knife at a whole frame, so play goes on from where it stopped many times a game.
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(core_module, "LOG_CAPACITY", 1)
        return Simulation(30, seed=seed, engine=engine, escape=escape, record_events=True)


def _act(sim: Simulation, action: tuple, heard: list) -> object:
    kind, value = action
    if kind == "play":
        return sim.play_to(sim.time + value, lambda h: heard.append((sim.time, h, sim.score)))
    if kind == "finish":
        return sim.play_to(math.floor(sim.time) + 1.0)
    if kind in ("ask", "now"):
        return sim.ask_height(value, kind == "now")
    if kind == "hold":
        return sim.hold(value)
    return sim.force_win()


@settings(max_examples=120, deadline=None)
@given(
    st.integers(0, 2**31),
    st.booleans(),
    st.lists(st.one_of(STEP, ASK, NOW, FINISH, HOLD, WIN), min_size=1, max_size=30),
)
def test_the_cores_clock_plays_as_its_oracle(seed: int, knife: bool, actions: list) -> None:
    sims = {e: _sim(e, seed, knife) for e in ("reference", "fast")}
    out: dict[str, list] = {}
    for engine, sim in sims.items():
        heard: list = []
        answers = [_act(sim, a, heard) for a in actions]
        out[engine] = [
            answers,
            heard,
            sim.moves(),
            sim.score,
            sim.win_frame,
            sim.asked_height,
            sim.trap_height,
            sim.time,
            sim.event_log,
            sim.to_state(),
        ]
    assert out["fast"] == out["reference"]


def test_a_full_log_stops_play_where_it_goes_on() -> None:
    """The small log of the test above fills: the core returns, is emptied, goes on."""
    sim = _sim("fast", 4, knife=True)
    sim.play_to(40.0)
    assert len(sim.event_log) > 3 * (30 + 8)


def test_moves_beyond_the_cores_buffer_are_all_kept() -> None:
    """More runs than the core keeps at once (CORE_MOVES_CAPACITY): taken, none lost."""
    sims = [Simulation(20, seed=5, engine=e, win=False) for e in ("reference", "fast")]
    want = [(450.0 - (k % 7), 1 + k % 3) for k in range(3 * CORE_MOVES_CAPACITY + 5)]
    for sim in sims:
        for height, frames in want:
            assert sim.ask_height(height, now=True)
            sim.play_to(sim.time + frames)
    assert sims[0].moves() == sims[1].moves() == want


def test_a_script_holds_from_the_start_and_refuses_the_player() -> None:
    for engine in ("reference", "fast"):
        sim = Simulation(20, seed=2, engine=engine, win=False)
        sim.play_to(2.0)
        sim.hold([(300.0, 3), (200.0, 2)])  # frames 0-2 at 300, 3-4 at 200: now frame 2
        assert sim.trap_height == 300.0 and not sim.ask_height(100.0, now=True)
        sim.play_to(4.0)
        assert sim.trap_height == 200.0
        sim.play_to(6.0)  # the script ended at frame 5: the player's again
        assert sim.ask_height(100.0) and sim.trap_height == 100.0
        assert sim.moves() == [(400.0, 2), (300.0, 1), (200.0, 3)]
