"""A game's path for the debrief (issue 36): sampled from the replay, ends where it does."""

from __future__ import annotations

import math

import numpy as np
import pytest

from evapcool.game.path import MAX_POINTS, game_path, round_t, stride_of
from evapcool.game.replay import Recording, Settings, record_autopilot, replay
from evapcool.game.rules import Game, clamp_height
from evapcool.physics import core


def test_the_path_ends_at_the_replayed_result_and_keeps_few_points() -> None:
    rec = record_autopilot("demo", Settings(), 7, budget=6000)
    path = game_path(rec)
    got = replay(rec)
    assert (path.won, path.score, path.frames) == (got.won, got.score, got.frames)
    assert len(path.k) <= MAX_POINTS and path.k[0] == 0 and path.k[-1] == got.frames
    assert all(k % stride_of(got.frames) == 0 for k in path.k[:-1])
    assert path.n[-1] == got.score and path.n[0] == rec.settings.n_atoms


def test_each_point_is_the_game_at_that_frame() -> None:
    """Played frame by frame with the game's own rules (Game.set_trap_height + run_frames):
    at every kept frame the same N, T (rounded) and the height held."""
    rec = Recording(
        Settings(n_atoms=30), 4, ((400.0, 40), (250.0, 300), (120.0, 400)), False, 0, 740
    )
    path = game_path(rec)
    at = {k: (n, t, h) for k, n, t, h in zip(path.k, path.n, path.t, path.h, strict=True)}
    game = Game(rec.settings.game_config(rec.seed))
    game.toggle_pause()
    for k, height in enumerate(rec.heights(), 1):
        game.set_trap_height(height)
        game.run_frames(1)
        if k in at and not game.won:
            n, t, h = at[k]
            assert (n, t, h) == (game.sim.n_trapped, round_t(game.sim.temperature), height)
    assert len(at) > 100


def test_full_stride_and_rounding() -> None:
    rec = Recording(Settings(n_atoms=20), 2, ((300.0, 50),), False, 0, 50)
    assert game_path(rec, stride=1).k == tuple(range(51))
    assert game_path(rec, frames=10).frames == 10
    assert round_t(80.00136587525876) == 80.001 and round_t(1.23456e-4) == 1.2346e-4
    assert math.isclose(round_t(2 / 3), 0.66667)


def _path_rows(rec: Recording, engine: str, stride: int) -> tuple[int, object, int | None]:
    sim = Game(rec.settings.game_config(rec.seed, engine)).sim
    runs = [(clamp_height(h), n) for h, n in rec.moves]
    frames, rows = sim.path(runs, rec.n_frames, stride, runs[0][0])
    return frames, rows, sim.score


def test_the_cores_path_is_the_reference_engines_bit_for_bit() -> None:
    """core_path (C) against its oracle, the reference engine's readable loop: the same
    frames, N, unrounded T (NumPy's pairwise sum) and heights, to the last bit."""
    if not core.available():
        pytest.skip("the compiled core is not installed here (core.available() is False)")
    won = record_autopilot("demo", Settings(n_atoms=49), 3, budget=4000)
    assert replay(won).won
    ramp = ((400.0, 40), (250.0, 300), (120.0, 400))
    dense = Settings(n_atoms=200, radius=4.0)
    cases = [
        (won, stride_of(won.n_frames)),
        (Recording(Settings(n_atoms=30), 4, ramp, False, 0, 740), 1),
        (Recording(dense, 9, ((380.0, 30), (90.0, 170)), False, 0, 200), 7),
    ]
    for rec, stride in cases:
        frames, rows, score = _path_rows(rec, "fast", stride)
        want_frames, want_rows, want_score = _path_rows(rec, "reference", stride)
        assert (frames, score) == (want_frames, want_score)
        assert np.array_equal(rows, want_rows) and len(rows) > 20  # type: ignore[arg-type]
    assert score is None and won.n_frames > 0
