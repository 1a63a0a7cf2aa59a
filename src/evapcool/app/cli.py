"""`evapcool` (the default command): play the applet, or run it headless for a screenshot."""

from __future__ import annotations

import argparse
import os
import sys
import threading
from pathlib import Path

from evapcool import limits
from evapcool.app.storage import settings_path
from evapcool.argtypes import one_line, output_file, ranged
from evapcool.game.rules import Game, GameConfig
from evapcool.game.settings import (
    TC_LAWS,
    load_settings,
    max_atoms,
    with_overrides,
)
from evapcool.physics.world import ESCAPE_RULES

PROG = "evapcool"
#: A start slower than this (s) is the fast engine compiling: say so once.
SLOW_START_NOTICE_S = 2.0
#: Parameter names -> our options, so ValueErrors name what the user typed.
_OPTION_OF = {
    "n_atoms": "--atoms",
    "radius": "--radius",
    "seed": "--seed",
    "speed": "--speed",
    "tc_law": "--tc-law",
    "escape": "--escape",
}


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line and exit 2, never a usage dump
        print(f"{PROG}: {one_line(message)}", file=sys.stderr)
        raise SystemExit(2)


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(
        prog=PROG,
        description="Evaporative cooling of atoms in a cup: play the applet. "
        "Other commands: 'evapcool lab ...', 'evapcool bench'.",
    )
    # Atoms, radius, Tc law and escape rule default to the saved settings (key O in
    # the applet); given here they apply to this run only and are not saved.
    p.add_argument(
        "--atoms",
        type=ranged(limits.APPLET_ATOMS),
        default=None,
        metavar="N",
        help=f"atoms, {limits.APPLET_ATOMS.span()} and as many as fit at the radius "
        "(saved setting; 49)",
    )
    p.add_argument(
        "--radius",
        type=ranged(limits.APPLET_RADIUS),
        default=None,
        metavar="R",
        help=f"atom radius, {limits.APPLET_RADIUS.span()} (saved setting; 12)",
    )
    p.add_argument(
        "--tc-law",
        choices=tuple(TC_LAWS),
        default=None,
        help="Tc ~ N^p: seed p = 2/3 (original), cup p = 2/5 (saved setting; seed)",
    )
    p.add_argument(
        "--escape",
        choices=ESCAPE_RULES,
        default=None,
        help="atoms leave over the rim, or by the energy knife (saved setting; rim)",
    )
    p.add_argument(
        "--seed",
        type=ranged(limits.SEED),
        default=None,
        metavar="S",
        help=f"random seed, {limits.SEED.span()} (default: random)",
    )
    p.add_argument(
        "--speed",
        type=ranged(limits.APPLET_SPEED),
        default=1.0,
        metavar="X",
        help=f"simulation speed, {limits.APPLET_SPEED.span()} (default 1)",
    )
    p.add_argument("--fullscreen", action="store_true", help="start in full screen")
    p.add_argument(
        "--frames",
        type=ranged(limits.APPLET_FRAMES),
        default=None,
        metavar="N",
        help="play N frames without waiting for the clock (1 physics frame x speed each), "
        f"then exit; {limits.APPLET_FRAMES.span()}",
    )
    p.add_argument(
        "--screenshot",
        type=output_file((".png",)),
        default=None,
        metavar="PATH",
        help="with --frames: save the window as PNG (the path is checked before the run)",
    )
    p.add_argument(
        "--data-dir",
        type=Path,
        default=None,
        metavar="DIR",
        help="folder for the high scores (default $EVAPCOOL_DATA_DIR, else the user data folder)",
    )
    p.add_argument(
        "--config-dir",
        type=Path,
        default=None,
        metavar="DIR",
        help="folder for the settings (default $EVAPCOOL_CONFIG_DIR, else the user config folder)",
    )
    return p


def _user_message(exc: ValueError) -> str:
    text = str(exc)
    if text.startswith("n_atoms:") and "do not fit" in text:
        return "--atoms and --radius" + text[len("n_atoms") :]  # a joint limit
    for name, option in _OPTION_OF.items():
        if text.startswith((name + " ", name + ":")):
            return option + text[len(name) :]
    return text


def _no_display() -> bool:
    """True on a Linux/BSD machine with neither an X11 nor a Wayland display."""
    if sys.platform.startswith(("win", "darwin")):
        return False
    return not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def _build_game(config: GameConfig) -> Game:
    """Game(config), with one line on stderr if it keeps the player waiting.

    The first start with the Numba engine on a machine compiles it (about half a
    minute); without a word the window would just not appear for that long.
    """
    notice = threading.Timer(
        SLOW_START_NOTICE_S,
        lambda: print(
            f"{PROG}: preparing the fast engine; its first start on this machine compiles it "
            "(about half a minute, once)...",
            file=sys.stderr,
            flush=True,
        ),
    )
    notice.daemon = True
    notice.start()
    try:
        return Game(config)
    finally:
        notice.cancel()


def main(argv: list[str] | None = None) -> int:
    """Play the applet (or, with --frames, run it headless); returns the exit status."""
    args = build_parser().parse_args(argv)
    if args.screenshot is not None and args.frames is None:
        print(f"{PROG}: --screenshot needs --frames N (frames to run first)", file=sys.stderr)
        return 2
    saved, notices = load_settings(settings_path(args.config_dir))
    overrides = {
        "n_atoms": args.atoms,
        "radius": args.radius,
        "tc_law": args.tc_law,
        "escape": args.escape,
    }
    if args.atoms is None and args.radius is not None:
        # Bigger atoms than saved: the saved count may not fit; take what does.
        overrides["n_atoms"] = min(saved.n_atoms, max_atoms(args.radius))
    try:
        run = with_overrides(saved, **overrides)
        config = GameConfig(
            n_atoms=run.n_atoms,
            radius=run.radius,
            seed=args.seed,
            speed=args.speed,
            tc_exponent=run.tc_exponent,
            escape=run.escape,
        )
        game = _build_game(config)
    except ValueError as exc:
        print(f"{PROG}: {one_line(_user_message(exc))}", file=sys.stderr)
        return 2

    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    if args.frames is not None and _no_display():
        os.environ.setdefault("SDL_VIDEODRIVER", "dummy")  # headless: no window needed
    import pygame  # only now: bad arguments should not pay for SDL start-up

    from evapcool.app.applet import App

    try:
        app = App(
            game,
            fullscreen=args.fullscreen,
            data_dir=args.data_dir,
            config_dir=args.config_dir,
            settings=saved,
            overrides={k: v for k, v in overrides.items() if v is not None},
            notices=notices,
        )
    except pygame.error as exc:
        print(
            f"{PROG}: cannot open a window ({exc}); for headless runs set SDL_VIDEODRIVER=dummy",
            file=sys.stderr,
        )
        return 1
    try:
        if args.frames is None:
            app.run()
        else:
            app.run_frames(args.frames)
            if args.screenshot is not None:
                try:
                    app.screenshot(args.screenshot)
                except OSError as exc:
                    print(
                        f"{PROG}: cannot write {str(args.screenshot)!r}: {one_line(str(exc))}",
                        file=sys.stderr,
                    )
                    return 1
    except KeyboardInterrupt:
        return 130
    finally:
        app.close()
    return 0
