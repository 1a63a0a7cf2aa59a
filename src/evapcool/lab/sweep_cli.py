"""`evapcool sweep SPEC.toml`: every combination of a spec's lab parameters, on Dask."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from evapcool.about import error_line
from evapcool.argtypes import Parser
from evapcool.lab.cluster import VersionMismatchError, add_cluster_options, open_command

PROG = "evapcool sweep"
EXIT_USAGE = 2
EXIT_FAILED_RUNS = 1
EXIT_INTERRUPTED = 130


def build_parser() -> argparse.ArgumentParser:
    p = Parser(
        prog=PROG,
        description=(
            "Run every combination of the lab parameters in a TOML spec as one lab run each, "
            "on a local Dask cluster or a running one; tidy Parquet tables out. "
            "See docs/cluster.md."
        ),
    )
    p.add_argument(
        "spec", metavar="SPEC.toml", nargs="?", help="the sweep: [sweep] seeds, [parameters]"
    )
    p.add_argument(
        "--example", metavar="FILE", help="write an example spec to FILE (to edit) and exit"
    )
    p.add_argument(
        "--out",
        metavar="DIR",
        help="folder for runs.parquet and records.parquet (default: SPEC-results); "
        "runs already there are skipped",
    )
    p.add_argument("--csv", action="store_true", help="also write runs.csv and records.csv")
    add_cluster_options(p)
    p.add_argument(
        "--dry-run", action="store_true", help="check the spec, say how many runs, run nothing"
    )
    return p


def _fail(message: str) -> int:
    print(error_line("sweep", message), file=sys.stderr)
    return EXIT_USAGE


def _write_example(path: Path, text: str) -> int:
    from evapcool.fileio import atomic_write_text

    if path.exists():
        return _fail(f"--example {str(path)!r} exists; give a new file name")
    if not path.parent.is_dir():
        return _fail(f"--example: folder {str(path.parent)!r} does not exist")
    atomic_write_text(path, text)
    print(f"wrote {path}; run it with: evapcool sweep {path}", file=sys.stderr)
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of `evapcool sweep`; 0 all ran, 1 some runs failed, 2 bad input, 130 Ctrl-C."""
    args = open_command("sweep", build_parser(), argv)
    if isinstance(args, int):
        return args
    from evapcool.lab.sweeps import EXAMPLE_SPEC, check_out, plan, sweep

    if args.example is not None:
        return _write_example(Path(args.example), EXAMPLE_SPEC)
    if args.spec is None:
        return _fail("give a spec file (SPEC.toml), or --example FILE to write one")
    spec = Path(args.spec)
    out = Path(args.out) if args.out else spec.with_name(spec.stem + "-results")
    try:
        runs, todo = plan(spec, out)
        check_out(out)
    except ValueError as exc:
        text = str(exc)
        return _fail(text if text.startswith(("spec", "out")) else f"{spec}: {text}")
    if args.dry_run:
        print(f"{len(runs)} runs in {spec}; {len(runs) - len(todo)} already in {out}")
        return 0

    def log(text: str) -> None:
        print(f"{PROG}: {text}", file=sys.stderr)

    start = time.monotonic()
    try:
        result = sweep(
            spec,
            out,
            scheduler=args.scheduler,
            workers=args.workers,
            csv=args.csv,
            progress=None,
            log=log,
        )
    except KeyboardInterrupt:
        log(f"interrupted; finished runs are in {out}; run the same command to go on")
        return EXIT_INTERRUPTED
    except (OSError, TimeoutError, VersionMismatchError) as exc:
        return _fail(f"--scheduler {args.scheduler}: {exc}" if args.scheduler else str(exc))
    elapsed = time.monotonic() - start
    failed = result.failed
    log(
        f"{result.ran} runs in {elapsed:.1f} s, {result.skipped} already done, "
        f"{failed} failed; {len(result.runs)} runs and {len(result.records)} records in {out}"
    )
    if failed:
        bad = result.runs[result.runs["status"] != "ok"].iloc[0]
        log(f"first failure: run {bad['run_id']}: {bad['error']}")
        return EXIT_FAILED_RUNS
    return 0
