"""The `evapcool` command: play (default), `lab`, `sweep`, `optimize`, `bench` or `web`."""

from __future__ import annotations

import importlib
import sys

#: Subcommands and the module whose main(argv) runs them.
SUBCOMMANDS = {
    "lab": "evapcool.lab.cli",
    "bench": "evapcool.bench",
    "web": "evapcool.web",
    "sweep": "evapcool.lab.sweep_cli",
    "optimize": "evapcool.optimize.cli",
}


def main(argv: list[str] | None = None) -> int:
    """Dispatch to the applet, the lab or the benchmarks; returns the exit status."""
    args = sys.argv[1:] if argv is None else list(argv)
    if args and args[0] in SUBCOMMANDS:
        try:
            module = importlib.import_module(SUBCOMMANDS[args[0]])
        except ModuleNotFoundError as err:
            # The stand-alone executable ships the applet only.
            print(f"evapcool: '{args[0]}' is not part of this build ({err.name})", file=sys.stderr)
            return 2
        return module.main(args[1:])
    from evapcool.app.cli import main as app_main

    return app_main(args)
