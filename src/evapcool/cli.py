"""The `evapcool` command: play (default) or one of the subcommands below."""

from __future__ import annotations

import argparse
import importlib
import sys
import warnings
from collections.abc import Callable
from typing import TextIO

from evapcool.about import __version__, error_line, note_line
from evapcool.extras import (
    CoreMissingWarning,
    MissingExtraError,
    SlowEngineWarning,
    missing_message,
)

#: Subcommands: the module whose main(argv) runs each, and its line in `evapcool --help`.
SUBCOMMANDS = {
    "lab": ("evapcool.lab.cli", "run an evaporation experiment headless: series and a figure"),
    "bench": ("evapcool.bench", "print the performance figures"),
    "web": ("evapcool.web", "open the browser edition (one HTML file), or copy it"),
    "sweep": ("evapcool.lab.sweep_cli", "run a grid of lab experiments, locally or on Dask"),
    "optimize": ("evapcool.optimize.cli", "search the best evaporation ramp (Optuna on Dask)"),
    "verify": (
        "evapcool.classroom.verify_cli",
        "verify replay codes by replay, rank them by score",
    ),
    "class": ("evapcool.classroom.class_cli", "run the class competition server"),
    "open": ("evapcool.app.open_cli", "play a setup's link (the page's address) on the desktop"),
}
EXIT_USAGE = 2


def commands_help() -> str:
    """The subcommands' section of `evapcool --help`."""
    width = max(len(name) for name in SUBCOMMANDS)
    lines = [f"  {name:<{width}}  {text}" for name, (_, text) in SUBCOMMANDS.items()]
    return (
        "commands (evapcool COMMAND --help for each):\n"
        + "\n".join(lines)
        + "\n\nWithout a command, evapcool plays the applet with the options above."
    )


def _print_help() -> None:
    from evapcool.app.cli import build_parser

    parser = build_parser()
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.description = (
        "Evaporative cooling of atoms in a cup: play the applet (without a command), "
        "or run one of the commands below."
    )
    parser.epilog = commands_help()
    parser.add_argument("--version", action="store_true", help="print the version and exit")
    parser.print_help()


def _note_printer(command: str | None) -> Callable[..., None]:
    """showwarning for our warnings: one line on stderr, not a code location."""

    def show(
        message: Warning | str,
        category: type[Warning],
        filename: str,
        lineno: int,
        file: TextIO | None = None,
        line: str | None = None,
    ) -> None:
        if issubclass(category, (SlowEngineWarning, CoreMissingWarning)):
            print(note_line(command, str(message)), file=sys.stderr, flush=True)
        else:
            _default_showwarning(message, category, filename, lineno, file, line)

    return show


_default_showwarning = warnings.showwarning


def main(argv: list[str] | None = None) -> int:
    """Dispatch to the applet or a subcommand; returns the exit status."""
    args = sys.argv[1:] if argv is None else list(argv)
    if args[:1] == ["--version"]:
        print(f"evapcool {__version__}")
        return 0
    if args[:1] in (["-h"], ["--help"]):
        _print_help()
        return 0
    command = args[0] if args and args[0] in SUBCOMMANDS else None
    warnings.showwarning = _note_printer(command)
    try:
        if command is None:
            from evapcool.app.cli import main as app_main

            return app_main(args)
        try:
            module = importlib.import_module(SUBCOMMANDS[command][0])
        except ModuleNotFoundError as err:
            if err.name and not err.name.startswith("evapcool"):
                message = missing_message(err.name.split(".")[0], f"evapcool {command}")
                raise MissingExtraError(message) from err
            # The stand-alone executable ships the applet only.
            print(error_line(None, f"'{command}' is not part of this build"), file=sys.stderr)
            return EXIT_USAGE
        status: int = module.main(args[1:])
        return status
    except MissingExtraError as exc:
        print(error_line(command, str(exc)), file=sys.stderr)
        return EXIT_USAGE
    finally:
        warnings.showwarning = _default_showwarning
