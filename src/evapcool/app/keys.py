"""The desktop's key table: which keys do what, and what the help says of them.

Each `Binding` names its keys, its help line and its action on the app's `Commands`
(app.commands); the help overlay lists exactly these, so a
new key is one entry here. The mouse's lines follow them in the help (app.overlays).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import cast

import pygame

from evapcool.app.commands import Commands
from evapcool.app.input import Binding, Controls, Mode
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN

#: Trap height change per arrow-key press (key repeat is on), px.
HEIGHT_STEP = 5.0
_SUBMIT = (pygame.K_RETURN, pygame.K_KP_ENTER)
#: The numbers the help's messages name.
HELP_ARGS: dict[str, object] = {
    "step": HEIGHT_STEP,
    "height": 400,
    "low": HEIGHT_MIN,
    "high": HEIGHT_MAX,
    "fast": 4,
    "slow": "1/4",
}


def _do(action: Callable[[Commands], object]) -> Callable[[Controls], object]:
    """An action of the table: the machine hands it the app's Commands."""
    return cast(Callable[[Controls], object], action)


#: The keys each part a setup's link can hide (`hide=`) leaves out with it.
HIDDEN_KEYS = {
    "pause": (pygame.K_SPACE,),
    "restart": (pygame.K_r,),
    "step": (pygame.K_s,),
    "slower": (pygame.K_MINUS,),
    "faster": (pygame.K_PLUS,),
    "autopilot": (pygame.K_a,),
    "chart": (pygame.K_e,),
    "path": (pygame.K_g,),
    "help": (pygame.K_h,),
    "table": (pygame.K_t, pygame.K_x),
    "settings": (pygame.K_o,),
    "fullscreen": (pygame.K_F11,),
}


def _shifted() -> bool:
    return bool(pygame.key.get_mods() & pygame.KMOD_SHIFT)


def default_bindings(hide: frozenset[str] | tuple[str, ...] = ()) -> list[Binding]:
    """The applet's keyboard controls (the help overlay lists exactly these), less those of
    the parts a setup's link hides."""
    gone = {key for part in hide for key in HIDDEN_KEYS.get(part, ())}
    return [b for b in _all_bindings() if not set(b.keys) & gone]


def _all_bindings() -> list[Binding]:
    return [
        Binding(
            (pygame.K_SPACE,), "help.key.space", "help.space", _do(lambda app: app.toggle_pause())
        ),
        Binding(
            (pygame.K_r,),
            "R",
            "help.restart",
            _do(lambda app: app.restart()),
            ends_drag=True,
            starts_game=True,
        ),
        Binding(
            (pygame.K_LEFT, pygame.K_DOWN),
            "help.key.left_down",
            "help.lower",
            _do(lambda app: app.nudge(-HEIGHT_STEP)),
        ),
        Binding(
            (pygame.K_RIGHT, pygame.K_UP),
            "help.key.right_up",
            "help.raise",
            _do(lambda app: app.nudge(HEIGHT_STEP)),
        ),
        Binding((pygame.K_s,), "S", "help.step", _do(lambda app: app.game.step())),
        Binding(
            (pygame.K_a,),
            "A",
            "help.autopilot",
            _do(lambda app: app.toggle_autopilot()),
            more=("help.autopilot_more",),
        ),
        Binding(
            (pygame.K_PLUS, pygame.K_EQUALS, pygame.K_KP_PLUS),
            "+",
            "help.faster",
            _do(lambda app: app.faster()),
        ),
        Binding(
            (pygame.K_MINUS, pygame.K_KP_MINUS),
            "-",
            "help.slower",
            _do(lambda app: app.slower()),
        ),
        Binding((pygame.K_e,), "E", "help.energy", _do(lambda app: app.toggle_chart("energy"))),
        Binding(
            (pygame.K_g,),
            "G",
            "help.path",
            _do(lambda app: app.toggle_chart("path")),
        ),
        Binding((pygame.K_t,), "T", "help.table", mode=Mode.TABLE),
        Binding((pygame.K_c,), "C", "help.copy", _do(lambda app: app.copy_replay())),
        Binding(
            (pygame.K_DELETE, pygame.K_x),
            "help.key.delete_x",
            "help.clear",
            mode=Mode.CONFIRM_CLEAR,
            more=("help.clear_more",),
        ),
        Binding(
            _SUBMIT,
            "help.key.enter",
            "help.next",
            _do(lambda app: app.next_player()),
            ends_drag=True,
            starts_game=True,
        ),
        Binding(
            (pygame.K_o,),
            "O",
            "help.settings",
            mode=Mode.SETTINGS,
            more=("help.choose_change_save",),
        ),
        Binding(
            (pygame.K_w,),
            "W",
            "help.saverun",
            _do(lambda app: app.save_run(_shifted())),
            more=("help.save_run_more",),
        ),
        Binding((pygame.K_d,), "D", "help.describe", _do(lambda app: app.describe())),
        Binding((pygame.K_m,), "M", "help.mute", _do(lambda app: app.toggle_mute())),
        Binding(
            (pygame.K_F11,), "F11", "help.fullscreen", _do(lambda app: app.toggle_fullscreen())
        ),
        Binding((pygame.K_h, pygame.K_F1), "H, F1", "help.help", mode=Mode.HELP),
        Binding((pygame.K_ESCAPE,), "help.key.esc", "help.escape", mode=Mode.PLAY),
    ]
