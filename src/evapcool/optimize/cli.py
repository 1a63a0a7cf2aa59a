"""`evapcool optimize`: search evaporation strategies for the game with Optuna, on Dask."""

from __future__ import annotations

import argparse
import contextlib
import sys
import time
from pathlib import Path

from evapcool.about import error_line
from evapcool.argtypes import Parser, choice, positive, whole
from evapcool.lab.cluster import add_cluster_options, open_command
from evapcool.optimize.families import FAMILY_HELP, parse_families
from evapcool.optimize.report import DEFAULT_FINALISTS, DEFAULT_VALIDATE
from evapcool.optimize.study import (
    DEFAULT_BATCH,
    DEFAULT_BUDGET,
    DEFAULT_CHUNK,
    DEFAULT_SEEDS,
    ESCAPES,
    SAMPLERS,
    STUDY_NAME,
    TC_LAWS,
    Problem,
)

PROG = "evapcool optimize"
EXIT_USAGE = 2
EXIT_INTERRUPTED = 130
DEFAULT_STUDY = "optimize.db"
#: Options that define the problem: stored in the study; --resume must not change them.
PROBLEM_OPTIONS = {
    "budget": "--budget",
    "seeds": "--seeds",
    "seed_start": "--seed-start",
    "families": "--family",
    "knots": "--knots",
    "objectives": "--objectives",
    "n_atoms": "--atoms",
    "radius": "--radius",
    "escape": "--escape",
    "tc_law": "--tc-law",
    "sampler": "--sampler",
    "sampler_seed": "--sampler-seed",
    "batch": "--batch",
    "chunk": "--chunk",
}


def _families(text: str) -> tuple[str, ...]:
    try:
        return parse_families(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"must be all or names from {FAMILY_HELP} (got {text!r})"
        ) from None


def _objectives(text: str) -> tuple[str, ...]:
    names = tuple(n.strip() for n in text.split(","))
    if names not in (("score",), ("score", "time")):
        raise argparse.ArgumentTypeError(f"must be score or score,time (got {text!r})")
    return names


def build_parser() -> argparse.ArgumentParser:
    p = Parser(
        prog=PROG,
        description=(
            "Search trap-height strategies for the game (open-loop ramps and closed-loop "
            "policies) with Optuna; games run as Dask tasks. See docs/cluster.md."
        ),
    )
    s = p.add_argument_group("the study")
    s.add_argument(
        "--study",
        metavar="FILE|URL",
        help=f"new study: a SQLite file or an Optuna storage URL ({DEFAULT_STUDY})",
    )
    s.add_argument(
        "--resume", metavar="FILE|URL", help="continue a study (several processes may work on one)"
    )
    s.add_argument("--study-name", default=STUDY_NAME, help=f"name in the storage ({STUDY_NAME})")
    s.add_argument(
        "--trials",
        type=whole(0),
        default=100,
        help="trials this process runs (default 100; 0: just report)",
    )
    s.add_argument(
        "--timeout", type=positive, metavar="SECONDS", help="stop starting trials after this long"
    )
    q = p.add_argument_group("the problem (stored in the study)")
    q.add_argument("--budget", type=whole(1), help=f"frames a game may take ({DEFAULT_BUDGET})")
    q.add_argument(
        "--seeds",
        type=whole(2),
        metavar="S",
        help=f"starting seeds each strategy is scored on ({DEFAULT_SEEDS})",
    )
    q.add_argument("--seed-start", type=whole(0), help="first search seed (0)")
    q.add_argument(
        "--family", dest="families", type=_families, help=f"all (default) or some of: {FAMILY_HELP}"
    )
    q.add_argument("--knots", type=whole(1), help="knots of the 'knots' ramps (4)")
    q.add_argument(
        "--objectives", type=_objectives, help="score (default), or score,time for the Pareto front"
    )
    q.add_argument("--sampler", type=choice(SAMPLERS), help="tpe (default), cmaes or nsga2")
    q.add_argument("--sampler-seed", type=whole(0), help="seed of the sampler (repeatable)")
    q.add_argument("--batch", type=whole(1), help=f"trials asked at once ({DEFAULT_BATCH})")
    q.add_argument("--chunk", type=whole(1), help=f"games per task ({DEFAULT_CHUNK})")
    q.add_argument("--atoms", dest="n_atoms", type=whole(2), help="atoms (the game's 49)")
    q.add_argument("--radius", type=positive, help="atom radius, px (12)")
    q.add_argument("--escape", type=choice(ESCAPES), help="rim (the game) or knife")
    q.add_argument(
        "--tc-law",
        dest="tc_law",
        type=choice(tuple(TC_LAWS)),
        help="seed (N^2/3, the game) or cup (N^2/5)",
    )
    add_cluster_options(p.add_argument_group("where games run"))
    r = p.add_argument_group("the report")
    r.add_argument(
        "--out",
        metavar="DIR",
        help="folder for best.json, pareto.csv, ... (default: STUDY-results)",
    )
    r.add_argument(
        "--baseline",
        metavar="STRATEGY",
        help="compare with this (a schedule, FILE.json or demo) instead of the "
        "study's best linear ramps, or a grid of them",
    )
    r.add_argument(
        "--finalists",
        type=whole(1),
        default=DEFAULT_FINALISTS,
        help=f"top trials re-ranked on fresh seeds ({DEFAULT_FINALISTS})",
    )
    r.add_argument(
        "--validate",
        type=whole(0),
        default=DEFAULT_VALIDATE,
        metavar="N",
        help=f"held-out seeds for the validation ({DEFAULT_VALIDATE}; 0: none)",
    )
    metavars = {"study_name": "NAME", "trials": "N", "budget": "FRAMES", "seed_start": "SEED",
                "families": "NAMES", "knots": "K", "objectives": "score[,time]",
                "sampler": "NAME", "sampler_seed": "SEED", "batch": "B", "chunk": "C",
                "n_atoms": "N", "radius": "R", "escape": "RULE", "tc_law": "LAW",
                "workers": "N", "finalists": "K"}  # fmt: skip
    for action in p._actions:
        action.metavar = metavars.get(action.dest, action.metavar)
    return p


