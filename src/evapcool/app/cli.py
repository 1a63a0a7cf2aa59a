"""`evapcool` (the default command): play the applet, or run it headless for a screenshot."""

from __future__ import annotations

import argparse
import getpass
import os
import sys
from dataclasses import replace
from pathlib import Path

from evapcool import i18n, limits
from evapcool.about import APP_NAME, error_line
from evapcool.app.classlink import ClassLink
from evapcool.app.links import HIDEABLE, LOCKABLE, Setup, make_link, parse_link
from evapcool.app.storage import settings_path
from evapcool.app.words import choose
from evapcool.argtypes import OneLineParser, folder, output_file, ranged
from evapcool.fileio import read_user_text
from evapcool.game.replay import Recording, ReplayError, decode
from evapcool.game.rules import HEIGHT_START, GameConfig
from evapcool.game.settings import (
    SOUNDS,
    TC_LAWS,
    THEMES,
    Settings,
    load_settings,
    max_atoms,
    with_overrides,
)
from evapcool.limits import CLASS_NAME_MAX, USER_FILE_MAX_BYTES, ParameterError
from evapcool.physics.world import ESCAPE_RULES
from evapcool.view.screen import WINDOW as SCENE_SIZE
from evapcool.view.screen import window_room

PROG = APP_NAME
#: Parameter names -> our options, so errors name what the user typed (ParameterError.render).
_OPTION_OF = {
    "n_atoms": "--atoms",
    "radius": "--radius",
    "seed": "--seed",
    "speed": "--speed",
    "tc_law": "--tc-law",
    "escape": "--escape",
}

#: The same, as a link names them (the page's ADDRESS_NAMES).
_LINK_NAMES = {"n_atoms": "atoms", "radius": "radius"}


def _languages() -> list[str]:
    return [*i18n.shipped_locales(), i18n.PSEUDO]


def _language(value: str) -> str:
    """A --lang value: the shipped catalog it names (de-AT gives de), else one line naming
    the allowed tags."""
    match = i18n.best_match([value], _languages())
    if match is None:
        allowed = ", ".join(_languages())
        raise argparse.ArgumentTypeError(f"must be one of {allowed} (got {value!r})")
    return match


def build_parser() -> argparse.ArgumentParser:
    p = OneLineParser(
        None,
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
        help=f"atoms, {limits.APPLET_ATOMS.span()} and as many as fit below the window's top "
        "at the radius (saved setting; 49; the settings screen keeps all below the rim)",
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
        default=None,
        metavar="X",
        help=f"simulation speed, {limits.APPLET_SPEED.span()} (default 1)",
    )
    p.add_argument(
        "--trap",
        type=ranged(limits.APPLET_HEIGHT),
        default=None,
        metavar="H",
        help=(
            f"the rim's height at each start, {limits.APPLET_HEIGHT.span()} "
            f"(default {HEIGHT_START:g})"
        ),
    )
    p.add_argument(
        "--lock",
        type=_names_of("lock", LOCKABLE),
        default=None,
        metavar="LIST",
        help="controls shown but not changeable, a comma-separated list of " + ", ".join(LOCKABLE),
    )
    p.add_argument(
        "--hide",
        type=_names_of("hide", HIDEABLE),
        default=None,
        metavar="LIST",
        help="panels and buttons left out, a comma-separated list of " + ", ".join(HIDEABLE),
    )
    p.add_argument(
        "--theme",
        choices=THEMES,
        default=None,
        help="colours: dark (the original's) or projector (light, high contrast) "
        "(saved setting; dark)",
    )
    p.add_argument(
        "--sound",
        choices=SOUNDS,
        default=None,
        help="sound on or off from the start (saved setting; on; key M switches it)",
    )
    p.add_argument(
        "--link",
        default=None,
        metavar="LINK",
        help="play a setup's link (the page's address with its options, as "
        "'evapcool --print-link' writes); options given here beat the link's",
    )
    p.add_argument(
        "--print-link",
        action="store_true",
        help="print the page's address for these options (a setup to hand out) and exit",
    )
    p.add_argument("--fullscreen", action="store_true", help="start in full screen")
    p.add_argument(
        "--lang",
        type=_language,
        default=None,
        metavar="TAG",
        help="language of the window: "
        + ", ".join(_languages())
        + " (default: the saved setting, else the system's)",
    )
    p.add_argument(
        "--autopilot",
        default=None,
        metavar="FILE",
        help="a strategy plays by itself: demo, a strategy file (evapcool optimize) or a "
        "schedule like 425@0,162@1788; touch the slider to take over, A hands back",
    )
    p.add_argument(
        "--class",
        dest="class_url",
        default=None,
        metavar="URL",
        help="join a class competition: the class server's address (evapcool class), "
        "like http://192.168.1.10:8765/; its challenge is played and each win is sent",
    )
    p.add_argument(
        "--replay",
        default=None,
        metavar="CODE|FILE",
        help="watch a recorded game: a replay code (EC1....) or a file holding one",
    )
    p.add_argument(
        "--name",
        default=None,
        metavar="NAME",
        help="with --class: your name on the class's leaderboard (default: your user name)",
    )
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
        type=folder,
        default=None,
        metavar="DIR",
        help="folder for the high scores (default $EVAPCOOL_DATA_DIR, else the user data folder)",
    )
    p.add_argument(
        "--config-dir",
        type=folder,
        default=None,
        metavar="DIR",
        help="folder for the settings (default $EVAPCOOL_CONFIG_DIR, else the user config folder)",
    )
    return p


