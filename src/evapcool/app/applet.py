"""The playable applet: window, event handling, main loop, screenshot.

The scene is drawn in logical pixels on `canvas` (640 x 672 plus the width of
any side panels to its right) and scaled to the window with the aspect kept.
Keys go through one table, `App.bindings`, which also writes the help overlay.
Modal states (typing a name, the settings screen, confirming a reset) see the
keys first, so typing "r" into a name never restarts the game.
"""

from __future__ import annotations

import io
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Protocol

import pygame

from evapcool.app.charts import CHART_BUTTON_RECT, ChartColumn, chart_button_looks
from evapcool.app.storage import folder_problem, scores_path, settings_path
from evapcool.fileio import atomic_write_bytes
from evapcool.game import settings as settings_mod
from evapcool.game.highscores import NAME_MAX, HighScoreTable
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN, Game
from evapcool.game.settings import Settings, describe, load_settings, save_settings
from evapcool.physics.simulation import FPS
from evapcool.view.icons import button_looks, window_icon
from evapcool.view.scene import (
    KNOB_RADIUS,
    PAUSE_RECT,
    RESTART_RECT,
    SCENE_SIZE,
    SLIDER_RECT,
    Scene,
    scale_for,
)
from evapcool.view.text_input import CANCEL, SUBMIT, TextInput
from evapcool.view.widgets import ImageButton, MouseState, Slider, ToggleButton

TITLE = "Evaporation cooling"
#: Display frame rate we aim for; physics time follows the wall clock regardless.
TARGET_FPS = 60
#: Trap height change per arrow-key press (key repeat is on), px.
HEIGHT_STEP = 5.0
#: How long a notice (damaged file, read-only folder...) stays on screen, s.
NOTICE_SECONDS = 8.0
#: At most this many notices at once; older ones make room.
NOTICE_MAX = 3
_SUBMIT_KEYS = (pygame.K_RETURN, pygame.K_KP_ENTER)


class Panel(Protocol):
    """A side panel drawn to the right of the scene (high scores, condensate...)."""

    width: int

    def draw(self, surface: pygame.Surface, app: App) -> None:
        """Draw on a surface `width` x 672 (logical pixels)."""

    def handle_event(self, event: pygame.event.Event, pos: tuple[float, float] | None) -> bool:
        """Take an event (pos: mouse position in panel pixels, or None); True if used."""


@dataclass(frozen=True)
class Binding:
    """Keys, how the help overlay names them, what they do, and the action."""

    keys: tuple[int, ...]
    label: str
    help: str
    action: Callable[[App], None]
    #: Continuation lines for the help overlay (shown under this row).
    more: tuple[str, ...] = ()


def default_bindings() -> list[Binding]:
    """The applet's keyboard controls (the help overlay lists exactly these)."""
    return [
        Binding((pygame.K_SPACE,), "Space", "pause / play", lambda app: app.game.toggle_pause()),
        Binding((pygame.K_r,), "R", "restart: new atoms, trap at 400, paused", App.restart),
        Binding(
            (pygame.K_LEFT, pygame.K_DOWN),
            "Left, Down",
            f"lower the trap by {HEIGHT_STEP:g} px",
            lambda app: app.game.nudge_height(-HEIGHT_STEP),
        ),
        Binding(
            (pygame.K_RIGHT, pygame.K_UP),
            "Right, Up",
            f"raise the trap by {HEIGHT_STEP:g} px",
            lambda app: app.game.nudge_height(HEIGHT_STEP),
        ),
        Binding(
            (pygame.K_s,), "S", "one frame forward (while paused)", lambda app: app.game.step()
        ),
        Binding(
            (pygame.K_PLUS, pygame.K_EQUALS, pygame.K_KP_PLUS),
            "+",
            "faster (up to 4x)",
            lambda app: app.game.faster(),
        ),
        Binding(
            (pygame.K_MINUS, pygame.K_KP_MINUS),
            "-",
            "slower (down to 1/4x)",
            lambda app: app.game.slower(),
        ),
        Binding((pygame.K_e,), "E", "energy chart on / off", App.toggle_energy),
        Binding((pygame.K_g,), "G", "path-to-condensation chart on / off", App.toggle_path),
        Binding((pygame.K_t,), "T", "high-score table on / off", App.toggle_table),
        Binding(
            (pygame.K_DELETE, pygame.K_x),
            "Delete, X",
            "clear the high-score table...",
            App.ask_reset,
            more=("...asks first: Y clears it, N or Esc keeps it",),
        ),
        Binding(
            _SUBMIT_KEYS,
            "Enter",
            "after a name is stored: next player",
            App.next_player,
        ),
        Binding(
            (pygame.K_o,),
            "O",
            "settings (R restarts with them)",
            App.open_settings,
            more=("Up/Down choose, Left/Right change, Enter/O save",),
        ),
        Binding((pygame.K_F11,), "F11", "full screen on / off", App.toggle_fullscreen),
        Binding((pygame.K_h, pygame.K_F1), "H, F1", "this help on / off", App.toggle_help),
        Binding((pygame.K_ESCAPE,), "Esc", "close a panel, leave full screen, or quit", App.escape),
    ]