def _fail(message: str) -> int:
    print(error_line("optimize", message), file=sys.stderr)
    return EXIT_USAGE


def _given(args: argparse.Namespace) -> dict:
    return {k: getattr(args, k) for k in PROBLEM_OPTIONS if getattr(args, k) is not None}


def _sqlite_path(storage: str) -> Path | None:
    if "://" not in storage:
        return Path(storage)
    if storage.startswith("sqlite:///"):
        return Path(storage[len("sqlite:///") :])
    return None


def _out_dir(args: argparse.Namespace, storage: str) -> Path:
    if args.out is not None:
        return Path(args.out)
    path = _sqlite_path(storage)
    return path.with_name(path.stem + "-results") if path else Path("optimize-results")


def _check_out(out: Path) -> None:
    if out.exists() and not out.is_dir():
        raise ValueError(f"--out {str(out)!r} is a file, not a folder")
    parent = out if out.exists() else out.parent
    while not parent.exists():
        parent = parent.parent
    import os

    if not os.access(parent, os.W_OK):
        raise ValueError(f"--out {str(out)!r} cannot be written")


def _open(args: argparse.Namespace):
    """(study, problem, storage) for a new or resumed study; ValueError with the option."""
    from evapcool.optimize.study import load_study, storage_url

    given = _given(args)
    if args.resume is not None:
        if args.study is not None:
            raise ValueError("--study and --resume: give one (--resume continues a study)")
        path = _sqlite_path(args.resume)
        if path is not None and not path.is_file():
            raise ValueError(f"--resume: no study file {str(path)!r}")
        storage = storage_url(args.resume)
        study, problem = load_study(storage, args.study_name)
        stored = problem.to_attr()
        for name, value in given.items():
            if (list(value) if isinstance(value, tuple) else value) != stored[name]:
                raise ValueError(
                    f"{PROBLEM_OPTIONS[name]}: the study was made with {stored[name]!r} "
                    f"(got {value!r}); a resumed study keeps its problem"
                )
        return study, problem, storage
    text = args.study or DEFAULT_STUDY
    problem = Problem(**given)
    path = _sqlite_path(text)
    if path is not None:
        if path.exists():
            raise ValueError(f"--study {str(path)!r} exists; continue it with --resume {path}")
        if not path.parent.is_dir():
            raise ValueError(f"--study: folder {str(path.parent)!r} does not exist")
    return None, problem, storage_url(text)


def main(argv: list[str] | None = None) -> int:
    """Entry point of `evapcool optimize`; 0 done, 2 bad input, 130 interrupted."""
    args = open_command("optimize", build_parser(), argv)
    if isinstance(args, int):
        return args
    try:
        if args.baseline is not None:
            from evapcool.game.autopilot import load_strategy

            try:
                args.baseline = load_strategy(args.baseline).text
            except ValueError as exc:
                raise ValueError(f"--baseline: {exc}") from None
        study, problem, storage = _open(args)
        out = _out_dir(args, storage)
        _check_out(out)
    except ValueError as exc:
        msg = str(exc)
        return _fail(msg if msg.startswith("--") else _option_message(msg))
    return _run(args, study, problem, storage, out)


