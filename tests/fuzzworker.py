"""The process that runs fuzz cases for tests/test_fuzz.py, one at a time.

Protocol: one line of base64(pickle(case)) in, one line of JSON out. The parent kills
this process when a case runs over its time limit, and reads the peak memory from
every answer. Cases run with the working directory the parent made (files to read,
folders to write) and with the user folders pointed there too.
"""

from __future__ import annotations

import base64
import contextlib
import importlib
import io
import json
import os
import pickle
import sys
import traceback


def peak_rss_mb() -> float:
    try:
        import resource
    except ImportError:  # Windows
        return 0.0
    kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return kb / 1024 if sys.platform != "darwin" else kb / 2**20


def _stub_bench() -> None:
    """`evapcool bench` sections take minutes; the fuzz is about their options."""
    from evapcool import bench

    for name in bench.SECTIONS.values():
        with contextlib.suppress(ImportError):
            importlib.import_module(name).run = lambda args: print("[bench stub]")


def _warm_up() -> None:
    """Compile (or load) the fast engine once, outside any case's time limit."""
    try:
        from evapcool.physics import fast
    except ImportError:
        return
    prepare = getattr(fast, "prepare", None)
    if prepare is not None:
        prepare()
    else:
        from evapcool import Simulation

        Simulation(100, radius=3.0, engine="fast", seed=1).advance(1.0)


def run_cli(argv: list[str]) -> dict:
    from evapcool.cli import main

    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        try:
            code = main(argv)
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
    return {"code": code, "stderr": err.getvalue()}


def _finite(*values: object) -> bool:
    import numpy as np

    return all(bool(np.all(np.isfinite(np.asarray(v, dtype=float)))) for v in values)


def run_sim(kwargs: dict, dt: object) -> dict:
    from evapcool import Simulation

    try:
        sim = Simulation(**kwargs)
    except (ValueError, TypeError) as exc:
        return {"error": type(exc).__name__, "message": str(exc), "stage": "init"}
    try:
        sim.advance(dt)
    except (ValueError, TypeError) as exc:
        return {"error": type(exc).__name__, "message": str(exc), "stage": "advance"}
    finite = _finite(
        sim.positions,
        sim.velocities,
        sim.temperature,
        sim.total_energy(),
        sim.critical_temperature,
        sim.escaped_positions,
    )
    return {"ok": True, "finite": finite, "events": sim.collision_count, "n": sim.n_atoms}


def run_state(state: object, dt: object) -> dict:
    from evapcool import Simulation

    try:
        sim = Simulation.from_state(state)
        sim.advance(dt)
    except (ValueError, TypeError) as exc:
        return {"error": type(exc).__name__, "message": str(exc)}
    finite = _finite(sim.positions, sim.velocities, sim.temperature, sim.total_energy())
    return {"ok": True, "finite": finite, "events": sim.collision_count}


def run_lab(kwargs: dict) -> dict:
    from evapcool.lab.experiment import run_experiment

    try:
        result = run_experiment(**kwargs)
    except (ValueError, TypeError) as exc:
        return {"error": type(exc).__name__, "message": str(exc)}
    finite = _finite(*(result.columns[c] for c in ("temperature", "total_energy")))
    return {"ok": True, "finite": finite, "records": len(result)}


def run_case(case: dict) -> dict:
    kind = case["kind"]
    if kind == "cli":
        return run_cli(case["argv"])
    if kind == "sim":
        return run_sim(case["kwargs"], case["dt"])
    if kind == "lab":
        return run_lab(case["kwargs"])
    if kind == "state":
        return run_state(case["state"], case["dt"])
    raise ValueError(f"unknown case kind {kind!r}")


def main() -> None:
    os.chdir(sys.argv[1])
    _stub_bench()
    _warm_up()
    print(json.dumps({"ready": True}), flush=True)
    for line in sys.stdin:
        case = pickle.loads(base64.b64decode(line))
        try:
            answer = run_case(case)
        except BaseException:  # a crash is the finding: report it, keep serving
            answer = {"crash": traceback.format_exc()}
        answer["rss_mb"] = peak_rss_mb()
        print(json.dumps(answer, default=str, allow_nan=True), flush=True)


if __name__ == "__main__":
    main()
