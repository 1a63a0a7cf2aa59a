"""The applet's input state machine: which mode it is in, and what each event does there.

Modes: PLAY (the game has the keys and the mouse), DRAG (the trap slider follows the
mouse), HELP and TABLE (overlays that leave the game's keys working), SETTINGS,
CONFIRM_CLEAR and NAME (modal: they take every key until they are answered). Events
are handled one at a time, in order, so nothing is lost or mixed between frames: a
press, a drag and a release in one frame are three steps.

The machine knows nothing of windows or drawing: it calls a `Controls` object (the app's
`Commands`) for hit tests and actions, the `Scores` (name box, table) and the
`SettingsScreen`, so it is tested with stand-ins.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from enum import Enum
from typing import Protocol

import pygame

Point = tuple[float, float]


class Mode(Enum):
    PLAY = "play"
    DRAG = "drag"
    HELP = "help"
    TABLE = "table"
    CONFIRM_CLEAR = "confirm-clear"
    SETTINGS = "settings"
    NAME = "name"


#: Modes that take every key until answered.
MODAL = (Mode.CONFIRM_CLEAR, Mode.SETTINGS, Mode.NAME)
#: Overlay drawn in each mode (DRAG shows the one it was started from).
OVERLAY = {Mode.HELP: "help", Mode.TABLE: "table", Mode.CONFIRM_CLEAR: "table"}
OVERLAY[Mode.SETTINGS] = "settings"
SUBMIT_KEYS = (pygame.K_RETURN, pygame.K_KP_ENTER)


class Controls(Protocol):
    """What the machine asks of the app (window pixels in, actions out)."""

    def target_at(self, pos: Point) -> str | None:
        """'pause', 'restart', 'slider', 'chart', 'replay', 'close:<chart>' or None."""

    def slider_press(self, pos: Point) -> bool: ...
    def slider_drag(self, pos: Point) -> None: ...
    def slider_release(self) -> None: ...
    def toggle_pause(self) -> None: ...
    def restart(self) -> None: ...
    def toggle_chart(self, name: str) -> None: ...
    def copy_replay(self) -> None: ...
    def save_run(self, every_frame: bool = False) -> None: ...
    def leave(self) -> None:
        """Esc with nothing open: leave full screen, else quit."""

    def quit(self) -> None: ...


class Scores(Protocol):
    """The name box and the high-score table (app.scoring.Scoreboard)."""

    def name_event(self, event: pygame.event.Event) -> str | None:
        """A key or typed text for the name box: 'submit', 'cancel' or other."""

    def clear(self) -> None: ...


class SettingsScreen(Protocol):
    """The settings screen (app.options.SettingsEditor)."""

    def open(self) -> None: ...
    def key(self, key: int) -> None: ...
    def close(self, save: bool) -> None: ...


@dataclass(frozen=True)
class Binding:
    """Keys, how the help overlay names them, what they do, and the action.

    mode: the machine's mode the key switches to (None: an action in the current one).
    """

    keys: tuple[int, ...]
    label: str
    help: str
    action: Callable[[Controls], object] | None = None
    mode: Mode | None = None
    #: Continuation lines for the help overlay (shown under this row).
    more: tuple[str, ...] = ()
    #: A drag in progress ends first (keys that start a new game: R, Enter).
    ends_drag: bool = False
    #: The action starts a new game (unless it answers False): the machine resets after it.
    starts_game: bool = False


class InputMachine:
    """Feeds events to the current mode; `mode`, `overlay` and `pointer` say where it is."""

    def __init__(
        self,
        controls: Controls,
        scores: Scores,
        settings: SettingsScreen,
        bindings: Iterable[Binding] = (),
    ) -> None:
        self.controls = controls
        self.scores = scores
        self.settings = settings
        self.mode = Mode.PLAY
        self._after_drag = Mode.PLAY
        #: The mouse: position in window pixels (None before it is seen) and left button.
        self.pointer: Point | None = None
        self.button_down = False
        self.bindings: list[Binding] = []
        self._keymap: dict[int, Binding] = {}
        for b in bindings:
            self.bind(b)

    # -- the key table -------------------------------------------------------------------
    def bind(self, binding: Binding) -> None:
        """Add (or override) a key binding; it shows up in the help overlay."""
        self.bindings = [b for b in self.bindings if not set(b.keys) & set(binding.keys)]
        self.bindings.append(binding)
        self._keymap = {k: b for b in self.bindings for k in b.keys}

    def binding_for(self, event: pygame.event.Event) -> Binding | None:
        b = self._keymap.get(event.key)
        text = getattr(event, "unicode", "")
        if b is None and text in ("+", "-"):  # shifted '+' on any keyboard layout
            b = self._keymap.get(ord(text))
        return b

    @property
    def overlay(self) -> str | None:
        """'help', 'table', 'settings' or None: what is drawn over the play area."""
        mode = self._after_drag if self.mode is Mode.DRAG else self.mode
        return OVERLAY.get(mode)

    # -- transitions the app starts -----------------------------------------------------------
    def set_mode(self, mode: Mode) -> None:
        """Switch mode; a drag in progress ends first (it never outlives its mode)."""
        self.end_drag()
        self.mode = mode

    def end_drag(self) -> None:
        if self.mode is Mode.DRAG:
            self.controls.slider_release()
            self.mode = self._after_drag

    def ask_name(self) -> None:
        """A score for the table: the name box takes the keyboard."""
        self.set_mode(Mode.NAME)

    def reset(self) -> None:
        """After a restart (its own keys and button, or the app's): play, no drag, no table;
        help stays if it was open."""
        self.set_mode(Mode.HELP if self.mode is Mode.HELP else Mode.PLAY)

    # -- events --------------------------------------------------------------------------------
    def handle(self, event: pygame.event.Event) -> None:
        kind = event.type
        if kind == pygame.QUIT:
            self.controls.quit()
        elif kind == pygame.KEYDOWN:
            self._key(event)
        elif kind == pygame.TEXTINPUT:
            if self.mode is Mode.NAME:
                self._name(event)
        elif kind == pygame.MOUSEMOTION:
            self.pointer = event.pos
            if self.mode is Mode.DRAG:
                self.controls.slider_drag(event.pos)
        elif kind == pygame.MOUSEBUTTONDOWN and event.button == 1:
            self._press(event.pos)
        elif kind == pygame.MOUSEBUTTONUP and event.button == 1:
            self.pointer, self.button_down = event.pos, False
            if self.mode is Mode.DRAG:
                self.controls.slider_drag(event.pos)
                self.end_drag()
        elif kind == pygame.WINDOWLEAVE:
            if not self.button_down:  # a drag goes on outside: SDL keeps the mouse
                self.pointer = None
        elif kind == pygame.WINDOWFOCUSLOST:  # Alt+Tab: the release will not come
            self.pointer, self.button_down = None, False
            self.end_drag()

    def _press(self, pos: Point) -> None:
        # A press while dragging means the release was lost (outside the window, a
        # touch screen...): the drag is over, and this press counts on its own.
        self.end_drag()
        self.pointer, self.button_down = pos, True
        if self.mode in MODAL:
            return
        target = self.controls.target_at(pos)
        if target == "slider":
            if self.controls.slider_press(pos):
                self._after_drag, self.mode = self.mode, Mode.DRAG
        elif target == "pause":
            self.controls.toggle_pause()
        elif target == "restart":
            self.controls.restart()
            self.reset()
        elif target == "chart":
            self.controls.toggle_chart("energy")
        elif target == "replay":
            self.controls.copy_replay()
        elif target == "save":
            self.controls.save_run()
        elif target and target.startswith("close:"):
            self.controls.toggle_chart(target.split(":", 1)[1])

    def _key(self, event: pygame.event.Event) -> None:
        mode = self.mode
        if mode is Mode.NAME:
            self._name(event)
        elif mode is Mode.SETTINGS:
            self._settings(event.key)
        elif mode is Mode.CONFIRM_CLEAR:
            if event.key == pygame.K_y:
                self.scores.clear()
                self.mode = Mode.TABLE
            elif event.key in (pygame.K_n, pygame.K_ESCAPE):
                self.mode = Mode.TABLE
        else:
            binding = self.binding_for(event)
            if binding is not None:
                self._run(binding)

    def _run(self, binding: Binding) -> None:
        """A key of the table in PLAY, DRAG, HELP or TABLE."""
        if binding.ends_drag:
            self.end_drag()
        shown = self.overlay
        target = binding.mode
        if target is not None:
            if target is Mode.PLAY:  # Esc: close what is open, else leave
                if shown is not None:
                    self.set_mode(Mode.PLAY)
                else:
                    self.end_drag()
                    self.controls.leave()
            elif target is Mode.SETTINGS:
                self.set_mode(Mode.SETTINGS)
                self.settings.open()
            elif target is Mode.CONFIRM_CLEAR:
                self.set_mode(target)
            else:  # help or table: a second press closes it
                self.set_mode(Mode.PLAY if OVERLAY[target] == shown else target)
        if binding.action is not None:
            started = binding.action(self.controls)
            if binding.starts_game and started is not False:
                self.reset()

    def _settings(self, key: int) -> None:
        if key in (*SUBMIT_KEYS, pygame.K_o):
            self.mode = Mode.PLAY
            self.settings.close(save=True)
        elif key == pygame.K_ESCAPE:
            self.mode = Mode.PLAY
            self.settings.close(save=False)
        else:
            self.settings.key(key)

    def _name(self, event: pygame.event.Event) -> None:
        result = self.scores.name_event(event)
        if result == "submit":
            self.mode = Mode.TABLE
        elif result == "cancel":
            self.mode = Mode.PLAY
