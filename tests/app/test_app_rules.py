"""Game rules without pygame: pause, speed, wall-clock time, restart, win, empty cup."""

from __future__ import annotations

import sys

import pytest

from evapcool import Simulation
from evapcool.game import rules
from evapcool.game.rules import Game, GameConfig, check_speed, lose_message
from evapcool.physics.reference import out_of_reach


def test_rules_do_not_need_pygame():
    assert "pygame" not in rules.__dict__
    with open(rules.__file__, encoding="utf-8") as fh:
        assert "import pygame" not in fh.read()


def test_new_game_is_the_classic_start_paused():
    g = Game(GameConfig(seed=4))
    assert (g.sim.n_trapped, g.trap_height, g.paused, g.speed) == (49, 400.0, True, 1.0)
    assert g.score is None and not g.won and not g.all_escaped and g.play_time == 0.0


def test_paused_game_does_not_move():
    g = Game(GameConfig(seed=4))
    assert g.update(0.5) == 0.0 and g.run_frames(3) == 0.0
    assert g.sim.time == 0.0


def test_wall_time_times_30_times_speed_with_a_cap():
    g = Game(GameConfig(seed=4))
    g.paused = False
    g.update(1 / 60)
    assert g.sim.time == pytest.approx(0.5)
    g.set_speed(2.0)
    g.update(1 / 60)
    assert g.sim.time == pytest.approx(1.5)
    g.update(120.0)  # a two-minute stall advances only the capped step
    assert g.sim.time == pytest.approx(1.5 + rules.MAX_WALL_STEP * 30 * 2)
    assert g.play_time == pytest.approx(g.sim.time / 30)


def test_speed_doubles_and_halves_within_quarter_to_four():
    g = Game()
    for expected in (2.0, 4.0, 4.0):
        g.faster()
        assert g.speed == expected
    for expected in (2.0, 1.0, 0.5, 0.25, 0.25):
        g.slower()
        assert g.speed == expected
    for bad in (0.2, 4.5, float("nan"), True, "2"):
        with pytest.raises(ValueError, match="speed"):
            check_speed(bad)


def test_step_only_while_paused():
    g = Game(GameConfig(seed=4))
    assert g.step() == 1.0 and g.sim.time == 1.0
    g.paused = False
    assert g.step() == 0.0 and g.sim.time == 1.0


def test_trap_height_clamped_to_the_slider_range():
    g = Game(GameConfig(seed=4))
    g.set_trap_height(10.0)
    assert g.trap_height == 25.0
    g.nudge_height(1000.0)
    assert g.trap_height == 450.0


def test_restart_uses_the_config_and_bumps_the_generation():
    g = Game(GameConfig(n_atoms=20, radius=6.0, seed=7))
    first = g.sim.positions.copy()
    g.paused = False
    g.set_trap_height(50.0)
    g.run_frames(5)
    gen = g.generation
    g.restart()
    assert (g.sim.n_trapped, g.trap_height, g.paused, g.generation) == (20, 400.0, True, gen + 1)
    assert (g.sim.positions == first).all()  # same seed, same start


def test_win_latches_once_and_freezes_the_trap():
    g = Game(GameConfig(seed=4))
    calls = []
    g.on_win.append(calls.append)
    g.paused = False
    g.run_frames(2)
    g.sim.force_win()
    g.run_frames(2)
    g.run_frames(2)
    # The win is checked at each whole frame (issue 26.4): seen at t = 3, not at the step's end.
    assert calls == [g] and g.won_at == pytest.approx(3 / 30)
    assert g.score == g.sim.n_trapped
    assert not g.set_trap_height(100.0) and g.trap_height == 400.0


def test_all_escaped():
    g = Game()
    g.sim = Simulation(n_atoms=1, radius=12.0, positions=[[0.0, 10.0]], velocities=[[8.0, 8.0]])
    g.set_trap_height(25.0)
    g.paused = False
    for _ in range(100):
        g.run_frames(1)
    assert g.all_escaped and g.score is None


def test_missing_core_falls_back_to_reference(monkeypatch):
    # As an sdist installed without a C compiler: no compiled core.
    monkeypatch.setitem(sys.modules, "evapcool.physics._core", None)
    g = Game(GameConfig(n_atoms=400, radius=3.0, seed=1))
    assert g.sim.engine == "reference"


# -- when the gas can no longer condense (issue 14, item 6) -----------------------------------

