"""The start, the game's frame and the replay written once in the core (core/start.c,
core/game.c), against their Python twins: the readable oracle and the fallback without the
compiled core (physics/start.py, loading.py, portable.py; Simulation.replay's
Python branch). Bit for bit, on many seeds and sizes, and on recorded games.
"""

from __future__ import annotations

import functools
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.game import replay as r
from evapcool.game.rules import Game, GameConfig
from evapcool.limits import ParameterError
from evapcool.physics import loading
from evapcool.physics.core import compiled
from evapcool.physics.portable import power
from evapcool.physics.simulation import Simulation

core = compiled()
pytestmark = pytest.mark.skipif(core is None, reason="the compiled core is not built")


def _core_start(n: int, radius: float, a: float, y_top: float, seed: int):
    pos, vel = np.empty((n, 2)), np.empty((n, 2))
    placed = core.load_cup(pos, vel, radius, a, y_top, seed)
    return placed, pos, vel


@settings(max_examples=150, deadline=None)
@given(
    st.integers(0, 2**53 - 1),
    st.integers(1, 3000),
    st.sampled_from([0.3, 1.0, 3.5, 7.25, 12.0, 20.0, 40.0]),
    st.sampled_from([0.0035, 0.006, 0.01, 0.02]),
    st.sampled_from([400.0, 532.0, 2000.0, 1e5]),
)
def test_the_core_starts_as_the_python_generator(seed, n, radius, a, y_top) -> None:
    try:
        want = loading.load_cup_reference(n, radius, a, y_top, seed)
    except ParameterError:
        want = None
    placed, pos, vel = _core_start(n, radius, a, y_top, seed)
    if want is None:
        assert 0 <= placed < n  # they do not fit: the core says how many do
        return
    assert placed == n
    assert pos.tobytes() == want[0].tobytes() and vel.tobytes() == want[1].tobytes()


def test_a_large_start_is_the_same_bits() -> None:
    want = loading.load_cup_reference(100_000, 0.35, 0.01, 543.0, seed=3)
    placed, pos, vel = _core_start(100_000, 0.35, 0.01, 543.0, 3)
    assert placed == 100_000
    assert pos.tobytes() == want[0].tobytes() and vel.tobytes() == want[1].tobytes()


def test_too_many_atoms_are_refused_alike_with_and_without_the_core(monkeypatch) -> None:
    with pytest.raises(ParameterError) as with_core:
        loading.load_cup(200, 12.0, 0.01, 400.0, seed=1)
    monkeypatch.setitem(sys.modules, "evapcool.physics._core", None)
    assert compiled() is None
    with pytest.raises(ParameterError) as without:
        loading.load_cup(200, 12.0, 0.01, 400.0, seed=1)
    assert str(with_core.value) == str(without.value)
    assert "at most" in str(without.value)


def test_without_the_core_the_python_generator_starts_the_game(monkeypatch) -> None:
    want = Simulation.classic(seed=77)
    monkeypatch.setitem(sys.modules, "evapcool.physics._core", None)
    pos, vel = loading.load_cup(49, 12.0, 0.01, 532.0, seed=77)
    assert np.array_equal(pos, want.positions) and np.array_equal(vel, want.velocities)


@pytest.mark.parametrize("radius", [0.5, 1.0, 3.0, 7.0, 12.0, 25.0, 40.0])
@pytest.mark.parametrize("a", [0.006, 0.01, 0.02])
def test_the_capacity_is_the_python_count(radius: float, a: float, monkeypatch) -> None:
    got = loading.capacity(radius, a, 400.0)
    monkeypatch.setitem(sys.modules, "evapcool.physics._core", None)
    assert got == loading.capacity(radius, a, 400.0) > 0


@settings(max_examples=2000, deadline=None)
@given(st.floats(0.0, 1.0), st.floats(0.01, 10.0))
def test_the_core_power_is_the_portable_power(x: float, p: float) -> None:
    assert core.power(x, p) == power(x, p)


@pytest.mark.parametrize("exponent", [2.0 / 3.0, 2.0 / 5.0, 1.0, 1.7])
def test_the_core_critical_temperatures_are_the_worlds(exponent: float) -> None:
    sim = Simulation(n_atoms=60, radius=8.0, seed=4, tc_exponent=exponent, engine="fast")
    for n in (60, 59, 31, 2, 1):
        sim._world.n_trapped = n  # the World's expression for every N the core tables
        assert sim.critical_temperature == sim._world.tc0 * core.power(n / 60, exponent)


# -- the game's frame, its win and score, and the replay -------------------------------------


@functools.cache
def recordings() -> list[r.Recording]:
    """Autopilot games: rim and knife, the seed's and the cup's Tc law, won and lost."""
    return [
        r.record_autopilot("demo", r.Settings(), seed=1, engine="fast"),
        r.record_autopilot("demo", r.Settings(escape="knife"), seed=2, engine="fast"),
        r.record_autopilot(
            "demo", r.Settings(n_atoms=30, tc_exponent=0.4), seed=3, budget=400, engine="fast"
        ),
    ]


@pytest.mark.parametrize("k", range(3))
def test_the_core_replays_a_recording_as_the_python_frames(k: int) -> None:
    rec = recordings()[k]
    fast, reference = r.replay(rec, engine="fast"), r.replay(rec, engine="reference")
    assert fast == reference
    assert (fast.won, fast.score, fast.frames) == (rec.won, rec.score, rec.frames)


def test_a_replay_stops_at_its_frame_limit_and_at_the_win() -> None:
    rec = recordings()[0]
    for engine in ("fast", "reference"):
        game = Game(rec.settings.game_config(rec.seed, engine))
        game.toggle_pause()
        assert game.sim.replay(list(rec.moves), 100) == 100
        assert game.sim.score is None and game.sim.time == 100.0
        # the rest, from frame 100: the win at the recording's frame, its score fixed then
        rest = [(h, n) for h, n in zip(rec.heights()[100:], [1] * rec.frames, strict=False)]
        assert game.sim.replay(rest, 10**6) == rec.frames - 100
        assert game.sim.score == rec.score and game.sim.time == rec.frames


def _play_in_pieces(engine: str, rec: r.Recording) -> tuple[float | None, int | None, list]:
    """The recording played by a Game at 0.7 frames a step (pieces within frames)."""
    game = Game(GameConfig(seed=rec.seed, engine=engine, speed=1.0))
    held: list[float] = []
    game.on_frame.append(held.append)
    game.playback(rec.moves)
    game.toggle_pause()
    for _ in range(int(rec.frames / 0.7) + 3):
        game.update(0.7 / 30.0)
    return game.won_at, game.score, held


def test_the_game_loop_sees_the_same_win_on_the_core_and_without() -> None:
    rec = recordings()[0]
    fast = _play_in_pieces("fast", rec)
    assert fast == _play_in_pieces("reference", rec)
    assert fast[0] == rec.frames / 30.0 and fast[1] == rec.score
    assert fast[2] == rec.heights()
