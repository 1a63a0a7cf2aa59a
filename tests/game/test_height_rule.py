"""When the player's trap height takes effect (issue 26.4): at the next whole frame."""

from __future__ import annotations

from evapcool.game.rules import Game, GameConfig


def _playing(seed: int = 3) -> Game:
    game = Game(GameConfig(seed=seed, engine="reference"))
    game.toggle_pause()
    return game


def test_height_set_mid_frame_takes_effect_at_the_next_whole_frame() -> None:
    game = _playing()
    game._advance(0.5)
    assert game.sim.time == 0.5
    assert game.set_trap_height(300.0)
    assert game.trap_height == 300.0  # what the slider shows: the height asked for
    assert game.sim.trap_height == 400.0  # the physics still has the old rim
    seen: list[tuple[float, float]] = []
    engine = game.sim._engine  # the reference engine, playing by physics/play.py
    advance_to = engine.advance_to

    def watch(t_end: float) -> None:
        advance_to(t_end)
        seen.append((game.sim.time, game.sim.trap_height))

    engine.advance_to = watch  # type: ignore[method-assign]
    game._advance(1.25)  # from 0.5 to 1.75: pieces 0.5 -> 1 -> 1.75
    assert [t for t, _ in seen] == [1.0, 1.75]
    assert seen[0][1] == 400.0  # the piece up to t = 1 ran with the old rim
    assert seen[1][1] == 300.0  # applied at t = 1, before the next piece
    assert game.sim.trap_height == 300.0


def test_same_heights_in_the_same_frames_give_the_same_run_at_any_step() -> None:
    """A run depends on what was asked in which frame, not on the display's step."""
    late, early = _playing(), _playing()
    early.set_trap_height(200.0)
    early._advance(2.0)
    late._advance(0.5)
    late.set_trap_height(200.0)
    late._advance(1.5)
    # early: 200 from t = 0; late: 200 from t = 1, as if asked at frame 1
    again = _playing()
    again._advance(1.0)
    again.set_trap_height(200.0)
    again._advance(1.0)
    assert late.sim.to_state() == again.sim.to_state()
    assert early.sim.time == late.sim.time == 2.0


def test_paused_or_whole_frame_applies_at_once() -> None:
    game = Game(GameConfig(seed=1, engine="reference"))
    assert game.paused
    game.set_trap_height(250.0)
    assert game.sim.trap_height == 250.0
    game.toggle_pause()
    game._advance(2.0)
    game.set_trap_height(200.0)
    assert game.sim.trap_height == 200.0


def test_restart_drops_a_held_height() -> None:
    game = _playing()
    game._advance(0.5)
    game.set_trap_height(100.0)
    game.restart()
    assert game.trap_height == game.sim.trap_height == 400.0


def test_the_game_checks_a_height_once_and_the_physics_trusts_it(monkeypatch) -> None:
    """The slider's range is the one check (issue 26.2): no second range check below."""
    from evapcool import limits

    game = _playing()
    checked: list[str] = []
    original = limits.Range.check

    def counting(self, name, value):
        checked.append(name)
        return original(self, name, value)

    monkeypatch.setattr(limits.Range, "check", counting)
    game._advance(0.5)
    game.set_trap_height(1e9)  # clamped to the slider's top
    game._advance(1.0)
    assert game.sim.trap_height == 450.0
    assert "trap_height" not in checked
    game.sim.trap_height = 300.0  # the physics API itself still checks, at once
    assert checked.count("trap_height") == 1


def test_pausing_mid_frame_finishes_the_frame_so_a_paused_height_lands_on_a_whole_one() -> None:
    """A paused game stands on a whole frame: a recording of heights per frame is exact."""
    game = _playing()
    game._advance(0.4)
    game.toggle_pause()
    assert game.paused and game.sim.time == 1.0
    game.set_trap_height(250.0)
    assert game.sim.trap_height == 250.0  # applied at once: frame 1 on starts with it
    held: list[float] = []
    game.on_frame.append(held.append)
    game.toggle_pause()
    game._advance(2.0)
    assert held == [250.0, 250.0]


def test_a_game_at_any_display_step_replays_to_the_same_win() -> None:
    """The win is checked at whole frames: half-frame steps record a game that replays."""
    from evapcool.game.replay import Recorder, Settings, verify

    game = Game(GameConfig(seed=21))
    game.toggle_pause()
    k = 0
    while game.won_at is None and game.sim.time < 3000:
        if k % 50 == 0 and game.trap_height > 100:
            game.nudge_height(-5.0)
        game.update(1.0 / 60.0)  # half a frame per display frame
        k += 1
    rec = Recorder(Settings(), 21).finish(game)
    assert rec.won and rec.frames == int(game.sim.time)
    assert verify(rec).score == game.score


def test_playback_holds_a_recordings_heights_and_ignores_the_player() -> None:
    """A recording watched: its heights frame by frame, whatever the display's step."""
    from evapcool.game.replay import Settings, record_autopilot

    rec = record_autopilot("demo", Settings(), 9)
    game = Game(Settings().game_config(9))
    game.playback(rec.moves)
    assert game.trap_height == rec.heights()[0]
    assert not game.set_trap_height(100.0)  # the recording holds the trap
    game.toggle_pause()
    while game.won_at is None and game.sim.time < rec.frames + 5:
        game.update(0.7 / 30.0)
    assert (game.won, game.score, round(game.won_at * 30)) == (rec.won, rec.score, rec.frames)


def test_the_win_is_seen_at_its_frames_end_before_a_height_asked_in_it_applies() -> None:
    """The replay's order (core/game.c, Simulation.replay): the score is the atoms trapped at
    the end of the win's frame; a height asked during that frame applies after, so a knife
    cut it makes cannot change the score (nor make the live game disagree with its replay)."""
    for engine in ("reference", "fast"):
        games = [Game(GameConfig(seed=3, engine=engine, escape="knife")) for _ in range(2)]
        for game in games:
            game.toggle_pause()
            game._advance(0.5)
        cut, kept = games
        assert cut.set_trap_height(25.0)  # held for the next frame: the knife cuts at t = 1
        for game in games:
            game.sim.force_win()  # the gas condenses within this frame
            game._advance(0.5)
        assert kept.won_at == cut.won_at == 1.0 / 30.0
        assert cut.sim.n_trapped < kept.sim.n_trapped  # the cut came, after the frame's end
        assert cut.score == kept.score == kept.sim.n_trapped