ESCAPE = 1.0 * (10.0 / 30.0) * rules.HEIGHT_MIN  # m g H_min: the least an escaping atom carries


def said(*args: float, trap_energy: float | None = None) -> str | None:
    """What the player reads for the reference's readable reach rule (the core's oracle)."""
    return lose_message(out_of_reach(int(args[0]), *args[1:], trap_energy=trap_energy))


def test_no_atoms_left_is_out_of_reach():
    assert said(0, 0.0, 0.0, ESCAPE) == "All the atoms escaped."


def test_one_atom_above_tc_is_out_of_reach_below_it_is_not():
    assert said(1, 5.0, 4.0, ESCAPE) is not None
    assert said(1, 3.0, 4.0, ESCAPE) is None  # condensing now


def test_two_atoms_with_energy_to_spare_can_still_win():
    # One may leave carrying nearly all the energy: the other is then as cold as it likes.
    assert said(2, 2 * 50.0, 4.0, ESCAPE) is None
    assert said(500, 500 * 50.0, 40.0, ESCAPE) is None


def test_atoms_that_cannot_leave_keep_their_temperature():
    assert said(3, 0.9 * ESCAPE, 0.1, ESCAPE) is not None
    assert said(3, 1.1 * ESCAPE, 0.1, ESCAPE) is None


def test_atoms_too_cold_to_leave_as_the_trap_stands_are_told_to_lower_it():
    # Issue 34: 2 atoms at T = 7.5 > Tc = 7.2 under a high trap stayed frozen with no word.
    here = 1.0 * (10.0 / 30.0) * 60.0  # m g H at a trap height of 60
    told = said(2, 15.0, 7.2, ESCAPE, trap_energy=here)
    assert told is not None and "lower the trap, or restart" in told
    assert said(2, 15.0, 7.2, ESCAPE, trap_energy=0.5 * here) is None  # can leave
    assert said(2, 13.0, 7.2, ESCAPE, trap_energy=here) is None  # condensing


def test_a_real_gas_under_a_high_trap_is_told_within_a_frame():
    g = Game(GameConfig(seed=4))
    g.sim = Simulation(
        n_atoms=2,
        radius=12.0,
        positions=[[-40.0, 60.0], [40.0, 60.0]],
        velocities=[[1.0, 0], [0, 1.0]],
    )
    sim = g.sim
    assert sim.temperature > sim.critical_temperature
    assert sim.total_energy() < float(sim.masses.min()) * sim.gravity * g.trap_height
    assert g.too_few_atoms is not None and "lower the trap" in g.too_few_atoms
    g.set_trap_height(rules.HEIGHT_MIN)
    g.paused = False
    g.run_frames(1)
    assert g.too_few_atoms is None or "lower the trap" not in g.too_few_atoms


def test_a_lone_atom_in_a_real_game_is_out_of_reach_until_restart():
    g = Game(GameConfig(seed=4))
    assert g.too_few_atoms is None
    g.sim = Simulation(n_atoms=1, radius=12.0, positions=[[0.0, 50.0]], velocities=[[1.0, 0.0]])
    assert g.sim.temperature > g.sim.critical_temperature
    assert g.too_few_atoms == "One atom alone cannot cool below Tc."
    g.sim.force_win()
    assert g.too_few_atoms is None  # a won game is not lost
    g.restart()
    assert g.too_few_atoms is None


def test_the_rule_is_exact_for_a_lone_atom_in_the_simulation():
    """Its energy, hence T, is kept through every bounce: T never falls below Tc(1)."""
    sim = Simulation(n_atoms=1, radius=12.0, positions=[[0.0, 50.0]], velocities=[[1.5, 0.5]])
    g = Game()
    g.sim = sim
    g.paused = False
    t0 = sim.temperature
    for _ in range(300):
        g.run_frames(1)
        assert sim.temperature == pytest.approx(t0, rel=1e-9)
        assert not sim.won and g.too_few_atoms is not None


def test_the_score_is_fixed_when_the_gas_condenses():
    """An atom on its way over the rim may leave after the win: the score does not change."""
    g = Game(GameConfig(seed=4))
    g.paused = False
    g.run_frames(2)
    g.sim.force_win()
    g.run_frames(1)
    won_with = g.sim.n_trapped
    g.sim.trap_height = 25.0  # (the game freezes the trap; the physics lets atoms out)
    for _ in range(300):
        g.run_frames(1)
    assert g.sim.n_trapped < won_with and g.score == won_with
