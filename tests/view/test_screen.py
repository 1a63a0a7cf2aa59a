"""The screen map: the view places the cup in the window; the physics knows only the room
around the cup (issue 26.3)."""

from __future__ import annotations

import numpy as np
import pytest

from evapcool.game.rules import Game, GameConfig
from evapcool.game.settings import SHOWN_BELOW_TOP
from evapcool.physics.room import CLASSIC_ROOM, Room
from evapcool.physics.simulation import Simulation
from evapcool.physics.state import room_of_window, to_state
from evapcool.view.screen import BORDER_TOP, WINDOW, ScreenMap, cup_vertex, window_room


def test_the_original_window_gives_the_original_room_and_mapping():
    assert cup_vertex(WINDOW) == (296.0, 544.0)
    assert window_room(WINDOW) == CLASSIC_ROOM
    screen = ScreenMap.of(Simulation.classic(seed=1))
    assert screen.vertex == (296.0, 544.0)
    assert screen.origin == (296.0, 532.0)  # R = 12 above the drawn cup bottom


@pytest.mark.parametrize("size", [(160, 160), (640, 672), (641, 1000), (8192, 8192)])
def test_the_view_and_the_state_format_name_the_same_room(size):
    assert window_room(size) == room_of_window(size)


def test_trap_and_screen_coordinates_round_trip():
    screen = ScreenMap((296.0, 544.0), 12.0)
    xy = np.array([[0.0, 0.0], [-30.5, 120.25], [200.0, -7.0]])
    px = screen.to_screen(xy)
    np.testing.assert_array_equal(px[0], [296.0, 532.0])
    np.testing.assert_array_equal(px[1], [265.5, 411.75])  # y up in the trap, down on screen
    np.testing.assert_array_equal(screen.to_trap(px), xy)


def test_the_model_holds_no_window():
    sim = Simulation.classic(seed=1)
    assert not any(hasattr(sim, name) for name in ("window", "screen_origin", "to_screen"))
    assert sim.room == CLASSIC_ROOM and sim.origin_lift == 12.0


def test_the_room_sets_where_escaped_atoms_are_gone():
    wide = window_room((1280, 672))
    sim = Simulation(n_atoms=20, seed=2, room=wide)
    world = sim._world
    assert (world.x_left, world.x_right) == (-wide.left, wide.right)
    assert world.y_bottom == (wide.above - 12.0) - 672.0
    # the same room as the classic one gives the same start, bit for bit
    same = Simulation(n_atoms=20, seed=2, room=Room(296.0, 344.0, 128.0, 544.0))
    np.testing.assert_array_equal(same.positions, Simulation(n_atoms=20, seed=2).positions)


def test_the_game_builds_its_simulation_in_the_room_it_is_given():
    room = window_room((800, 900))
    game = Game(GameConfig(seed=1, n_atoms=10, room=room))
    assert game.sim.room == room
    assert ScreenMap.of(game.sim).vertex == cup_vertex((800, 900))


def test_a_state_keeps_its_room():
    room = window_room((800, 900))
    sim = Simulation(n_atoms=10, seed=3, room=room)
    state = to_state(sim)
    assert state["window"] == [800, 900]
    assert Simulation.from_state(state).room == room
    odd = Simulation(n_atoms=10, seed=3, room=Room(10.0, 400.0, 128.0, 600.0))
    with pytest.raises(ValueError, match=r"^room"):
        to_state(odd)


def test_the_settings_keep_atoms_below_the_drawn_top_border():
    assert SHOWN_BELOW_TOP == BORDER_TOP