def _option_message(message: str) -> str:
    head, sep, rest = message.partition(" ")
    name = head.rstrip(":").replace("_", "-")
    return f"--{name}{head[len(head.rstrip(':')) :]}{sep}{rest}"


def _run(args, study, problem: Problem, storage: str, out: Path) -> int:
    from evapcool.lab.cluster import VersionMismatchError, connect
    from evapcool.optimize import report
    from evapcool.optimize.study import Search, best_so_far, create_study

    def log(text: str) -> None:
        print(f"{PROG}: {text}", file=sys.stderr)

    start = time.monotonic()
    interrupted = False
    with contextlib.ExitStack() as stack:
        try:
            engine = stack.enter_context(connect(args.scheduler, args.workers))
        except (OSError, TimeoutError, VersionMismatchError) as exc:
            return _fail(f"--scheduler {args.scheduler}: {exc}" if args.scheduler else str(exc))
        if study is None:  # made only now: a failed start leaves no file behind
            study = create_study(problem, storage, args.study_name)
        log(f"{engine.description}; study {args.study_name!r}, {len(study.trials)} trials so far")
        search = Search(study, problem, engine)
        bar = _bar(args.trials)
        try:
            search.run(args.trials, args.timeout, on_trial=lambda s: _tick(bar, s, start))
        except KeyboardInterrupt:
            interrupted = True
        finally:
            bar.close()
        elapsed = time.monotonic() - start
        run_info = {
            "this_run": {
                "trials": search.told,
                "games": search.games,
                "cpu_seconds": round(search.cpu_seconds, 2),
                "wall_seconds": round(elapsed, 2),
                "engine": engine.description,
            }
        }
        log(
            f"{search.told} trials, {search.games} games in {elapsed:.0f} s"
            f" ({1000 * search.cpu_seconds / max(search.games, 1):.1f} ms CPU per game);"
            f" best mean score so far {best_so_far(study):.2f}"
        )
        if interrupted:
            where = args.resume or args.study or DEFAULT_STUDY
            log(f"interrupted: finished trials are stored; continue with --resume {where}")
            return EXIT_INTERRUPTED
        try:
            best, base, info = report.choose(
                study, problem, engine, args.finalists, args.validate, args.baseline, log=log
            )
        except ValueError as exc:
            log(str(exc))
            return 1
        except KeyboardInterrupt:
            where = args.resume or args.study or DEFAULT_STUDY
            log(f"interrupted in the validation; the trials are stored: --resume {where} "
                "--trials 0 reports again")  # fmt: skip
            return EXIT_INTERRUPTED
        summary = report.write_outputs(out, study, problem, best, base, info, run_info)
    _print_summary(summary, out)
    return 0


def _bar(total: int):
    from tqdm import tqdm

    return tqdm(total=total, unit="trial", desc="trials", disable=None, dynamic_ncols=True)


def _tick(bar, search, start: float) -> None:
    from evapcool.optimize.study import best_so_far

    rate = search.games / max(time.monotonic() - start, 1e-9)
    bar.set_postfix_str(f"best {best_so_far(search.study):.2f}, {rate:.0f} games/s", refresh=False)
    bar.update(1)


def _fmt(stats: dict | None) -> str:
    if not stats:
        return "-"
    return (f"{stats['mean']:.2f} ± {stats['se']:.2f} ({stats['no_wins']} no-win, "
            f"{stats['time_mean_s']:.1f} s)")  # fmt: skip


def _print_summary(summary: dict, out: Path) -> None:
    b, lin = summary["best"], summary["baseline"]
    print(f"best: {b['family']} {b['strategy']}")
    print(f"  search seeds   {_fmt(b['search'])}")
    if b["rerank"]:
        print(f"  re-rank seeds  {_fmt(b['rerank'])}")
    print(f"best linear ramp: {lin['strategy']}")
    if lin["search"]:
        print(f"  search seeds   {_fmt(lin['search'])}")
    cmp = summary["comparison"]
    if cmp:
        print(f"held-out seeds {summary['holdout_seeds'][0]}..{summary['holdout_seeds'][1]}:")
        print(f"  best           {_fmt(b['holdout'])}")
        print(f"  linear         {_fmt(lin['holdout'])}")
        lo, hi = cmp["ci95"]
        w, worse, eq = cmp["better_worse_equal"]
        print(f"  paired difference {cmp['difference_mean']:+.2f} ± {cmp['difference_se']:.2f}"
              f" (95 % CI {lo:+.2f} .. {hi:+.2f}); better on {w}, worse on {worse},"
              f" equal on {eq} seeds")  # fmt: skip
    print(f"wrote {out}/: best.json, pareto.csv, trials.csv, summary.json, optimize.png")
