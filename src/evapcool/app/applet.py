"""The playable applet: one window, the game, and the parts that run it.

`App` composes the parts and runs the frame loop; each part is a module of its own and
none calls back into the App:

- `Framing` (app.framing): the window, the charts beside the scene, the layout;
- `GameClock` (app.clock): how far each frame moves the physics, the frame timings;
- `InputMachine` (app.input): modes and what each event does; it acts through
  `Commands` (app.commands), the actions of the key table (app.keys, which also writes
  the help) and of the scene's buttons;
- `Rounds` (app.rounds): the game in play, and making each new one;
- `Overlays` (app.overlays): the help, high scores, settings and name box drawn over
  the play area;
- `WinScreen` (app.winscreen): what a win means, the name box, the replay code;
- `PilotSeat` (app.pilot): the autopilot, if any, and whether it has the trap;
- `ClassMode` (app.classmode): the class challenge and what the class server says;
- `Notices` (app.notices): news and problems at the bottom of the play area.

Everything is drawn each frame straight into the window at the layout's scale (crisp at
any size).
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable, Mapping, Sequence

import pygame

from evapcool.about import note_line
from evapcool.app.charts import ChartColumn
from evapcool.app.classlink import Challenge, ClassLink
from evapcool.app.classmode import ClassMode
from evapcool.app.clock import GameClock
from evapcool.app.commands import Commands
from evapcool.app.controls import SceneControls
from evapcool.app.framing import Framing
from evapcool.app.input import Binding, InputMachine, Mode
from evapcool.app.keys import HEIGHT_STEP, HELP_ARGS, default_bindings
from evapcool.app.layout import Layout
from evapcool.app.notices import NOTICE_SECONDS, Notices
from evapcool.app.options import SettingsEditor
from evapcool.app.overlays import Overlays
from evapcool.app.pilot import PilotSeat
from evapcool.app.replays import REPLAY_FOLDER, ReplayKeeper
from evapcool.app.rounds import Rounds
from evapcool.app.scoring import Scoreboard
from evapcool.app.sound import Sound
from evapcool.app.stats import FrameStats
from evapcool.app.storage import scores_path, settings_path
from evapcool.app.teaching import LOCKED_FIELDS, Teaching
from evapcool.app.window import Window
from evapcool.app.winscreen import WinScreen
from evapcool.app.words import t
from evapcool.game.autopilot import Autopilot
from evapcool.game.replay import Recording
from evapcool.game.rules import Game, GameConfig, make_simulation
from evapcool.game.settings import Settings
from evapcool.view.icons import window_icon
from evapcool.view.pen import Pen
from evapcool.view.scene import PLAY_RECT, REPLAY_RECT, SCENE_SIZE, Scene
from evapcool.view.theme import theme_named
from evapcool.view.widgets import Pointer

TITLE = "app.title"  # the window's title, in the chosen language
#: Display frame rate we aim for; physics time follows the wall clock regardless.
TARGET_FPS = 60
#: A folder argument that names no folder (the command line's --data-dir says the same).
BAD_FOLDER = "{name} must name a folder (got {value!r})"
#: SDL's video drivers that show no window.
HEADLESS = ("dummy", "offscreen")
#: Modes that take every key and click: the scene's buttons do not light up under them.
_MODAL = (Mode.NAME, Mode.SETTINGS, Mode.CONFIRM_CLEAR)


class App:
    """The applet: composes the parts and runs the frames."""

    def __init__(
        self,
        game: Game | GameConfig,
        *,
        fullscreen: bool = False,
        data_dir: str | os.PathLike[str] | None = None,
        config_dir: str | os.PathLike[str] | None = None,
        settings: Settings | None = None,
        overrides: Mapping[str, object] | None = None,
        notices: Sequence[str] = (),
        screen: tuple[int, int] | None = None,
        log: Callable[[str], None] | None = None,
        autopilot: Autopilot | None = None,
        classroom: ClassLink | None = None,
        replay: Recording | None = None,
        lock: Sequence[str] = (),
        hide: Sequence[str] = (),
    ) -> None:
        """game: what to play, or the config to make it from. data_dir / config_dir: where scores
        and settings live (default $EVAPCOOL_DATA_DIR / $EVAPCOOL_CONFIG_DIR, else the
        user folders). settings: the saved settings (read from config_dir if None);
        overrides: this run's command-line values on top (never saved); notices: problems
        shown at start. screen: the desktop size to lay out for (default: the real one).
        log: where a one-line note about a slow start goes (e.g. stderr).
        autopilot: a strategy that plays by itself (`evapcool --autopilot FILE`; key A).
        classroom: a class server to join (`evapcool --class URL`): its challenge is
        played, and each win is sent to it. replay: a recording to watch (`--replay`).
        lock: controls shown but not changeable, hide: parts left out (a setup's link).
        """
        for name, value in (("data_dir", data_dir), ("config_dir", config_dir)):
            _check_folder(name, value)
        pygame.display.init()
        pygame.font.init()
        self.log = log
        self.notices = Notices()
        self.notices.add_all(tuple(notices))
        self.scores = Scoreboard(scores_path(data_dir), self.notices)
        self.options = SettingsEditor(settings_path(config_dir), self.notices, settings, overrides)
        self.replays = ReplayKeeper(scores_path(data_dir).parent / REPLAY_FOLDER, self.notices)
        self.win_screen = WinScreen(self.scores, self.replays, self.notices)
        self.pilot = PilotSeat(self.notices, autopilot)
        if classroom is not None:  # a restarted applet rejoins as the same student
            classroom.remember_in(scores_path(data_dir).parent)
        self.classroom = ClassMode(classroom, self.notices)
        looks = self.options.looks()
        self.scene = Scene(theme_named(looks.theme))
        # A headless run (--frames, tests) has no ears unless an audio driver is named.
        device = pygame.display.get_driver() not in HEADLESS or "SDL_AUDIODRIVER" in os.environ
        sound = Sound(looks.sound == "on", looks.volume / 100, classroom is not None, device)
        self.teaching = Teaching(
            sound, self.notices, self.replays, scores_path(data_dir).parent, lock, hide
        )
        self.options.locked = frozenset(
            LOCKED_FIELDS[name] for name in lock if name in LOCKED_FIELDS
        )
        self.time = GameClock()
        window = Window(t(TITLE), SCENE_SIZE, window_icon(64), screen)
        self.framing = Framing(window)
        pygame.key.set_repeat(300, 40)  # hold an arrow key to sweep the trap
        pygame.key.stop_text_input()  # no IME / on-screen keyboard until a name is asked
        self.clock = pygame.time.Clock()
        if isinstance(game, GameConfig):
            try:
                sim = make_simulation(game)  # the compiled core starts at once
            except BaseException:
                self.close()
                raise
            game = Game(game, sim=sim)
        game.on_win.append(self._on_win)
        self.rounds = Rounds(
            game,
            make_simulation,
            options=self.options,
            scores=self.scores,
            replays=self.replays,
            pilot=self.pilot,
            classroom=self.classroom,
            charts=self.framing.charts,
            notices=self.notices,
            watching=replay,
        )
        rounds = self.rounds
        self.teaching.attach(game)
        self.controls = SceneControls(
            lambda: rounds.game.trap_height, hide=self.teaching.hide, locked=self.teaching.lock
        )
        self.slider = self.controls.slider
        self.commands = Commands(
            rounds, self.framing, self.pilot, self.win_screen, self.controls, self.teaching
        )
        self.input = InputMachine(
            self.commands, self.scores, self.options, default_bindings(self.teaching.hide)
        )
        self.overlays = Overlays(
            self.scene, self.input, self.scores, self.options, self.time.stats, HELP_ARGS
        )
        if fullscreen:
            self.framing.toggle_fullscreen()
        self.classroom.start()
        self.pilot.seat(game)

    # -- the parts, as the tests and extensions name them --------------------------------------
    @property
    def game(self) -> Game:
        return self.rounds.game

    @property
    def running(self) -> bool:
        return self.commands.running

    @running.setter
    def running(self, value: bool) -> None:
        self.commands.running = value

    @property
    def watching(self) -> Recording | None:
        return self.rounds.watching

    @property
    def window(self) -> Window:
        return self.framing.window

    @property
    def charts(self) -> ChartColumn:
        return self.framing.charts

    @property
    def layout(self) -> Layout:
        return self.framing.layout

    @property
    def preferred_scale(self) -> float:
        return self.framing.preferred_scale

    @property
    def fullscreen(self) -> bool:
        return self.window.fullscreen

    @property
    def stats(self) -> FrameStats:
        return self.time.stats

    @property
    def anim_time(self) -> float:
        return self.time.anim_time

    @property
    def autopilot(self) -> Autopilot | None:
        return self.pilot.autopilot

    @property
    def challenge(self) -> Challenge | None:
        return self.classroom.challenge

    @property
    def overlay(self) -> str | None:
        return self.input.overlay

    @property
    def bindings(self) -> list[Binding]:
        return self.input.bindings

    @property
    def visible_notices(self) -> list[str]:
        return self.notices.visible

    @property
    def replay_offered(self) -> bool:
        """The win screen shows the replay strip (a won game that was recorded)."""
        return self.win_screen.offered(self.game)

    def bind(self, binding: Binding) -> None:
        """Add (or override) a key binding (its action gets the app's `Commands`); it shows
        up in the help overlay."""
        self.input.bind(binding)

    def notify(self, text: str) -> None:
        """Show news in the notice area (until the next game, a few seconds at most)."""
        self.notices.news(text)

    def help_rows(self) -> list[tuple[str, str]]:
        """The help overlay's (keys, what they do) rows in the chosen language."""
        return self.overlays.help_rows()

    def toggle_chart(self, name: str) -> None:
        self.framing.toggle_chart(name)

    def toggle_fullscreen(self) -> None:
        self.framing.toggle_fullscreen()

    # -- games ---------------------------------------------------------------------------------
    def restart(self) -> None:
        """New atoms with the current settings, trap at 400, paused; ends any name entry."""
        self.input.end_drag()  # a drag never carries into the new game
        self.rounds.restart()
        self.input.reset()

    def _on_win(self, game: Game) -> None:
        autopilot = self.pilot.autopilot
        won = self.win_screen.settle(
            game,
            watched=self.watching.score if self.watching is not None else None,
            pilot=autopilot.table_name if autopilot is not None and autopilot.flew else None,
            in_class=self.classroom.challenge is not None,
            name=self.classroom.player_name,
        )
        if won.send is not None:
            self.classroom.send(won.send)
        if won.ask_name:
            self.input.ask_name()
        else:
            self.input.end_drag()

    # -- one frame -------------------------------------------------------------------------------
    def handle_events(self, events: Sequence[pygame.event.Event]) -> None:
        for event in events:
            self.framing.event(event)
            self.input.handle(event)

    def frame(self, wall_seconds: float | None = None) -> None:
        """Events, physics, drawing, presenting.

        wall_seconds: elapsed wall time to advance by (x 30 x speed, at most
        MAX_WALL_STEP); None advances exactly one physics frame x speed (headless runs).
        """
        t0 = time.perf_counter()
        self.teaching.observe(self.game)  # who is in the cup before a key lowers the trap
        self.handle_events(pygame.event.get())
        if not self.running:
            return
        played = self.advance(wall_seconds)
        t1 = time.perf_counter()
        self.draw()
        self.present()
        t2 = time.perf_counter()
        wall = wall_seconds if wall_seconds is not None else t2 - t0
        self.time.record(wall, t1 - t0, t2 - t1, played)

    def advance(self, wall_seconds: float | None = None) -> float:
        """The physics for one frame (see `frame`), then the charts record it if it moved.

        Returns the seconds of play it advanced (at 1x; 0 while paused).
        """
        self.pilot.steer(self.game)  # the trap for this frame, from the gas now
        dt, played = self.time.advance(self.game, wall_seconds)
        self.notices.now = self.time.anim_time
        if self.classroom.news(begun=self.game.sim.time > 0.0):
            self.restart()  # the challenge's atoms, before the game began
            self.classroom.joined()
        self._send_if_lost()
        if self.scores.name_box is not None:
            self.scores.name_box.update(dt)
        self.charts.observe(self.game.sim)
        self.teaching.observe(self.game)
        return played

    def _send_if_lost(self) -> None:
        """A player's game lost for good goes to a class that counts lost games (once)."""
        if not self.classroom.counts_lost or self.replays.recorder is None or self.pilot.flew:
            return
        if self.game.lost and self.classroom.challenge is not None:
            code = self.replays.finish_lost(self.game, self.classroom.challenge.max_frames)
            if code is not None:
                self.classroom.send_lost(code)

    def draw(self) -> None:
        title = t(TITLE)
        if self.window.win.title != title:  # the settings screen chose another language
            self.window.win.title = title
        lay = self.layout
        surface = self.window.surface
        surface.fill((0, 0, 0))
        looks = self.options.looks()
        if looks.theme != self.scene.theme.name:  # chosen on the settings screen
            self.scene.theme = theme_named(looks.theme)
        self.teaching.sound.enabled = looks.sound == "on"
        self.teaching.sound.volume = looks.volume / 100
        pen = Pen(surface, lay.scale, lay.scene.topleft)
        game = self.game
        self.scene.draw(pen, game, self.time.anim_time)
        self._draw_widgets(pen, lay)
        if game.score is not None:
            self.scene.draw_score(pen, game.score)
        elif (reason := game.too_few_atoms) is not None:
            self.scene.draw_too_few(pen, reason)
        elif game.paused and game.sim.time == 0.0 and self.overlay is None:
            self.scene.draw_start_hint(pen)
        offered = self.replay_offered
        bottom = REPLAY_RECT.top if offered else PLAY_RECT.bottom  # the table and notices
        self.overlays.draw(pen, game.score is not None, bottom)
        if offered:  # over a full table's lowest edge: the strip stays whole
            hover = self._hovering("replay")
            self.scene.draw_replay_button(pen, self.win_screen.strip_label(), hover)
        self.scene.draw_notices(pen, [(n.text, n.problem) for n in self.notices.shown], bottom)
        self.charts.draw(surface, lay.charts, lay.scale)

    def _pointer(self, lay: Layout) -> Pointer:
        """The mouse as the scene's buttons see it (nothing under a modal panel)."""
        pointer = self.input.pointer
        if self.input.mode in _MODAL:
            return Pointer()  # modal: the buttons do not answer, so do not light up
        return Pointer(lay.to_scene(pointer) if pointer else None, self.input.button_down)

    def _draw_widgets(self, pen: Pen, lay: Layout) -> None:
        self.controls.theme(self.scene.theme)
        self.controls.draw(pen, self._pointer(lay), self.game)

    def _hovering(self, target: str) -> bool:
        pointer = self.input.pointer
        modal = self.input.mode in _MODAL
        return not modal and pointer is not None and self.commands.target_at(pointer) == target

    def present(self) -> None:
        self.window.flip()

    # -- loops -------------------------------------------------------------------------------------
    def run(self) -> None:
        """Interactive loop at the display's pace; physics follows the wall clock."""
        self.clock.tick()
        while self.running:
            elapsed = self.clock.tick(TARGET_FPS) / 1000.0
            self.frame(elapsed)

    def run_frames(self, n: int) -> None:
        """Play n frames as fast as possible, each advancing 1 physics frame x speed."""
        if not self.running:
            return
        self.game.paused = False
        if n == 0:  # still draw once, so a screenshot shows the start
            self.draw()
            self.present()
        for _ in range(n):
            if not self.running:
                break
            self.frame(None)

    def screenshot(self, path: str | os.PathLike[str]) -> None:
        """Save the window as a PNG (written atomically)."""
        self.window.screenshot(path)

    def close(self) -> None:
        self.teaching.sound.close()
        self.window.close()
        pygame.display.quit()


def stderr_log(text: str) -> None:
    print(note_line(None, text), file=sys.stderr, flush=True)


__all__ = [
    "HEIGHT_STEP",
    "HELP_ARGS",
    "NOTICE_SECONDS",
    "TARGET_FPS",
    "App",
    "Binding",
    "default_bindings",
]


def _check_folder(name: str, value: object) -> None:
    """ValueError naming the argument unless value is None or a usable folder path."""
    if value is None:
        return
    try:
        text = os.fspath(value)  # type: ignore[call-overload]
    except TypeError:
        raise ValueError(BAD_FOLDER.format(name=name, value=value)) from None
    if not text or (b"\0" if isinstance(text, bytes) else "\0") in text:
        raise ValueError(BAD_FOLDER.format(name=name, value=value))
