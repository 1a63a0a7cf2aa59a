"""The playable applet: one window, the game, and the pieces that run it.

`App` composes: a `Window` (one OS window for the session), the layout (scene and
charts fitted to the window and the screen, `app.layout`), the `InputMachine`
(modes and what each event does, `app.input`), the `Scoreboard` (name entry, high
scores), the `SettingsEditor`, `Notices`, `FrameStats`, the charts and the scene with
its widgets. Everything is drawn each frame straight into the window at the layout's
scale (crisp at any size). The key table, `default_bindings()`, also writes the help.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import replace

import pygame

from evapcool.about import note_line
from evapcool.app.charts import ChartColumn
from evapcool.app.classlink import Challenge, ClassLink, Event
from evapcool.app.controls import SceneControls
from evapcool.app.input import Binding, InputMachine, Mode
from evapcool.app.layout import Layout, arrange, window_size_for
from evapcool.app.notices import NOTICE_SECONDS, Notices
from evapcool.app.options import SettingsEditor
from evapcool.app.replays import REPLAY_FOLDER, ReplayKeeper
from evapcool.app.scoring import Scoreboard
from evapcool.app.stats import FrameStats
from evapcool.app.storage import scores_path, settings_path
from evapcool.app.window import Window
from evapcool.app.words import t
from evapcool.game.autopilot import Autopilot
from evapcool.game.replay import Recording
from evapcool.game.rules import (
    HEIGHT_MAX,
    HEIGHT_MIN,
    MAX_WALL_STEP,
    Game,
    GameConfig,
    make_simulation,
)
from evapcool.game.settings import Settings
from evapcool.physics.simulation import FPS, Simulation
from evapcool.view.icons import window_icon
from evapcool.view.pen import Pen
from evapcool.view.scene import (
    PLAY_RECT,
    REPLAY_RECT,
    SCENE_SIZE,
    UNDER_MESSAGE,
    Scene,
)
from evapcool.view.widgets import Pointer

TITLE = "app.title"  # the window's title, in the chosen language
#: Display frame rate we aim for; physics time follows the wall clock regardless.
TARGET_FPS = 60
#: Trap height change per arrow-key press (key repeat is on), px.
HEIGHT_STEP = 5.0
_SUBMIT = (pygame.K_RETURN, pygame.K_KP_ENTER)
#: A folder argument that names no folder (the command line's --data-dir says the same).
BAD_FOLDER = "{name} must name a folder (got {value!r})"


def default_bindings() -> list[Binding]:
    """The applet's keyboard controls (the help overlay lists exactly these)."""
    return [
        Binding((pygame.K_SPACE,), "help.key.space", "help.space", lambda app: app.toggle_pause()),
        Binding(
            (pygame.K_r,),
            "R",
            "help.restart",
            App.restart,
            ends_drag=True,
        ),
        Binding(
            (pygame.K_LEFT, pygame.K_DOWN),
            "help.key.left_down",
            "help.lower",
            lambda app: app.nudge(-HEIGHT_STEP),
        ),
        Binding(
            (pygame.K_RIGHT, pygame.K_UP),
            "help.key.right_up",
            "help.raise",
            lambda app: app.nudge(HEIGHT_STEP),
        ),
        Binding((pygame.K_s,), "S", "help.step", lambda app: app.game.step()),
        Binding(
            (pygame.K_a,),
            "A",
            "help.autopilot",
            App.toggle_autopilot,
            more=("help.autopilot_more",),
        ),
        Binding(
            (pygame.K_PLUS, pygame.K_EQUALS, pygame.K_KP_PLUS),
            "+",
            "help.faster",
            lambda app: app.game.faster(),
        ),
        Binding(
            (pygame.K_MINUS, pygame.K_KP_MINUS),
            "-",
            "help.slower",
            lambda app: app.game.slower(),
        ),
        Binding((pygame.K_e,), "E", "help.energy", lambda app: app.toggle_chart("energy")),
        Binding(
            (pygame.K_g,),
            "G",
            "help.path",
            lambda app: app.toggle_chart("path"),
        ),
        Binding((pygame.K_t,), "T", "help.table", mode=Mode.TABLE),
        Binding((pygame.K_c,), "C", "help.copy", App.copy_replay),
        Binding(
            (pygame.K_DELETE, pygame.K_x),
            "help.key.delete_x",
            "help.clear",
            mode=Mode.CONFIRM_CLEAR,
            more=("help.clear_more",),
        ),
        Binding(_SUBMIT, "help.key.enter", "help.next", App.next_player, ends_drag=True),
        Binding(
            (pygame.K_o,),
            "O",
            "help.settings",
            mode=Mode.SETTINGS,
            more=("help.choose_change_save",),
        ),
        Binding((pygame.K_F11,), "F11", "help.fullscreen", App.toggle_fullscreen),
        Binding((pygame.K_h, pygame.K_F1), "H, F1", "help.help", mode=Mode.HELP),
        Binding((pygame.K_ESCAPE,), "help.key.esc", "help.escape", mode=Mode.PLAY),
    ]