def _names_of(option: str, allowed: tuple[str, ...]):
    """A --lock or --hide value: names from allowed, comma-separated; one line otherwise."""

    def parse(value: str) -> tuple[str, ...]:
        items = tuple(dict.fromkeys(p.strip() for p in value.split(",") if p.strip()))
        bad = [item for item in items if item not in allowed]
        if bad:
            raise argparse.ArgumentTypeError(
                f"must be a comma-separated list of {', '.join(allowed)} (got {bad[0]!r})"
            )
        return items

    parse.__name__ = option
    return parse


def _with_link(args: argparse.Namespace) -> list[str]:
    """Fill the options not given on the command line from --link; the link's notices."""
    if args.link is None:
        return []
    setup = parse_link(args.link, _languages())
    taken = {
        "atoms": setup.atoms,
        "radius": setup.radius,
        "seed": setup.seed,
        "speed": setup.speed,
        "tc_law": setup.tc_law,
        "escape": setup.escape,
        "replay": setup.replay,
        "lang": _language(setup.lang) if setup.lang else None,
        "trap": setup.trap,
        "theme": setup.theme,
        "sound": setup.sound,
        "lock": setup.lock or None,
        "hide": setup.hide or None,
    }
    args.from_link = set()
    for name, value in taken.items():
        if getattr(args, name) is None and value is not None:
            setattr(args, name, value)
            args.from_link.add(name)
    return setup.notices


def _print_link(args: argparse.Namespace, run: Settings) -> int:
    """`--print-link`: the page's address for this run's options."""
    setup = Setup(
        atoms=run.n_atoms,
        radius=run.radius,
        seed=args.seed,
        speed=args.speed,
        tc_law=run.tc_law,
        escape=run.escape,
        replay=args.replay,
        lang=args.lang,
        trap=args.trap,
        theme=args.theme,
        sound=args.sound,
        lock=tuple(args.lock or ()),
        hide=tuple(args.hide or ()),
    )
    print(make_link(setup))
    return 0


def _user_message(exc: ValueError) -> str:
    """The error's line with our option names (the parameter's name is data, not text)."""
    return exc.render(_OPTION_OF) if isinstance(exc, ParameterError) else str(exc)


def _class_link(args: argparse.Namespace) -> tuple[ClassLink | None, str | None]:
    """The class server to join (--class, --name), or why the options do not work."""
    if args.class_url is None:
        return None, "--name needs --class URL" if args.name is not None else None
    name = args.name if args.name is not None else _user_name()
    if args.name is not None and len(" ".join(args.name.split())) > CLASS_NAME_MAX:
        return None, (
            f"--name must be at most {CLASS_NAME_MAX} characters, as the class's leaderboard "
            f"shows it (got {len(' '.join(args.name.split()))})"
        )
    try:
        return ClassLink(args.class_url, name, named=args.name is not None), None
    except ValueError as exc:
        return None, str(exc)


def _watched(args: argparse.Namespace) -> tuple[Recording | None, str | None]:
    """The recording to watch (--replay CODE|FILE), or why it cannot be watched."""
    if args.replay is None:
        return None, None
    if args.class_url is not None:
        return None, "--replay cannot be combined with --class"
    text = args.replay
    path = Path(text)
    if not text.startswith("EC") and _is_file(path):
        try:
            text = read_user_text(path, USER_FILE_MAX_BYTES).strip()
        except (OSError, ValueError) as exc:
            return None, f"--replay: cannot read {path} ({exc})"
    try:
        return decode(text), None
    except ReplayError as exc:
        return None, f"--replay: not a replay code to watch ({exc})"


def _is_file(path: Path) -> bool:
    """A regular file there; False for a name the system refuses (too long, say)."""
    try:
        return path.is_file()
    except OSError:
        return False