#: Mouse controls, listed in the help overlay after the keys.
MOUSE_HELP = [
    ("Mouse", "play/pause, restart and chart buttons;"),
    ("", f"drag the slider: trap height {HEIGHT_MIN:g} to {HEIGHT_MAX:g} px"),
]


class App:
    """The applet: owns the window, the game, the widgets and the main loop."""

    def __init__(
        self,
        game: Game,
        *,
        fullscreen: bool = False,
        data_dir: str | os.PathLike[str] | None = None,
        config_dir: str | os.PathLike[str] | None = None,
        settings: Settings | None = None,
        overrides: Mapping[str, object] | None = None,
        notices: Sequence[str] = (),
    ) -> None:
        """game: what to play. data_dir / config_dir: where scores and settings live
        (default $EVAPCOOL_DATA_DIR / $EVAPCOOL_CONFIG_DIR, else the user folders).
        settings: the saved settings (read from config_dir if None); overrides: this
        run's command-line values on top (never saved); notices: shown at start.
        """
        pygame.display.init()
        pygame.font.init()
        self.game = game
        self.running = True
        #: The overlay over the play area: None, "help", "table" or "settings".
        self.overlay: str | None = None
        self.fullscreen = False
        #: Seconds of animation (wall clock, or 1/30 per headless frame): fades, toasts.
        self.anim_time = 0.0
        self._notices: list[tuple[str, float]] = []
        for text in notices:
            self.notify(text)

        self.scores = HighScoreTable(scores_path(data_dir))
        problem = folder_problem(self.scores.path)
        if problem:
            self.notify(f"High scores cannot be saved ({problem}); they last this session only.")
        for text in self.scores.take_notices():
            self.notify(text)
        self.name_box: TextInput | None = None
        self.stored_rank: int | None = None
        self.ready_for_next = False
        self.confirm_reset = False

        self.settings_path = settings_path(config_dir)
        if settings is None:
            settings, loaded_notices = load_settings(self.settings_path)
            for text in loaded_notices:
                self.notify(text)
        self.settings = settings
        self.overrides = {k: v for k, v in (overrides or {}).items() if v is not None}
        self.settings_draft = settings
        self.settings_row = 0

        self.charts = ChartColumn()
        self.panels: list[Panel] = []
        self.bindings: list[Binding] = []
        self._keymap: dict[int, Binding] = {}
        for binding in default_bindings():
            self.bind(binding)
        self._mouse_xy: tuple[float, float] = (-1.0, -1.0)
        self._mouse_down = False
        self._build_canvas()
        self._windowed_size = self.canvas.get_size()

        pygame.display.set_caption(TITLE)
        pygame.display.set_icon(window_icon(64))
        self.window = pygame.display.set_mode(self._windowed_size, pygame.RESIZABLE)
        pygame.key.set_repeat(300, 40)  # hold an arrow key to sweep the trap
        pygame.key.stop_text_input()  # no IME / on-screen keyboard until a name is asked
        game.on_win.append(self._on_win)
        if fullscreen:
            self.toggle_fullscreen()

        scene = self.scene_surface
        self.pause_button = ToggleButton(
            scene, PAUSE_RECT, button_looks("play"), button_looks("pause"), is_on=True
        )
        self.restart_button = ImageButton(scene, RESTART_RECT, *button_looks("restart"))
        self.slider = Slider(
            scene,
            SLIDER_RECT,
            HEIGHT_MIN,
            HEIGHT_MAX,
            game.trap_height,
            knob_radius=KNOB_RADIUS,
            label="Trap height",
        )
        self.chart_button = ImageButton(scene, CHART_BUTTON_RECT, *chart_button_looks())
        self.clock = pygame.time.Clock()

    # -- extension points ----------------------------------------------------------------
    def bind(self, binding: Binding) -> None:
        """Add (or override) a key binding; it shows up in the help overlay."""
        self.bindings = [b for b in self.bindings if not set(b.keys) & set(binding.keys)]
        self.bindings.append(binding)
        self._keymap = {k: b for b in self.bindings for k in b.keys}

    def add_panel(self, panel: Panel) -> None:
        """Widen the canvas by a panel to the right of the scene (window keeps its scale)."""
        self._set_panels([*self.panels, panel])

    def remove_panel(self, panel: Panel) -> None:
        """Take a panel away again; the canvas and the window narrow to match."""
        self._set_panels([p for p in self.panels if p is not panel])

    def _set_panels(self, panels: list[Panel]) -> None:
        # Keep the windowed scale: a window at 1.5x stays at 1.5x, only wider or narrower.
        windowed = self._windowed_size if self.fullscreen else self.window.get_size()
        scale, _ = scale_for(windowed, self.canvas.get_size())
        self.panels = panels
        self._build_canvas()
        w, h = self.canvas.get_size()
        self._windowed_size = (round(w * scale), round(h * scale))
        if not self.fullscreen:
            self.window = pygame.display.set_mode(self._windowed_size, pygame.RESIZABLE)

    def _build_canvas(self) -> None:
        width = SCENE_SIZE[0] + sum(p.width for p in self.panels)
        self.canvas = pygame.Surface((width, SCENE_SIZE[1]))
        self.scene_surface = self.canvas.subsurface(pygame.Rect((0, 0), SCENE_SIZE))
        if hasattr(self, "scene"):  # keep its state (the condensate's fade) across layouts
            self.scene.surface = self.scene_surface
        else:
            self.scene = Scene(self.scene_surface)
        for widget in ("pause_button", "restart_button", "slider", "chart_button"):
            if hasattr(self, widget):
                getattr(self, widget).surface = self.scene_surface

    # -- notices -------------------------------------------------------------------------------
    def notify(self, text: str) -> None:
        """Show a message in the notice area for NOTICE_SECONDS."""
        self._notices.append((text, self.anim_time + NOTICE_SECONDS))
        del self._notices[:-NOTICE_MAX]

    @property
    def visible_notices(self) -> list[str]:
        return [text for text, until in self._notices if until > self.anim_time]

    # -- actions ------------------------------------------------------------------------------
    @property
    def help_visible(self) -> bool:
        return self.overlay == "help"

    @help_visible.setter
    def help_visible(self, on: bool) -> None:
        if on:
            self.overlay = "help"
        elif self.overlay == "help":
            self.overlay = None

    def run_settings(self) -> Settings:
        """The settings a restart applies: the saved ones with this run's overrides on top."""
        try:
            return settings_mod.with_overrides(self.settings, **self.overrides)
        except ValueError as exc:
            self.notify(f"Command-line options dropped ({exc}).")
            self.overrides = {}
            return self.settings

    def restart(self) -> None:
        """New atoms with the current settings, trap at 400, paused; ends any name entry."""
        s = self.run_settings()
        config = replace(
            self.game.config,
            n_atoms=s.n_atoms,
            radius=s.radius,
            tc_exponent=s.tc_exponent,
            escape=s.escape,
        )
        try:
            self.game.restart(config)
        except ValueError as exc:  # settings are validated; this is a guard, not a path
            self.notify(f"Those settings do not work ({exc}); kept the previous ones.")
            self.game.restart()
        self._close_name_entry()
        self.ready_for_next = False
        self.stored_rank = None
        self.confirm_reset = False
        if self.overlay == "table":
            self.overlay = None
        self.charts.reset()
        self.slider.set_value(self.game.trap_height)

    def _toggle_overlay(self, name: str) -> None:
        self.overlay = None if self.overlay == name else name

    def toggle_help(self) -> None:
        self._toggle_overlay("help")

    def toggle_table(self) -> None:
        self._toggle_overlay("table")
        self.confirm_reset = False

    def ask_reset(self) -> None:
        """Show the table and ask before clearing it (Y clears, N or Esc keeps)."""
        self.overlay = "table"
        self.confirm_reset = True

    def next_player(self) -> None:
        """Enter after a stored (or skipped) score: a fresh game for the next student."""
        if self.ready_for_next:
            self.restart()

    def _toggle_chart(self, which: str) -> None:
        attr = f"show_{which}"
        setattr(self.charts, attr, not getattr(self.charts, attr))
        shown = any(p is self.charts for p in self.panels)
        if self.charts.visible and not shown:
            self.add_panel(self.charts)
        elif not self.charts.visible and shown:
            self.remove_panel(self.charts)

    def toggle_energy(self) -> None:
        self._toggle_chart("energy")

    def toggle_path(self) -> None:
        self._toggle_chart("path")

    def open_settings(self) -> None:
        self.overlay = "settings"
        self.settings_draft = self.settings
        self.settings_row = 0

    def _close_settings(self, save: bool) -> None:
        self.overlay = None
        draft = self.settings_draft
        if not save or draft == self.settings:
            return
        previous, self.settings = self.settings, draft
        self.overrides = {}  # a choice made here beats the command line for the rest of the run
        # Only the fields changed here go over the file: another window's choices stay.
        problems = save_settings(draft, self.settings_path, base=previous)
        for text in problems:
            self.notify(text)
        if not problems:
            self.notify("Settings saved. Press R (restart) to play with them.")

    def _settings_key(self, key: int) -> None:
        names = settings_mod.FIELD_NAMES
        if key == pygame.K_UP:
            self.settings_row = (self.settings_row - 1) % len(names)
        elif key == pygame.K_DOWN:
            self.settings_row = (self.settings_row + 1) % len(names)
        elif key in (pygame.K_LEFT, pygame.K_RIGHT):
            d = 1 if key == pygame.K_RIGHT else -1
            self.settings_draft = settings_mod.step(
                self.settings_draft, names[self.settings_row], d
            )
        elif key in (*_SUBMIT_KEYS, pygame.K_o):
            self._close_settings(save=True)
        elif key == pygame.K_ESCAPE:
            self._close_settings(save=False)

    # -- the win and the score table ----------------------------------------------------------
    def _on_win(self, game: Game) -> None:
        score, seconds = game.score or 0, game.won_at or 0.0
        if self.scores.qualifies(score, seconds):
            self.overlay = None  # the name box must be seen
            self.name_box = TextInput(max_length=NAME_MAX)
            pygame.key.start_text_input()
        else:
            self.notify(f"Score {score} is not in the top 10 this time. Enter: next player.")
            self.ready_for_next = True

    def _close_name_entry(self) -> None:
        if self.name_box is not None:
            self.name_box = None
            pygame.key.stop_text_input()

    def _store_name(self, name: str) -> None:
        game = self.game
        self._close_name_entry()
        self.stored_rank = self.scores.add(name, game.score or 0, game.won_at or 0.0)
        for text in self.scores.take_notices():
            self.notify(text)
        self.overlay = "table"
        self.ready_for_next = True

    def _modal_event(self, event: pygame.event.Event) -> bool:
        """Keys and typed text for a modal state; True if it took the event."""
        if self.confirm_reset:
            if event.type == pygame.KEYDOWN:
                if event.key == pygame.K_y:
                    self.confirm_reset = False
                    self.stored_rank = None
                    if self.scores.reset():
                        self.notify("The high-score table was cleared.")
                    for text in self.scores.take_notices():
                        self.notify(text)
                elif event.key in (pygame.K_n, pygame.K_ESCAPE):
                    self.confirm_reset = False
            return True  # nothing else happens until the question is answered
        if self.name_box is not None:
            result = self.name_box.handle_event(event)
            if result == SUBMIT:
                self._store_name(self.name_box.value or "")
            elif result == CANCEL:
                self._close_name_entry()
                self.notify("Score not stored. Enter: next player.")
                self.ready_for_next = True
            return True  # every key goes to the name: Space, R, S... are letters here
        if self.overlay == "settings":
            if event.type == pygame.KEYDOWN:
                self._settings_key(event.key)
            return True
        return event.type == pygame.TEXTINPUT  # typed text outside the name box: unused

    def toggle_fullscreen(self) -> None:
        if self.fullscreen:
            self.window = pygame.display.set_mode(self._windowed_size, pygame.RESIZABLE)
        else:
            self._windowed_size = self.window.get_size()
            self.window = pygame.display.set_mode((0, 0), pygame.FULLSCREEN)
        self.fullscreen = not self.fullscreen

    def escape(self) -> None:
        """Esc peels one layer: an overlay (help, table), then full screen, then the applet."""
        if self.overlay is not None:
            self.overlay = None
        elif self.fullscreen:
            self.toggle_fullscreen()
        else:
            self.running = False

    def help_rows(self) -> list[tuple[str, str]]:
        rows = []
        for b in self.bindings:
            rows.append((b.label, b.help))
            rows.extend(("", line) for line in b.more)
        return rows + MOUSE_HELP

    # -- input ----------------------------------------------------------------------------------
    def to_canvas(self, pos: tuple[float, float]) -> tuple[float, float]:
        """Window pixels to canvas (logical) pixels."""
        s, rect = scale_for(self.window.get_size(), self.canvas.get_size())
        return ((pos[0] - rect.x) / s, (pos[1] - rect.y) / s)

    def _panel_at(self, xy: tuple[float, float]) -> tuple[Panel | None, tuple[float, float]]:
        x0 = SCENE_SIZE[0]
        for panel in self.panels:
            if x0 <= xy[0] < x0 + panel.width:
                return panel, (xy[0] - x0, xy[1])
            x0 += panel.width
        return None, xy

    def _offer_to_panels(self, event: pygame.event.Event, pos: tuple[float, float] | None) -> bool:
        """Mouse events go to the panel under the mouse, other events to each in turn."""
        if pos is not None:
            panel, local = self._panel_at(pos)
            return panel is not None and panel.handle_event(event, local)
        return any(p.handle_event(event, None) for p in self.panels)

    def handle_events(self, events: Sequence[pygame.event.Event]) -> MouseState:
        """Apply the frame's events; returns the mouse state for the widgets."""
        clicked = False
        press_xy: tuple[float, float] | None = None
        for event in events:
            if event.type == pygame.QUIT:
                self.running = False
                continue
            if event.type in (pygame.KEYDOWN, pygame.TEXTINPUT) and self._modal_event(event):
                continue
            pos = self.to_canvas(event.pos) if hasattr(event, "pos") else None
            if (
                self.panels
                and self._offer_to_panels(event, pos)
                and event.type in (pygame.KEYDOWN, pygame.MOUSEBUTTONDOWN)
            ):
                continue  # taken; motion and release still update the mouse below
            if event.type == pygame.KEYDOWN:
                binding = self._keymap.get(event.key)
                if binding is None and getattr(event, "unicode", "") in ("+", "-"):
                    binding = self._keymap.get(ord(event.unicode))
                if binding is not None:
                    binding.action(self)
            elif event.type == pygame.MOUSEMOTION:
                self._mouse_xy = pos
            elif event.type == pygame.MOUSEBUTTONDOWN and event.button == 1:
                self._mouse_xy = pos
                self._mouse_down = True
                if not clicked:
                    clicked, press_xy = True, pos
            elif event.type == pygame.MOUSEBUTTONUP and event.button == 1:
                self._mouse_xy = pos
                self._mouse_down = False
        if clicked:
            # A press and release within one frame still counts as a press there.
            return MouseState(press_xy, True, True)
        return MouseState(self._mouse_xy, False, self._mouse_down)

    # -- one frame -------------------------------------------------------------------------------
    def frame(self, wall_seconds: float | None = None) -> None:
        """Events, physics, drawing, presenting.

        wall_seconds: elapsed wall time to advance by (x 30 x speed); None advances
        exactly one physics frame x speed (headless runs, benchmarks, tests).
        """
        mouse = self.handle_events(pygame.event.get())
        if not self.running:
            return
        self.advance(wall_seconds)
        self.draw(mouse)
        self.present()

    def advance(self, wall_seconds: float | None = None) -> None:
        """The physics for one frame (see `frame`), then the charts record it if it moved."""
        if wall_seconds is None:
            self.game.run_frames(1)
        else:
            self.game.update(wall_seconds)
        dt = 1.0 / FPS if wall_seconds is None else max(0.0, wall_seconds)
        self.anim_time += dt
        if self.name_box is not None:
            self.name_box.update(dt)
        self.charts.observe(self.game.sim)

    def draw(self, mouse: MouseState) -> None:
        game = self.game
        self.scene.draw(game, self.anim_time)
        self.pause_button.set_state(game.paused)
        game.paused = self.pause_button.control(mouse)
        if self.restart_button.control(mouse):
            self.restart()
        self.slider.enabled = not game.won
        if not self.slider.sliding:
            self.slider.set_value(game.trap_height)
        value = self.slider.control(mouse)
        if self.slider.sliding:
            game.set_trap_height(value)
        if self.chart_button.control(mouse):
            self.toggle_energy()
        if game.score is not None:
            self.scene.draw_score(game.score)
        elif game.all_escaped:
            self.scene.draw_empty()
        elif game.paused and game.sim.time == 0.0 and self.overlay is None:
            self.scene.draw_start_hint()
        if self.name_box is not None:
            self.scene.draw_name_entry(self.name_box, "Top 10! Type your name:")
        if self.overlay == "help":
            self.scene.draw_help(self.help_rows())
        elif self.overlay == "table":
            self.scene.draw_table(self.scores.entries, self.stored_rank, self._table_footer())
        elif self.overlay == "settings":
            self.scene.draw_settings(
                describe(self.settings_draft), self.settings_row, self._settings_footer()
            )
        self.scene.draw_notices(self.visible_notices)
        x0 = SCENE_SIZE[0]
        for panel in self.panels:
            sub = self.canvas.subsurface(pygame.Rect(x0, 0, panel.width, SCENE_SIZE[1]))
            panel.draw(sub, self)
            x0 += panel.width

    def _table_footer(self) -> list[str]:
        if self.confirm_reset:
            return ["Clear all scores?  Y: yes   N or Esc: no"]
        if self.ready_for_next:
            return ["Enter: next player"]
        return ["T: close   Delete or X: clear the table"]

    def _settings_footer(self) -> list[str]:
        lines = ["Up/Down choose, Left/Right change", "Enter or O: save   Esc: cancel"]
        if self.overrides:
            names = ", ".join(sorted(self.overrides))
            lines.append(f"This run uses command-line {names} until you save here.")
        return lines

    def present(self) -> None:
        """Copy the canvas to the window, scaled with its aspect kept."""
        window = self.window = pygame.display.get_surface()
        if window.get_size() == self.canvas.get_size():
            window.blit(self.canvas, (0, 0))
        else:
            _, rect = scale_for(window.get_size(), self.canvas.get_size())
            window.fill((0, 0, 0))
            window.blit(pygame.transform.smoothscale(self.canvas, rect.size), rect)
        pygame.display.flip()

    # -- loops -------------------------------------------------------------------------------------
    def run(self) -> None:
        """Interactive loop at the display's pace; physics follows the wall clock."""
        self.clock.tick()
        while self.running:
            elapsed = self.clock.tick(TARGET_FPS) / 1000.0
            self.frame(elapsed)

    def run_frames(self, n: int) -> None:
        """Play n frames as fast as possible, each advancing 1 physics frame x speed."""
        self.game.paused = False
        if n == 0:  # still draw once, so a screenshot shows the start
            self.draw(MouseState(self._mouse_xy))
            self.present()
        for _ in range(n):
            if not self.running:
                break
            self.frame(None)

    def screenshot(self, path: str | os.PathLike[str]) -> None:
        """Save the window as a PNG (written atomically)."""
        buf = io.BytesIO()
        pygame.image.save(self.window, buf, "png")
        atomic_write_bytes(path, buf.getvalue())

    def close(self) -> None:
        pygame.display.quit()


__all__ = ["TARGET_FPS", "App", "Binding", "Panel", "default_bindings"]