#: Mouse controls, listed in the help overlay after the keys.
MOUSE_HELP = [("help.key.mouse", "help.mouse"), ("", "help.mouse_more")]
#: The numbers the help's messages name.
HELP_ARGS = {
    "step": HEIGHT_STEP,
    "height": 400,
    "low": HEIGHT_MIN,
    "high": HEIGHT_MAX,
    "fast": 4,
    "slow": "1/4",
}


def _word(label: str) -> str:
    """A key's name: a catalog key (help.key.*) translated, a key cap ("R", "F11") as is."""
    return t(label) if label.startswith("help.key.") else label


class App:
    """The applet: owns the window, the game, the input machine and the main loop."""

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
    ) -> None:
        """game: what to play, or the config to make it from. data_dir / config_dir: where scores
        and settings live (default $EVAPCOOL_DATA_DIR / $EVAPCOOL_CONFIG_DIR, else the
        user folders). settings: the saved settings (read from config_dir if None);
        overrides: this run's command-line values on top (never saved); notices: shown
        at start. screen: the desktop size to lay out for (default: the real one).
        log: where a one-line note about a slow start goes (e.g. stderr).
        autopilot: a strategy that plays by itself (`evapcool --autopilot FILE`; key A).
        classroom: a class server to join (`evapcool --class URL`): its challenge is
        played, and each win is sent to it.
        """
        for name, value in (("data_dir", data_dir), ("config_dir", config_dir)):
            _check_folder(name, value)
        pygame.display.init()
        pygame.font.init()
        self.running = True
        self.log = log
        #: Seconds of animation (wall clock, or 1/30 per headless frame): fades, toasts.
        self.anim_time = 0.0
        self.notices = Notices()
        self.notices.add_all(tuple(notices))
        self.scores = Scoreboard(scores_path(data_dir), self.notify)
        self.options = SettingsEditor(settings_path(config_dir), self.notify, settings, overrides)
        self.replays = ReplayKeeper(scores_path(data_dir).parent / REPLAY_FOLDER, self.notify)
        self.classroom = classroom
        #: The class challenge being played (its settings and seed on every restart).
        self.challenge: Challenge | None = None
        self.charts = ChartColumn()
        self.input = InputMachine(self, self.scores, self.options, default_bindings())
        self.scene = Scene()
        self.stats = FrameStats()
        self.controls = SceneControls(lambda: self.game.trap_height)
        self.slider = self.controls.slider

        self.window = Window(t(TITLE), SCENE_SIZE, window_icon(64), screen)
        #: The scene's scale the player wants (1, or what they resized the window to).
        self.preferred_scale = min(1.0, arrange(self.window.usable(), 0).scale)
        self.fit_window()
        pygame.key.set_repeat(300, 40)  # hold an arrow key to sweep the trap
        pygame.key.stop_text_input()  # no IME / on-screen keyboard until a name is asked
        self.clock = pygame.time.Clock()
        if fullscreen:
            self.toggle_fullscreen()

        if isinstance(game, GameConfig):
            try:
                sim = self.build_simulation(game)
            except BaseException:
                self.close()
                raise
            game = Game(game, sim=sim)
        self.game = game
        game.on_win.append(self._on_win)
        self.replays.attach(game)  # every game is recorded, the autopilot's too
        if classroom is not None:
            self.notify(t("desk.class.joining", url=classroom.base))
            classroom.remember_in(scores_path(data_dir).parent)
            classroom.start()
        #: A recording watched (`evapcool --replay`): its heights frame by frame, each restart.
        self.watching = replay
        if replay is not None:
            game.playback(replay.heights())
            self.notify(t("desk.replay.watching", edition=replay.edition))
        self.autopilot: Autopilot | None = None
        if autopilot is not None:
            self.autopilot = autopilot
            self._say_autopilot()
            autopilot.steer(game)  # the start height it wants, shown before Space

    # -- the autopilot -------------------------------------------------------------------------
    def _say_autopilot(self) -> None:
        self.notify(t("notice.autopilot_plays", name=self.autopilot.label))

    def toggle_autopilot(self) -> None:
        """Key A: the autopilot takes the slider (the demo if none was given), or hands back."""
        if self.autopilot is None:
            self.autopilot = Autopilot.load("demo")
        elif self.autopilot.toggle() is False:
            self.notify(t("notice.you_have_trap"))
            return
        self.autopilot.engage()
        self._say_autopilot()

    def take_over(self) -> None:
        """The player touched the trap's controls: the autopilot lets go."""
        if self.autopilot is not None and self.autopilot.engaged:
            self.autopilot.take_over()
            self.notify(t("notice.you_have_trap"))

    def nudge(self, delta: float) -> None:
        self.take_over()
        self.game.nudge_height(delta)

    # -- extension points ----------------------------------------------------------------
    def bind(self, binding: Binding) -> None:
        """Add (or override) a key binding; it shows up in the help overlay."""
        self.input.bind(binding)

    @property
    def bindings(self) -> list[Binding]:
        return self.input.bindings

    def notify(self, text: str) -> None:
        """Show a message in the notice area for a few seconds."""
        self.notices.add(text)

    @property
    def visible_notices(self) -> list[str]:
        return self.notices.visible

    @property
    def overlay(self) -> str | None:
        return self.input.overlay

    @property
    def fullscreen(self) -> bool:
        return self.window.fullscreen

    # -- the window and its layout -------------------------------------------------------------
    @property
    def layout(self) -> Layout:
        return arrange(self.window.size, len(self.charts.shown))

    def fit_window(self) -> None:
        """Size the window for the scene (and charts) at the preferred scale, on screen."""
        size, _ = window_size_for(
            self.preferred_scale, len(self.charts.shown), self.window.usable()
        )
        self.window.resize(size)

    def _window_event(self, event: pygame.event.Event) -> None:
        if event.type == pygame.WINDOWRESIZED and not self.window.fullscreen:
            size = (event.x, event.y)
            if size != self.window.requested:  # the user's resize: their scale from now on
                self.preferred_scale = arrange(size, len(self.charts.shown)).scale

    def toggle_fullscreen(self) -> None:
        self.window.toggle_fullscreen()
        if not self.window.fullscreen:
            self.fit_window()  # charts may have come or gone meanwhile

    def toggle_chart(self, name: str) -> None:
        self.charts.toggle(name)
        self.fit_window()

    def leave(self) -> None:
        """Esc with nothing open: leave full screen, else quit."""
        if self.window.fullscreen:
            self.toggle_fullscreen()
        else:
            self.running = False

    def quit(self) -> None:
        self.running = False

    # -- making and restarting games ------------------------------------------------------------
    def build_simulation(self, config: GameConfig) -> Simulation:
        """A new simulation for config (the compiled core starts at once: no progress screen)."""
        return make_simulation(config)

    def restart(self) -> None:
        """New atoms with the current settings, trap at 400, paused; ends any name entry."""
        if self.watching is not None:
            s = self.watching.settings
        else:
            s = self.challenge.settings if self.challenge else self.options.for_run()
        config = replace(
            self.game.config,
            n_atoms=s.n_atoms,
            radius=s.radius,
            tc_exponent=s.tc_exponent,
            escape=s.escape,
        )
        if self.challenge is not None:  # everyone in the class plays the same atoms
            config = replace(config, seed=self.challenge.seed)
        if self.watching is not None:
            config = replace(config, seed=self.watching.seed)
        self.input.end_drag()  # a drag never carries into the new game
        try:
            self.game.restart(config, sim=self.build_simulation(config))
        except ValueError as exc:  # settings are validated; this is a guard, not a path
            self.notify(t("notice.settings_failed", problem=exc))
            self.game.restart()
        self.replays.start(self.game)
        if self.watching is not None:
            self.game.playback(self.watching.heights())
        self.scores.new_round()
        if self.autopilot is not None:
            self.autopilot.new_game()
            self.autopilot.steer(self.game)
        self.input.reset()
        self.charts.reset()

    def next_player(self) -> bool:
        """Enter after a stored (or skipped) score: a fresh game for the next student."""
        if not self.scores.ready_for_next:
            return False
        self.restart()
        return True

    # -- the Controls the input machine drives --------------------------------------------------
    def target_at(self, pos: tuple[float, float]) -> str | None:
        hit = self.charts.target_at(pos)
        if hit is not None:
            return hit
        lay = self.layout
        if not lay.scene.collidepoint(pos):
            return None
        at = lay.to_scene(pos)
        if self.replay_offered and REPLAY_RECT.collidepoint(at):
            return "replay"
        return self.controls.target_at(at)

    def slider_press(self, pos: tuple[float, float]) -> bool:
        self.slider.enabled = not self.game.won
        if not self.slider.press(self.layout.to_scene(pos)):
            return False
        self.take_over()
        self.game.set_trap_height(self.slider.value)
        return True

    def slider_drag(self, pos: tuple[float, float]) -> None:
        self.slider.drag(self.layout.to_scene(pos))
        self.game.set_trap_height(self.slider.value)

    def slider_release(self) -> None:
        self.slider.release()

    def toggle_pause(self) -> None:
        self.game.toggle_pause()

    def _on_win(self, game: Game) -> None:
        if self.watching is not None:  # a replay's win is not a player's
            claimed = self.watching.score
            self.notify(t("desk.replay.won", n=game.score or 0, claimed=claimed))
            self.input.end_drag()
            return
        code = self.replays.finish(game)
        if self.autopilot is not None and self.autopilot.flew:  # never in the players' table
            if self.challenge is not None:
                self.notify(t("desk.class.autopilot"))
            self.scores.autopilot_win(
                self.autopilot.table_name, game.score or 0, game.won_at or 0.0
            )
            self.input.end_drag()
            return
        if self.classroom is not None and self.challenge is not None and code is not None:
            self.classroom.submit(code)
            self.notify(t("desk.class.sending"))
        if self.scores.win(game.score or 0, game.won_at or 0.0):
            self.input.ask_name()
        else:
            self.input.end_drag()

    # -- replay codes and the class ------------------------------------------------------------
    @property
    def replay_offered(self) -> bool:
        """The win screen shows the replay button (a won game that was recorded)."""
        return self.game.score is not None and self.replays.code is not None

    def copy_replay(self) -> None:
        """Key C or the win screen's button: the won game's code to the clipboard."""
        if self.replay_offered:
            self.replays.copy()

    def _class_news(self) -> None:
        """What the class server said since the last frame, as notices."""
        if self.classroom is None:
            return
        for event in self.classroom.poll():
            self._class_event(event)

    def _class_event(self, event: Event) -> None:
        if event.kind == "joined":
            ch: Challenge = event.value
            self.challenge = ch
            self.notify(t("desk.class.joined", id=ch.id, n=ch.settings.n_atoms, name=event.name))
            if self.game.sim.time == 0.0:  # not begun: switch to the challenge's atoms now
                self.restart()
            else:
                self.notify(t("desk.class.press_r"))
        elif event.kind == "result":
            doc = event.value
            self.notify(
                t("desk.class.result", n=doc["rank"], score=doc["score"], frames=doc["frames"])
            )
        elif event.kind == "refused":
            self.notify(t("desk.class.refused", reason=event.value))
        else:
            self.notify(t("desk.class.unreachable", problem=event.value))

    def help_rows(self) -> list[tuple[str, str]]:
        """The help overlay's (keys, what they do) rows in the chosen language."""
        mouse = Binding((), *MOUSE_HELP[0], more=(MOUSE_HELP[1][1],))
        rows = []
        for b in [*self.input.bindings, mouse]:
            rows.append((_word(b.label), t(b.help, **HELP_ARGS)))
            rows.extend(("", t(line, **HELP_ARGS)) for line in b.more)
        return rows

    # -- one frame -------------------------------------------------------------------------------
    def handle_events(self, events: Sequence[pygame.event.Event]) -> None:
        for event in events:
            self._window_event(event)
            self.input.handle(event)

    def frame(self, wall_seconds: float | None = None) -> None:
        """Events, physics, drawing, presenting.

        wall_seconds: elapsed wall time to advance by (x 30 x speed, at most
        MAX_WALL_STEP); None advances exactly one physics frame x speed (headless runs).
        """
        t0 = time.perf_counter()
        self.handle_events(pygame.event.get())
        if not self.running:
            return
        played = self.advance(wall_seconds)
        t1 = time.perf_counter()
        self.draw()
        self.present()
        t2 = time.perf_counter()
        wall = wall_seconds if wall_seconds is not None else t2 - t0
        self.stats.add(wall, t1 - t0, t2 - t1, played)

    def advance(self, wall_seconds: float | None = None) -> float:
        """The physics for one frame (see `frame`), then the charts record it if it moved.

        Returns the seconds of play it advanced (at 1x; 0 while paused).
        """
        paused = self.game.paused
        if self.autopilot is not None:
            self.autopilot.steer(self.game)  # the trap for this frame, from the gas now
        if wall_seconds is None:
            self.game.run_frames(1)
            dt = 1.0 / FPS
            played = 0.0 if paused else dt
        else:
            self.game.update(wall_seconds)
            dt = max(0.0, wall_seconds)
            played = 0.0 if paused else min(dt, MAX_WALL_STEP)
        self.anim_time += dt
        self.notices.now = self.anim_time
        self._class_news()
        if self.scores.name_box is not None:
            self.scores.name_box.update(dt)
        self.charts.observe(self.game.sim)
        return played

    def draw(self) -> None:
        title = t(TITLE)
        if self.window.win.title != title:  # the settings screen chose another language
            self.window.win.title = title
        lay = self.layout
        surface = self.window.surface
        surface.fill((0, 0, 0))
        pen = Pen(surface, lay.scale, lay.scene.topleft)
        game = self.game
        self.scene.draw(pen, game, self.anim_time)
        self._draw_widgets(pen, lay)
        if game.score is not None:
            self.scene.draw_score(pen, game.score)
        elif (reason := game.too_few_atoms) is not None:
            self.scene.draw_too_few(pen, reason)
        elif game.paused and game.sim.time == 0.0 and self.overlay is None:
            self.scene.draw_start_hint(pen)
        offered = self.replay_offered
        bottom = REPLAY_RECT.top if offered else PLAY_RECT.bottom  # the table and notices
        self._draw_overlay(pen, bottom)
        if offered:  # over a full table's lowest edge: the button stays whole
            self.scene.draw_replay_button(pen, t("replay.button"), self._hovering("replay"))
        self.scene.draw_notices(pen, self.visible_notices, bottom)
        self.charts.draw(surface, lay.charts, lay.scale)

    def _draw_widgets(self, pen: Pen, lay: Layout) -> None:
        pointer = self.input.pointer
        mouse = Pointer(lay.to_scene(pointer) if pointer else None, self.input.button_down)
        if self.input.mode in (Mode.NAME, Mode.SETTINGS, Mode.CONFIRM_CLEAR):
            mouse = Pointer()  # modal: the buttons do not answer, so do not light up
        self.controls.draw(pen, mouse, self.game)

    def _hovering(self, target: str) -> bool:
        pointer = self.input.pointer
        modal = self.input.mode in (Mode.NAME, Mode.SETTINGS, Mode.CONFIRM_CLEAR)
        return not modal and pointer is not None and self.target_at(pointer) == target

    def _draw_overlay(self, pen: Pen, bottom: int = PLAY_RECT.bottom) -> None:
        game, overlay = self.game, self.overlay
        if self.scores.name_box is not None:
            self.scene.draw_name_entry(pen, self.scores.name_box, t("win.top10"))
        elif overlay == "help":
            self.scene.draw_help(pen, self.help_rows(), self.stats.lines())
        elif overlay == "table":
            confirming = self.input.mode is Mode.CONFIRM_CLEAR
            self.scene.draw_table(
                pen,
                self.scores.table.entries,
                self.scores.stored_rank,
                self.scores.footer(confirming),
                top=UNDER_MESSAGE if game.score is not None else None,
                bottom=bottom,
            )
        elif overlay == "settings":
            self.scene.draw_settings(
                pen, self.options.rows(), self.options.row, self.options.footer()
            )

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
        self.window.close()
        pygame.display.quit()


def stderr_log(text: str) -> None:
    print(note_line(None, text), file=sys.stderr, flush=True)


__all__ = [
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