def _user_name() -> str:
    """The OS user's name (the class server cleans it), or 'player' if there is none."""
    try:
        return getpass.getuser() or "player"
    except (OSError, KeyError, ImportError):
        return "player"


def _no_display() -> str | None:
    """Why no window can open here, or None. Checked before anything slow happens."""
    driver = os.environ.get("SDL_VIDEODRIVER", "")
    if driver in ("dummy", "offscreen"):
        return f"SDL_VIDEODRIVER={driver} shows no window"
    if sys.platform.startswith(("win", "darwin")):
        return None
    if not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        return "no display (neither DISPLAY nor WAYLAND_DISPLAY is set)"
    return None


def main(argv: list[str] | None = None) -> int:
    """Play the applet (or, with --frames, run it headless); returns the exit status."""
    args = build_parser().parse_args(argv)
    link_notices = _with_link(args)
    if args.screenshot is not None and args.frames is None:
        print(
            error_line(None, "--screenshot needs --frames N (frames to run first)"), file=sys.stderr
        )
        return 2
    link, problem = _class_link(args)
    watched, problem = (None, problem) if problem else _watched(args)
    if problem:
        print(error_line(None, problem), file=sys.stderr)
        return 2
    saved, notices = load_settings(settings_path(args.config_dir))
    notices = [*link_notices, *notices]
    choose(args.lang, saved.language)
    overrides = {
        "n_atoms": args.atoms,
        "radius": args.radius,
        "tc_law": args.tc_law,
        "escape": args.escape,
        "theme": args.theme,
        "sound": args.sound,
    }
    if args.atoms is None and args.radius is not None:
        # Bigger atoms than saved: the saved count may not fit; take what does.
        overrides["n_atoms"] = min(saved.n_atoms, max_atoms(args.radius))
    if getattr(args, "from_link", set()) & {"atoms", "radius"}:
        try:  # the page's own rule: a count that does not fit plays the saved settings
            with_overrides(saved, **overrides)
        except ValueError as exc:
            named = exc.render(_LINK_NAMES) if isinstance(exc, ParameterError) else str(exc)
            link_problem = i18n.t("page.address_saved_settings", problem=named)
            notices.insert(len(link_notices), link_problem)
            overrides["n_atoms"] = overrides["radius"] = None
    try:
        run = with_overrides(saved, **overrides)
        if args.print_link:
            return _print_link(args, run)
        config = GameConfig(
            n_atoms=run.n_atoms,
            radius=run.radius,
            seed=args.seed,
            speed=1.0 if args.speed is None else args.speed,
            tc_exponent=run.tc_exponent,
            escape=run.escape,
            room=window_room(SCENE_SIZE),  # the room the scene shows
            start_height=HEIGHT_START if args.trap is None else args.trap,
        )
        if watched is not None:  # the recording's own settings and seed
            config = replace(
                watched.settings.game_config(watched.seed), speed=config.speed, room=config.room
            )
    except ValueError as exc:
        print(error_line(None, _user_message(exc)), file=sys.stderr)
        return 2
    pilot = None
    if args.autopilot is not None:
        from evapcool.game.autopilot import Autopilot

        try:
            pilot = Autopilot.load(args.autopilot)
        except ValueError as exc:
            print(error_line(None, f"--autopilot: {exc}"), file=sys.stderr)
            return 2
    if args.frames is None and (why := _no_display()):
        print(
            error_line(
                None,
                f"cannot play without a window: {why}; to run headless use "
                "--frames N --screenshot out.png",
            ),
            file=sys.stderr,
        )
        return 2

    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    if args.frames is not None and _no_display():
        os.environ.setdefault("SDL_VIDEODRIVER", "dummy")  # headless: no window needed
    import pygame  # only now: bad arguments should not pay for SDL start-up

    from evapcool.app.applet import App, stderr_log

    try:
        app = App(
            config,
            fullscreen=args.fullscreen,
            data_dir=args.data_dir,
            config_dir=args.config_dir,
            settings=saved,
            overrides={k: v for k, v in overrides.items() if v is not None},
            notices=notices,
            log=stderr_log,
            autopilot=pilot,
            classroom=link,
            replay=watched,
            lock=tuple(args.lock or ()),
            hide=tuple(args.hide or ()),
        )
    except ValueError as exc:
        print(error_line(None, _user_message(exc)), file=sys.stderr)
        return 2
    except pygame.error as exc:
        print(
            error_line(
                None,
                f"cannot open a window ({exc}); to run headless use "
                "--frames N --screenshot out.png",
            ),
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
                        error_line(None, f"cannot write {str(args.screenshot)!r}: {exc}"),
                        file=sys.stderr,
                    )
                    return 1
    except KeyboardInterrupt:
        return 130
    finally:
        app.close()
    return 0
