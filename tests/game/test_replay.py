"""Recordings, replay codes and verification by replay (issue 22)."""

from __future__ import annotations

import dataclasses
import functools

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.game import replay as r

SETTINGS = r.Settings()


@functools.cache
def autopilot_recording() -> r.Recording:
    return r.record_autopilot("demo", SETTINGS, seed=1)


@functools.cache
def autopilot_code() -> str:
    return r.encode(autopilot_recording())


def test_autopilot_game_verifies() -> None:
    rec = autopilot_recording()
    assert rec.won and rec.score > 0
    got = r.verify(r.decode(autopilot_code()))
    assert (got.won, got.score, got.frames) == (rec.won, rec.score, rec.frames)


def test_code_round_trips() -> None:
    assert r.decode(autopilot_code()) == autopilot_recording()
    assert autopilot_code().startswith("EC1.")


def test_forged_score_is_refused() -> None:
    rec = autopilot_recording()
    forged = dataclasses.replace(rec, score=rec.score + 1)
    with pytest.raises(r.ReplayError) as err:
        r.verify(r.decode(r.encode(forged)))
    assert err.value.reason == r.WRONG_SCORE


def test_forged_win_without_moves_to_win_is_refused() -> None:
    # the trap held high for 60 frames: no atom leaves, no win
    fake = r.Recording(SETTINGS, 1, ((450.0, 60),), won=True, score=49, frames=60)
    with pytest.raises(r.ReplayError) as err:
        r.verify(fake)
    assert err.value.reason == r.WRONG_SCORE


def test_edited_fields_and_other_versions() -> None:
    rec = autopilot_recording()
    doc = rec.to_json()
    with pytest.raises(r.ReplayError) as err:
        r.Recording.from_json({**doc, "frames": rec.frames + 1})
    assert err.value.reason == r.EDITED
    with pytest.raises(r.ReplayError) as err:
        r.Recording.from_json({**doc, "moves": [[9999.0, 3]], "frames": 3})
    assert err.value.reason == r.EDITED
    with pytest.raises(r.ReplayError) as err:
        r.Recording.from_json({**doc, "version": "0.0.1"})
    assert err.value.reason == r.OTHER_VERSION
    with pytest.raises(r.ReplayError) as err:
        r.decode("EC2." + autopilot_code()[4:])
    assert err.value.reason == r.OTHER_VERSION


@pytest.mark.parametrize("engine", ["reference", "fast"])
def test_recorder_run_length_codes(engine: str) -> None:
    """The moves the clock records (core/play.c, its oracle physics/play.py), run-length coded."""
    from evapcool.game.rules import Game

    game = Game(SETTINGS.game_config(3, engine))
    game.toggle_pause()
    for h in (400.0, 400.0, 300.0, 300.0, 300.0, 400.0):
        game.set_trap_height(h)
        game.run_frames(1)
    out = r.Recorder(SETTINGS, 3).finish(game)
    assert out.moves == ((400.0, 2), (300.0, 3), (400.0, 1))
    assert out.frames == 6 and out.heights() == [400.0, 400.0, 300.0, 300.0, 300.0, 400.0]


ALPHABET = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_."


@settings(max_examples=200, deadline=None)
@given(data=st.data())
def test_any_single_character_change_is_detected(data: st.DataObject) -> None:
    code = autopilot_code()
    i = data.draw(st.integers(0, len(code) - 1))
    ch = data.draw(st.sampled_from(ALPHABET).filter(lambda c: c != code[i]))
    changed = code[:i] + ch + code[i + 1 :]
    with pytest.raises(r.ReplayError) as err:
        r.decode(changed)
    assert err.value.reason in (r.DAMAGED, r.OTHER_VERSION)
