"""`evapcool bench`: the performance figures the issues ask for.

Each section lives in its own module with a `run(args) -> None` that prints
its figures; `--only NAME` picks sections. Timings are medians over repeats:
the machine is shared and noisy.
"""

from __future__ import annotations

import importlib
import warnings

from evapcool.argtypes import OneLineParser
from evapcool.extras import MissingExtraError, SlowEngineWarning, missing_message
from evapcool.physics import core

#: section name -> module (each has run(args)).
SECTIONS = {
    "physics": "evapcool.bench.physics",
    "fast": "evapcool.bench.fast",
    "applet": "evapcool.bench.applet",
    "cluster": "evapcool.bench.cluster",
}


def main(argv: list[str] | None = None) -> int:
    """Run the benchmark sections and print their figures."""
    p = OneLineParser("bench", prog="evapcool bench", description=__doc__.splitlines()[0])
    p.add_argument(
        "--engine",
        choices=("reference", "fast", "auto"),
        default="auto",
        help="engine for the physics figures (default: auto)",
    )
    p.add_argument(
        "--only",
        action="append",
        choices=sorted(SECTIONS),
        help="run only this section (repeatable)",
    )
    p.add_argument("--quick", action="store_true", help="fewer repeats, smaller systems")
    args = p.parse_args(argv)
    names = args.only or list(SECTIONS)
    if args.engine == "fast":
        if not core.available():  # asked for: an error, not a skip
            raise MissingExtraError(core.missing_message("evapcool bench --engine fast"))
        if not args.only:
            names = ["physics", "fast"]
    for name in names:
        try:
            mod = importlib.import_module(SECTIONS[name])
            with warnings.catch_warnings():
                # Thousands of atoms on the NumPy engine would take hours: skip instead.
                warnings.simplefilter("error", SlowEngineWarning)
                mod.run(args)
        except (MissingExtraError, SlowEngineWarning) as exc:  # e.g. no compiled core
            print(f"[{name}] skipped: {exc}")
        except ModuleNotFoundError as exc:
            if exc.name and not exc.name.startswith("evapcool"):
                package = exc.name.split(".")[0]
                print(f"[{name}] skipped: {missing_message(package, 'this section')}")
            else:
                print(f"[{name}] not available in this build")
    return 0
