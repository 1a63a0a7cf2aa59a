"""The autopilot's strategies: texts and files, the rules each family plays, the headless game
against the lab, and the demo that ships with the package."""

from __future__ import annotations

import itertools
import json
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.game import autopilot
from evapcool.game.autopilot import (
    GameSetup,
    Policy,
    Ramp,
    Reading,
    load_strategy,
    parse_strategy,
    play,
    read,
    save_strategy,
)
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN
from evapcool.lab import run_experiment
from evapcool.physics.simulation import Simulation

G = 10.0 / 30.0


def reading(frame=0.0, t=60.0, tc=45.0, n=49) -> Reading:
    return Reading(frame=frame, temperature=t, critical_temperature=tc, n_trapped=n)


# -- texts and files ----------------------------------------------------------------------


heights = st.floats(1.0, 1000.0, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.tuples(st.integers(0, 5000), heights), min_size=1, max_size=8, unique_by=lambda p: p[0]
    )
)
def test_ramp_text_reads_back_as_the_same_ramp(points):
    ramp = Ramp(tuple(sorted((float(f), h) for f, h in points)))
    again = parse_strategy(ramp.text)
    assert again == ramp
    for f in (0.0, 17.5, 900.0, 6000.0):
        assert again.height_at(f) == ramp.height_at(f)


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.tuples(st.integers(0, 3000), heights), min_size=2, max_size=6, unique_by=lambda p: p[0]
    ),
    st.floats(0.0, 4000.0),
)
def test_ramp_is_linear_between_points_and_clamped_to_the_slider(points, frame):
    pts = sorted((float(f), h) for f, h in points)
    ramp = Ramp(tuple(pts))
    h = ramp.height_at(frame)
    assert HEIGHT_MIN <= h <= HEIGHT_MAX
    inside = [(a, b) for a, b in itertools.pairwise(pts) if a[0] <= frame <= b[0]]
    if inside:
        (f0, h0), (f1, h1) = inside[0]
        expect = h0 + (h1 - h0) * (frame - f0) / (f1 - f0)
        assert h == pytest.approx(min(HEIGHT_MAX, max(HEIGHT_MIN, expect)), rel=1e-12, abs=1e-9)


def test_policy_text_round_trip_fills_defaults():
    p = parse_strategy("feedback:eta0=5.5,beta=-1")
    assert isinstance(p, Policy)
    assert p.params["eta0"] == 5.5 and p.params["beta"] == -1.0
    assert p.params["eta1"] == autopilot.POLICIES["feedback"].defaults["eta1"]
    assert parse_strategy(p.text) == p


@pytest.mark.parametrize(
    ("text", "named"),
    [
        ("", "strategy must be"),
        ("400@0,300", "strategy must be"),
        ("400@10,300@5", "ramp frames must increase"),
        ("-5@0", "heights > 0"),
        ("0@0,10@100", "heights > 0"),
        ("wobble:x=1", "policy family must be one of"),
        ("feedback:speed=3", "no parameter 'speed'"),
        ("feedback:eta0=fast", "must be name=number"),
        ("feedback:eta0=nan", "must be name=number"),
        ("feedback:budget=0", "budget must be > 0"),
    ],
)
def test_bad_strategies_say_what_is_wrong(text, named):
    with pytest.raises(ValueError, match=named):
        parse_strategy(text)


def test_strategy_file_round_trip_keeps_the_provenance(tmp_path):
    path = tmp_path / "best.json"
    strategy = parse_strategy("deadline:eta_hi=9,gain=12")
    save_strategy(path, strategy, family="deadline", search={"mean": 30.5})
    doc = json.loads(path.read_text())
    assert doc["format"] == "evapcool-strategy" and doc["kind"] == "policy"
    assert doc["search"] == {"mean": 30.5}
    assert load_strategy(str(path)) == strategy
    text_file = tmp_path / "ramp.txt"
    text_file.write_text("450@0,140@1800\n")
    assert load_strategy(str(text_file)) == parse_strategy("450@0,140@1800")


def test_files_that_are_not_strategies_are_refused(tmp_path):
    bad = tmp_path / "x.json"
    bad.write_text('{"format": "something else"}')
    with pytest.raises(ValueError, match="not an evapcool strategy file"):
        load_strategy(str(bad))
    bad.write_text("{not json")
    with pytest.raises(ValueError, match="not valid JSON"):
        load_strategy(str(bad))
    with pytest.raises(ValueError, match="cannot read"):
        load_strategy(str(tmp_path / "missing.json"))


def test_the_demo_ships_with_the_package_and_says_where_it_came_from():
    doc = autopilot.demo_document()
    strategy = load_strategy("demo")
    assert strategy == parse_strategy(doc["strategy"])
    assert doc["budget"] == 1800
    assert doc["game"]["n_atoms"] == 49
    # Its validation against the best linear ramp travels with it (docs/cluster.md).
    assert doc["comparison"]["seeds"] >= 100


# -- what each family does ----------------------------------------------------------------


