"""What the keys and the mouse do: the `Controls` the input machine drives.

Each action goes to the part it concerns (the game, the rounds, the window, the autopilot,
the win screen); hit tests ask the layout and the scene's controls. `running` turns False
when the player quits.
"""

from __future__ import annotations

from evapcool.app.controls import SceneControls
from evapcool.app.framing import Framing
from evapcool.app.pilot import PilotSeat
from evapcool.app.rounds import Rounds
from evapcool.app.teaching import Teaching
from evapcool.app.winscreen import WinScreen
from evapcool.game.rules import Game
from evapcool.view.scene import REPLAY_RECT

Point = tuple[float, float]


class Commands:
    """The actions of the key table and the scene's buttons, on the parts they concern."""

    def __init__(
        self,
        rounds: Rounds,
        framing: Framing,
        pilot: PilotSeat,
        win_screen: WinScreen,
        controls: SceneControls,
        teaching: Teaching,
    ) -> None:
        self.rounds = rounds
        self.framing = framing
        self.pilot = pilot
        self.win_screen = win_screen
        self.controls = controls
        self.teaching = teaching
        self.running = True

    @property
    def game(self) -> Game:
        return self.rounds.game

    # -- the game ------------------------------------------------------------------------------
    def toggle_pause(self) -> None:
        self.game.toggle_pause()

    def restart(self) -> None:
        self.rounds.restart()

    def next_player(self) -> bool:
        return self.rounds.next_player()

    def nudge(self, delta: float) -> None:
        """An arrow key: the trap a step lower or higher (the player takes it)."""
        if not self.teaching.allows("trap"):
            return
        self.pilot.take_over()
        self.game.nudge_height(delta)

    def toggle_autopilot(self) -> None:
        if self.teaching.allows("trap"):
            self.pilot.toggle(self.game)

    def faster(self) -> None:
        if self.teaching.allows("speed"):
            self.game.faster()

    def slower(self) -> None:
        if self.teaching.allows("speed"):
            self.game.slower()

    # -- for the class (issue 48) ---------------------------------------------------------------
    def save_run(self, every_frame: bool = False) -> None:
        """Key W (Shift+W: a row every frame) or the button: the run as a lab CSV."""
        self.teaching.save_run(self.game, every_frame)

    def describe(self) -> None:
        """Key D: the scene in one sentence."""
        self.teaching.say(self.game)

    def toggle_mute(self) -> None:
        """Key M."""
        self.teaching.toggle_mute()

    def copy_replay(self) -> None:
        """Key C or the win screen's strip: the won game's code to the clipboard."""
        self.win_screen.copy(self.game)

    # -- the window ----------------------------------------------------------------------------
    def toggle_chart(self, name: str) -> None:
        self.framing.toggle_chart(name)

    def toggle_fullscreen(self) -> None:
        self.framing.toggle_fullscreen()

    def leave(self) -> None:
        """Esc with nothing open: leave full screen, else quit."""
        if self.framing.window.fullscreen:
            self.toggle_fullscreen()
        else:
            self.running = False

    def quit(self) -> None:
        self.running = False

    # -- the mouse -----------------------------------------------------------------------------
    def target_at(self, pos: Point) -> str | None:
        """What is under a window pixel: a chart's parts, the replay strip, a scene button."""
        hit = self.framing.charts.target_at(pos)
        if hit is not None:
            return hit
        lay = self.framing.layout
        if not lay.scene.collidepoint(pos):
            return None
        at = lay.to_scene(pos)
        if self.win_screen.offered(self.game) and REPLAY_RECT.collidepoint(at):
            return "replay"
        return self.controls.target_at(at)

    def slider_press(self, pos: Point) -> bool:
        slider = self.controls.slider
        slider.enabled = not self.game.won
        if not slider.hit(self.framing.layout.to_scene(pos)) or not self.teaching.allows("trap"):
            return False
        if not slider.press(self.framing.layout.to_scene(pos)):
            return False
        self.pilot.take_over()
        self.game.set_trap_height(slider.value)
        return True

    def slider_drag(self, pos: Point) -> None:
        slider = self.controls.slider
        slider.drag(self.framing.layout.to_scene(pos))
        self.game.set_trap_height(slider.value)

    def slider_release(self) -> None:
        self.controls.slider.release()
