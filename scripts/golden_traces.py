"""Golden traces: write, check or make the event traces the web engine must replay bit for bit.

    python scripts/golden_traces.py write            # web/test/golden/*.json from the reference
                                                     # engine; the fast engine must agree
    python scripts/golden_traces.py check            # the committed traces still match (exit 1
                                                     # naming the ones that do not)
    python scripts/golden_traces.py run STATE.json --events N [--engine fast]
                                                     # any state: its trace on stdout

`npm run replay -- STATE.json --events N` (in web/) prints the web engine's trace of the same
state in the same format: `diff` the two. See docs/state.md.
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
from pathlib import Path

from evapcool.fileio import atomic_write_text
from evapcool.physics.state import read_json
from evapcool.physics.trace import (
    GOLDEN_CASES,
    golden_trace,
    make_trace,
    replay,
    trace_text,
)

GOLDEN_DIR = Path(__file__).resolve().parents[1] / "web" / "test" / "golden"


def _fast_available() -> bool:
    return importlib.util.find_spec("evapcool.physics._core") is not None


def _write(out: Path, only: list[str] | None) -> int:
    out.mkdir(parents=True, exist_ok=True)
    fast = _fast_available()
    for case in GOLDEN_CASES:
        if only and case.name not in only:
            continue
        trace = golden_trace(case)
        text = trace_text(trace)
        if fast and trace_text(replay(trace, "fast")) != text:
            print(f"{case.name}: the core disagrees with the reference engine", file=sys.stderr)
            return 1
        atomic_write_text(out / f"{case.name}.json", text)
        print(f"{case.name}: {len(trace['events'])} events, {len(trace['steps'])} steps"
              + (", fast engine agrees" if fast else ""))  # fmt: skip
    return 0


def _check(out: Path, only: list[str] | None) -> int:
    bad = 0
    for case in GOLDEN_CASES:
        if only and case.name not in only:
            continue
        path = out / f"{case.name}.json"
        fresh = trace_text(golden_trace(case))
        if not path.exists() or path.read_text(encoding="utf-8") != fresh:
            print(f"{case.name}: {path} does not match the engines", file=sys.stderr)
            bad += 1
    return 1 if bad else 0


def _run(state_path: Path, events: int, engine: str) -> int:
    try:
        state = read_json(state_path.read_text(encoding="utf-8"))
        if not isinstance(state, dict):
            raise ValueError("state must be a JSON object")
        trace = make_trace(state_path.stem, f"{events} events from {state_path.name}", state,
                           events, None, engine)  # fmt: skip
    except (OSError, ValueError) as e:
        print(f"golden_traces: {e}", file=sys.stderr)
        return 2
    sys.stdout.write(trace_text(trace))
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    w = sub.add_parser("write", help="write the golden traces")
    w.add_argument("--out", type=Path, default=GOLDEN_DIR)
    w.add_argument("cases", nargs="*", help="only these cases")
    c = sub.add_parser("check", help="check the committed golden traces")
    c.add_argument("--out", type=Path, default=GOLDEN_DIR)
    c.add_argument("cases", nargs="*", help="only these cases")
    r = sub.add_parser("run", help="print the trace of any state file")
    r.add_argument("state", type=Path)
    r.add_argument("--events", type=int, default=2000)
    r.add_argument("--engine", choices=("reference", "fast"), default="reference")
    args = parser.parse_args(argv)
    if args.command == "write":
        return _write(args.out, args.cases)
    if args.command == "check":
        return _check(args.out, args.cases)
    if args.events < 1:
        parser.error("--events must be a whole number >= 1")
    return _run(args.state, args.events, args.engine)


if __name__ == "__main__":
    sys.exit(main())