def test_feedback_sets_eta_kt_over_mg_and_its_ratchet_never_raises():
    free = Policy("feedback", {"eta0": 6, "eta1": 6}).controller()
    r = reading(t=50.0)
    assert free(r) == pytest.approx(6 * 0.4 * 50.0 / G)
    ratchet = Policy("feedback", {"eta0": 6, "eta1": 6, "ratchet": 1}).controller()
    first = ratchet(reading(t=50.0))
    assert ratchet(reading(frame=1, t=60.0)) == first  # hotter asks for more: held
    assert ratchet(reading(frame=2, t=40.0)) < first


def test_feedback_eta_moves_with_the_clock_and_the_thermometer():
    c = Policy("feedback", {"eta0": 8, "eta1": 4, "beta": 2, "budget": 1000}).controller()
    t, tc = 30.0, 20.0
    h = c(reading(frame=500, t=t, tc=tc))
    assert h == pytest.approx((6 + 2 * math.log(t / tc)) * 0.4 * t / G)


def test_heights_stay_on_the_slider():
    c = Policy("feedback", {"eta0": 100, "eta1": 100}).controller()
    assert c(reading()) == HEIGHT_MAX
    c = Policy("feedback", {"eta0": 0.001, "eta1": 0.001}).controller()
    assert c(reading()) == HEIGHT_MIN


def test_creep_moves_per_frame_of_play_however_often_it_is_asked():
    p = {"h0": 400, "v0": 0.5, "v1": 0.5, "back": 0, "eta": 8, "wait": 0}
    once, often = Policy("creep", p).controller(), Policy("creep", p).controller()
    once(reading(frame=0))
    often(reading(frame=0))
    for k in range(1, 41):
        h_often = often(reading(frame=k * 0.25))
    h_once = once(reading(frame=10.0))
    assert h_once == pytest.approx(h_often) == pytest.approx(400 - 0.5 * 10)


def test_creep_steps_back_up_and_waits_after_an_escape():
    c = Policy(
        "creep", {"h0": 300, "v0": 1, "v1": 1, "back": 2, "eta": 100, "wait": 5}
    ).controller()
    c(reading(frame=0, n=49))
    h1 = c(reading(frame=10, n=49))
    assert h1 == pytest.approx(290)
    h2 = c(reading(frame=11, n=48, t=60.0))
    assert h2 == pytest.approx(290 + 2 * 0.4 * 60 / G)
    assert c(reading(frame=15, n=48, t=60.0)) == pytest.approx(h2)  # waiting
    assert c(reading(frame=18, n=48, t=60.0)) == pytest.approx(h2 - 2)


def test_deadline_cuts_lower_when_far_from_tc_and_short_of_time():
    c = Policy("deadline", {"eta_hi": 6, "eta_lo": 2, "gain": 5, "finish": 1.0}).controller()
    near = c(reading(frame=0, t=50.0, tc=49.0))
    far = c(reading(frame=0, t=50.0, tc=30.0))
    late = c(reading(frame=1700, t=50.0, tc=49.0))
    assert far < near and late < near
    assert near == pytest.approx((6 - 5 * math.log(50 / 49)) * 0.4 * 50 / G)
    assert c(reading(frame=1799, t=50.0, tc=20.0)) == pytest.approx(2 * 0.4 * 50 / G)


def test_guarded_follows_its_ramp_until_late_and_far_from_tc():
    p = {"h0": 400, "h1": 300, "duration": 1800, "eta_cap": 10, "gain": 20, "eta_lo": 2}
    c = Policy("guarded", p).controller()
    assert c(reading(frame=900, t=50.0, tc=49.0)) == pytest.approx(350.0)  # the ramp
    late = c(reading(frame=1700, t=50.0, tc=40.0))  # u = ln(1.25) / (1/18): eta at its floor
    assert late == pytest.approx(2 * 0.4 * 50 / G)
    floored = Policy("guarded", {**p, "eta_floor": 5}).controller()
    assert floored(reading(frame=1700, t=50.0, tc=40.0)) == pytest.approx(5 * 0.4 * 50 / G)


def test_win_energy_is_what_one_escape_must_carry_and_rim_escapes_carry_more_than_mgh():
    """Reading.win_energy: removing an atom of that energy puts T on Tc(N - 1); and an atom
    leaving over the rim carries more than m g H, so a cut there makes the next escape win."""
    sim = Simulation.classic(seed=4, engine="fast")
    r = read(sim)
    t_after = (r.n_trapped * r.temperature - r.win_energy()) / (r.n_trapped - 1)
    assert t_after == pytest.approx(sim._world.critical_temperature_of(r.n_trapped - 1), rel=1e-12)
    seen = 0
    for frame in range(1500):
        h = 450.0 - 0.2 * frame
        sim.trap_height = h
        n0, u0 = sim.n_trapped, sim.total_energy()
        sim.advance(1.0)
        if sim.won:
            break
        if sim.n_trapped == n0 - 1:
            seen += 1
            assert u0 - sim.total_energy() > G * h * (1 - 1e-12)
    assert seen >= 10


# -- the headless game --------------------------------------------------------------------


