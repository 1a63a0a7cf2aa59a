"""`evapcool lab`: headless evaporation experiments from the command line."""

from __future__ import annotations

import argparse
import sys

import numpy as np

from evapcool import limits
from evapcool.about import error_line, note_line, one_line
from evapcool.argtypes import Parser, UsageError, choice, output_file, ranged
from evapcool.extras import check
from evapcool.lab.experiment import ESCAPES, START_HELP, TC_LAWS, LabConfig, run_experiment
from evapcool.lab.io import COLUMNS, read_result, to_csv_text
from evapcool.lab.schedule import SCHEDULE_HELP
from evapcool.limits import ParameterError
from evapcool.physics.simulation import ENGINES

EXIT_USAGE = 2
EXIT_NO_THEORY = 1  # the run is written, but too short (or unsuitable) for the model
EXIT_INTERRUPTED = 130


def build_parser() -> argparse.ArgumentParser:
    d = LabConfig()
    p = Parser(
        prog="evapcool lab",
        description=(
            "Run an evaporative-cooling experiment headless: a trap-height schedule in, "
            "time series (CSV/JSON) and a figure out. See docs/lab.md."
        ),
    )
    p.add_argument(
        "--atoms",
        dest="n_atoms",
        type=ranged(limits.N_ATOMS),
        help=f"number of atoms, {limits.N_ATOMS.span()}, at most "
        f"{limits.REFERENCE_MAX_ATOMS} with --engine reference (default {d.n_atoms})",
    )
    p.add_argument(
        "--radius",
        type=ranged(limits.RADIUS),
        help=f"atom radius, {limits.RADIUS.span()} (default {d.radius:g})",
    )
    p.add_argument(
        "--curvature",
        type=ranged(limits.CURVATURE),
        help=f"cup curvature a, {limits.CURVATURE.span()} (default {d.curvature:g})",
    )
    p.add_argument(
        "--gravity",
        type=ranged(limits.GRAVITY),
        help=f"g, {limits.GRAVITY.span()} (default 10/30)",
    )
    p.add_argument(
        "--seed",
        type=ranged(limits.SEED),
        help=f"random seed, {limits.SEED.span()} (default: drawn, recorded)",
    )
    p.add_argument(
        "--engine",
        type=choice(ENGINES),
        help=f"physics engine: {', '.join(ENGINES)} (default auto)",
    )
    p.add_argument(
        "--frames",
        type=ranged(limits.FRAMES),
        help=f"run length, {limits.FRAMES.span()} frames (default {d.frames})",
    )
    p.add_argument(
        "--every",
        type=ranged(limits.EVERY),
        metavar="K",
        help=f"record every K frames (default {d.every}); "
        f"at most {limits.RECORDS_MAX} records in a run",
    )
    p.add_argument(
        "--escape",
        type=choice(ESCAPES),
        help="rim: fly over the rim (the game); knife: E > m g H removed at once",
    )
    p.add_argument(
        "--schedule",
        help=f"trap height H(t): {SCHEDULE_HELP}, at most {limits.SCHEDULE_POINTS_MAX} points "
        f"(default {d.schedule})",
    )
    p.add_argument(
        "--tc-law",
        dest="tc_law",
        type=choice(tuple(TC_LAWS)),
        help="Tc ~ N^(2/3) (seed, default) or N^(2/5) (cup)",
    )
    p.add_argument("--start", help=f"initial atoms: {START_HELP} (default cup)")
    p.add_argument(
        "--continue-after-win",
        dest="stop_at_win",
        action="store_const",
        const=False,
        help="keep running under the game's rules once T < Tc",
    )
    p.add_argument(
        "--no-win",
        dest="win",
        action="store_const",
        const=False,
        help="turn the game's win rule off: the gas stays a gas below Tc (evaporation goes on)",
    )
    p.add_argument(
        "--from",
        dest="from_file",
        metavar="FILE",
        help="repeat the run recorded in FILE (other options override)",
    )
    p.add_argument(
        "--out",
        metavar="FILE",
        type=output_file((".csv", ".json")),
        help="results, .csv or .json (default: CSV on stdout); checked before the run",
    )
    p.add_argument(
        "--plot",
        metavar="FILE.png",
        type=output_file((".png",)),
        help="save the four-panel figure; checked before the run",
    )
    p.add_argument(
        "--theory",
        action="store_true",
        help="print the measured rates beside the truncated-Boltzmann model (stdout if --out "
        "is given, else stderr) and draw the model in the figure",
    )
    return p


def _fail(message: str) -> int:
    print(error_line("lab", message), file=sys.stderr)
    return EXIT_USAGE


#: Parameter names -> our options, so errors name what the user typed (ParameterError.render).
OPTION_OF = {
    **{name: "--" + name.replace("_", "-") for name in LabConfig.__dataclass_fields__},
    "n_atoms": "--atoms",
    "trap_height": "--schedule",
    "stop_at_win": "--continue-after-win",
    "win": "--no-win",
    "out": "--out",
    "plot": "--plot",
}


