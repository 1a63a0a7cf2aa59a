"""The `evapcool` command: play (default), `lab` or `bench`."""

from __future__ import annotations

import sys


def main(argv: list[str] | None = None) -> int:
    """Dispatch to the applet, the lab or the benchmarks; returns the exit status."""
    args = sys.argv[1:] if argv is None else list(argv)
    if args and args[0] == "lab":
        from evapcool.lab.cli import main as lab_main

        return lab_main(args[1:])
    if args and args[0] == "bench":
        from evapcool.bench import main as bench_main

        return bench_main(args[1:])
    from evapcool.app.cli import main as app_main

    return app_main(args)