@pytest.mark.parametrize(
    "text",
    [
        "450@0,140@1800",
        "feedback:eta0=6,eta1=4,beta=0.5,ratchet=1",
        "creep:h0=420,v0=0.3,v1=0.2,back=1,eta=7,wait=20",
        "deadline:eta_hi=11,eta_lo=4,gain=8,finish=0.8",
    ],
)
def test_play_scores_what_the_lab_measures(text):
    """The optimizer's games and `evapcool lab --schedule STRATEGY` are the same run."""
    o = play(parse_strategy(text), seed=3, budget=1800)
    lab = run_experiment(schedule=text, seed=3, engine="fast", frames=1800, every=1)
    assert o.won_frame == lab.metadata["won_frame"]
    if o.won:
        assert o.score == lab.n_trapped[-1] > 0
    else:
        assert o.score == 0 and o.n_final == lab.n_trapped[-1]
    # The heights the lab recorded are the strategy's, frame by frame.
    trace = []
    play(parse_strategy(text), seed=3, budget=1800, trace=trace)
    recorded = dict(zip(lab.frame.tolist(), lab.trap_height.tolist(), strict=True))
    for frame, h, *_ in trace[: len(lab.frame) - 1]:
        assert recorded[frame] == h


def test_no_win_in_the_budget_scores_zero():
    o = play(parse_strategy("450"), seed=1, budget=300)
    assert not o.won and o.won_frame is None and o.score == 0 < o.n_final


def test_play_is_deterministic_and_engine_independent():
    s = parse_strategy("430@0,150@1500")
    a = play(s, seed=11)
    b = play(s, seed=11)
    assert a == b
    ref = play(s, seed=11, budget=600, setup=GameSetup(engine="reference"))
    fast = play(s, seed=11, budget=600)
    assert ref == fast


def test_lab_accepts_demo_and_strategy_files(tmp_path):
    res = run_experiment(schedule="demo", seed=5, engine="fast", frames=300, every=100)
    assert res.parameters["schedule"] == "demo"
    path = tmp_path / "s.json"
    save_strategy(path, parse_strategy("feedback:eta0=3,eta1=3"))
    res = run_experiment(schedule=str(path), seed=5, engine="fast", frames=60, every=30)
    assert res.trap_height[0] == pytest.approx(3 * 0.4 * res.temperature[0] / G)
    with pytest.raises(ValueError, match="schedule"):
        run_experiment(schedule=str(tmp_path / "missing.json"), frames=10)


# -- the autopilot in a game ------------------------------------------------------------------


def _game(seed=2):
    from evapcool.game.rules import Game, GameConfig

    return Game(GameConfig(seed=seed, engine="fast"))


def test_autopilot_sets_the_start_while_paused_and_flies_once_playing():
    game = _game()
    pilot = autopilot.Autopilot(parse_strategy("300@0,100@600"), name="test")
    assert pilot.steer(game) == 300.0 and not pilot.flew
    game.paused = False
    for _ in range(150):
        game.run_frames(1)
        pilot.steer(game)
    assert pilot.flew and game.trap_height == pytest.approx(300 - 200 * 150 / 600)
    assert pilot.label == "Autopilot (test)"


def test_autopilot_plays_the_same_game_as_the_headless_player():
    """Frame by frame in a Game, the autopilot's game is the optimizer's game."""
    text = "feedback:eta0=6,eta1=4.5,beta=0.5"
    game = _game(seed=9)
    pilot = autopilot.Autopilot(parse_strategy(text))
    pilot.steer(game)
    game.paused = False
    while not game.won and game.sim.time < 1800:
        game.run_frames(1)
        pilot.steer(game)
    o = play(parse_strategy(text), seed=9)
    assert o.won_frame == (round(game.sim.time) if game.won else None)
    assert o.score == (game.score or 0)


def test_touching_the_controls_takes_over_and_the_key_gives_it_back():
    game = _game()
    pilot = autopilot.Autopilot(parse_strategy("400@0,100@300"))
    game.paused = False
    pilot.steer(game)
    game.run_frames(30)
    pilot.steer(game)
    pilot.take_over()
    game.set_trap_height(420.0)
    game.run_frames(30)
    assert pilot.steer(game) is None and game.trap_height == 420.0
    assert pilot.toggle() is True
    h = pilot.steer(game)
    assert h == pytest.approx(400 - 300 * 60 / 300)  # the ramp's clock went on
    game.paused = True
    game.set_trap_height(350.0)
    assert pilot.steer(game) is None and game.trap_height == 350.0  # paused: hands off


def test_restart_starts_the_strategy_over():
    game = _game()
    pilot = autopilot.Autopilot(parse_strategy("creep:h0=420,v0=1,v1=1"))
    game.paused = False
    pilot.steer(game)
    game.run_frames(50)
    pilot.steer(game)
    assert game.trap_height < 420
    game.restart()
    pilot.new_game()
    assert not pilot.flew
    assert pilot.steer(game) == 420.0


def test_autopilot_load_names_it():
    assert autopilot.Autopilot.load("demo").label == "Autopilot (demo)"
    with pytest.raises(ValueError, match="strategy must be"):
        autopilot.Autopilot.load("backwards")