def _option_message(exc: ValueError) -> str:
    """The error's line naming our options: 'tc_law must be ...' -> '--tc-law must be ...'."""
    return exc.render(OPTION_OF) if isinstance(exc, ParameterError) else str(exc)


def _from_file(path: str) -> dict:
    """The parameters recorded in a lab result file; ValueError or OSError saying why not."""
    metadata = read_result(path)[0]
    params = metadata.get("parameters")
    if not isinstance(params, dict):
        raise ValueError("it records no parameters")
    unknown = sorted(str(k) for k in params if k not in LabConfig.__dataclass_fields__)
    if unknown:
        raise ValueError(f"unknown parameter {limits.shown(unknown[0])}")
    if "note" in metadata:  # an older file, read as well as it can be
        print(note_line("lab", one_line(f"--from {path}: {metadata['note']}")), file=sys.stderr)
    return params


def main(argv: list[str] | None = None) -> int:
    """Entry point of `evapcool lab`; returns the exit status (2 on bad input)."""
    try:
        args = build_parser().parse_args(sys.argv[1:] if argv is None else argv)
    except UsageError as exc:
        return _fail(str(exc))
    params: dict = {}
    from_file: dict = {}
    if args.from_file is not None:
        try:
            from_file = _from_file(args.from_file)
        except (OSError, ValueError) as exc:
            why = exc.strerror or exc if isinstance(exc, OSError) else exc
            return _fail(f"--from must name a lab result file (.csv or .json): {why}")
        params.update(from_file)
    given = set()
    for name in LabConfig.__dataclass_fields__:
        value = getattr(args, name, None)
        if value is not None:
            params[name] = value
            given.add(name)
    if args.theory and (why := _too_few_records(params)):
        return _fail(why)  # known before the run: say it now, not after it
    if args.plot is not None:
        check("matplotlib", "--plot")  # before the run, which may be long
    plot = None if args.theory else args.plot  # with --theory the figure waits for the model
    try:
        result = run_experiment(out=args.out, plot=plot, progress=None, **params)
    except ValueError as exc:
        name = exc.parameter if isinstance(exc, ParameterError) else None
        if name in from_file and name not in given:
            return _fail(f"--from {args.from_file}: {exc}")
        return _fail(_option_message(exc))
    except OSError as exc:
        return _fail(f"could not write output: {exc}")
    if args.out is None:
        sys.stdout.write(to_csv_text(result.metadata, result.columns, result.final_energies))
    if not result.completed:
        if args.theory and args.plot:
            result.plot(args.plot)
        print(_summary(result, args.out, args.plot), file=sys.stderr)
        return EXIT_INTERRUPTED
    if args.theory:
        return _theory(result, args)
    print(_summary(result, args.out, args.plot), file=sys.stderr)
    return 0


def _too_few_records(params: dict) -> str | None:
    """Why --theory cannot work with these frames and every (it needs 3 records), or None."""
    frames = params.get("frames", LabConfig.frames)
    every = params.get("every", LabConfig.every)
    if not (isinstance(frames, int) and isinstance(every, int) and frames > 0 and every > 0):
        return None  # the run's own checks name the bad value
    records = frames // every + 1 + (frames % every != 0)
    if records >= 3:
        return None
    return (
        f"--theory needs a run of at least 3 records: --frames {frames} with --every {every} "
        f"records {records} (run longer, or record more often with --every)"
    )


def _summary(result, out: object, plot: object = None) -> str:
    """One line: records, N and T from first to last, when T fell below Tc, the files written."""
    n = result.n_trapped
    t = result.temperature
    won = result.metadata.get("won_frame")
    if result.parameters.get("win", True):
        below = f", T < Tc from frame {won}" if won is not None else ", T > Tc throughout"
    else:
        crossed = np.flatnonzero(t < result.critical_temperature)
        below = (
            f", T < Tc from frame {result.frame[crossed[0]]} (win rule off)"
            if crossed.size
            else ", T > Tc throughout (win rule off)"
        )
    summary = (
        f"evapcool lab: {len(result)} records, N {n[0]} -> {n[-1]}, "
        f"T {t[0]:.4g} -> {t[-1]:.4g}" + below
    )
    written = [str(f) for f in (out, plot) if f]
    if written:
        summary += "; wrote " + " and ".join(written)
    if not result.completed:
        summary += f" (interrupted at frame {result.metadata['frames_done']})"
    return summary


def _theory(result, args) -> int:
    """Print the comparison with the model (stdout if the CSV went to a file) and plot it;
    the summary, naming what was written, comes last (before a refusal, which ends it)."""
    try:
        report = result.theory()
    except ValueError as exc:
        if args.plot:
            result.plot(args.plot)
        print(_summary(result, args.out, args.plot), file=sys.stderr)
        print(error_line("lab", f"--theory: {exc}"), file=sys.stderr)
        return EXIT_NO_THEORY
    print(report, file=sys.stdout if args.out else sys.stderr)
    if args.plot:
        result.plot(args.plot, theory=report)
    print(_summary(result, args.out, args.plot), file=sys.stderr)
    return 0


__all__ = ["COLUMNS", "build_parser", "main"]
