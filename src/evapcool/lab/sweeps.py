"""Lab experiments at scale: every combination of a spec's parameters is one lab run.

A spec (TOML, or the same as a dict) lists values or ranges for lab parameters and a
range of seeds; `sweep(spec)` runs them all as Dask tasks (lab/cluster.py) and returns two
tidy pandas tables: one row per run (its parameters, the final N, T, won frame, rates, and
the program and library versions it ran with) and one row per record. With an output
folder the tables are written as Parquet (and CSV on request); runs already there are
skipped (keyed by their parameters), so an interrupted sweep resumes where it stopped, and
a run that fails is recorded with its error while the others go on.

    [sweep]
    seeds = { from = 1, to = 20 }          # or [1, 5, 9], or 7
    [parameters]
    n_atoms = [49, 100]
    schedule = ["400@0,140@1800", "eta=6"]
    radius = { from = 6, to = 12, step = 2 }   # or num = 4 (linspace), log = true
"""

from __future__ import annotations

import contextlib
import hashlib
import itertools
import json
import math
import numbers
import os
import sys
import time
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from evapcool.fileio import atomic_write_bytes, atomic_write_text, locked, set_aside
from evapcool.lab.experiment import LabConfig
from evapcool.lab.io import RENAMED_PARAMETERS, current_names
from evapcool.limits import ParameterError

#: Lab parameters a spec may set (the seed comes from [sweep] seeds); 'eta' is short for
#: schedule = "eta=...".
PARAMETERS = (*(f.name for f in fields(LabConfig) if f.name != "seed"), "eta")
SWEEP_KEYS = ("seeds",)
RUNS_FILE = "runs.parquet"
RECORDS_FILE = "records.parquet"
PARTS_DIR = "parts"
SPEC_FILE = "spec.toml"
CHECKPOINT_SECONDS = 10.0
#: How long a sweep waits for another one merging into the same folder (seconds).
MERGE_LOCK_SECONDS = 600.0
#: The spec `evapcool sweep --example FILE` writes (docs/cluster.md shows it).
EXAMPLE_SPEC = """\
# rim-or-knife.toml: the game's gas, two escape rules, two schedules, five seeds (20 runs)
[sweep]
seeds = { from = 1, to = 5 }              # or [1, 2, 3], or 7

[parameters]
n_atoms = 49
escape = ["rim", "knife"]
schedule = ["425@0,162@1788", "eta=5"]    # or eta = [4, 5, 6]
frames = 1800
every = 60
engine = "fast"
# radius = { from = 6, to = 12, step = 2 }        a range, both ends included
# curvature = { from = 0.005, to = 0.02, num = 4 }    evenly spaced (log = true: geometric)
"""
#: Summary columns of the runs table besides the parameters (docs/cluster.md explains them).
RESULT_COLUMNS = (
    "run_id", "status", "error", "completed", "frames_done", "won_frame", "n_initial",
    "n_final", "temperature_initial", "temperature_final", "critical_temperature_final",
    "escaped", "pair_collisions", "wall_collisions", "escape_rate", "pair_collision_rate",
    "wall_collision_rate", "cooling_efficiency", "phase_space_density_gain",
)  # fmt: skip
ENV_COLUMNS = (
    "evapcool_version", "python_version", "numpy_version", "core_compiler", "host", "platform",
    "worker", "cpu_seconds", "wall_seconds",
)  # fmt: skip


class SpecError(ValueError):
    """A bad spec: the message names the field and what is allowed."""


# -- the spec ---------------------------------------------------------------------------------


def load_spec(spec: str | os.PathLike[str] | Mapping) -> dict:
    """The spec as a dict: from a TOML file (path) or a mapping; SpecError if unreadable."""
    if isinstance(spec, Mapping):
        return dict(spec)
    path = Path(spec)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise SpecError(f"spec {str(path)!r} cannot be read: {exc.strerror or exc}") from None
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - Python 3.10
        import tomli as tomllib
    try:
        return tomllib.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise SpecError(f"spec {str(path)!r} is not valid TOML: {exc}") from None


def _is_number(v: object) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def _range(name: str, table: Mapping) -> list:
    """Values of a {from, to, step} / {from, to, num[, log]} table, 'to' included."""
    where = f"{name}: a range"
    allowed = {"from", "to", "step", "num", "log"}
    extra = sorted(set(table) - allowed)
    if extra:
        raise SpecError(f"{where} has no key {extra[0]!r}; allowed: from, to, step or num, log")
    lo, hi = table.get("from"), table.get("to")
    if not (_is_number(lo) and _is_number(hi) and math.isfinite(lo) and math.isfinite(hi)):
        raise SpecError(f"{where} needs numbers from and to (got from={lo!r}, to={hi!r})")
    if "step" not in table and "num" not in table and all(isinstance(v, int) for v in (lo, hi)):
        table = {**table, "step": 1}  # {from = 1, to = 20}: every whole number
    if ("step" in table) == ("num" in table):
        raise SpecError(f"{where} needs exactly one of step (> 0) or num (>= 1)")
    log = table.get("log", False)
    if not isinstance(log, bool):
        raise SpecError(f"{where}: log must be true or false (got {log!r})")
    if "step" in table:
        step = table["step"]
        if not (_is_number(step) and math.isfinite(step) and step > 0) or log or hi < lo:
            raise SpecError(f"{where}: step must be a number > 0 with to >= from, without log")
        count = math.floor((hi - lo) / step + 1e-9) + 1
        if count > 1_000_000:
            raise SpecError(f"{where} has more than a million values")
        ints = all(isinstance(v, int) for v in (lo, hi, step))
        return [lo + k * step if ints else round(lo + k * step, 12) for k in range(count)]
    num = table["num"]
    if isinstance(num, bool) or not isinstance(num, int) or num < 1:
        raise SpecError(f"{where}: num must be a whole number >= 1 (got {num!r})")
    if log and not (lo > 0 and hi > 0):
        raise SpecError(f"{where}: log needs from and to > 0")
    if num == 1:
        return [lo]
    if log:
        a, b = math.log(lo), math.log(hi)
        return [math.exp(a + (b - a) * k / (num - 1)) for k in range(num)]
    return [lo + (hi - lo) * k / (num - 1) for k in range(num)]


def _values(name: str, value: object) -> list:
    if isinstance(value, Mapping):
        return _range(name, value)
    if isinstance(value, list):
        if not value:
            raise SpecError(f"{name}: the list is empty; give at least one value")
        return list(value)
    return [value]


def _seeds(value: object) -> list[int]:
    seeds = _values("sweep.seeds", value)
    for s in seeds:
        if isinstance(s, bool) or not isinstance(s, int) or s < 0:
            raise SpecError(f"sweep.seeds: seeds must be whole numbers >= 0 (got {s!r})")
    if len(set(seeds)) != len(seeds):
        raise SpecError("sweep.seeds: a seed is listed twice")
    return seeds


def expand(spec: Mapping) -> list[dict]:
    """Every run of the spec as validated LabConfig fields (seed last); SpecError on bad input.

    Nothing runs and nothing is written before the whole spec has been checked.
    """
    unknown = sorted(set(spec) - {"sweep", "parameters"})
    if unknown:
        raise SpecError(f"{unknown[0]}: unknown table; a spec has [sweep] and [parameters]")
    head = spec.get("sweep", {})
    params = spec.get("parameters", {})
    for name, table in (("sweep", head), ("parameters", params)):
        if not isinstance(table, Mapping):
            raise SpecError(f"{name} must be a table ([{name}])")
    bad = sorted(set(head) - set(SWEEP_KEYS))
    if bad:
        raise SpecError(f"sweep.{bad[0]}: unknown key; [sweep] has {', '.join(SWEEP_KEYS)}")
    if "seeds" not in head:
        raise SpecError("sweep.seeds is missing: give seeds = [1, 2] or { from = 1, to = 20 }")
    try:
        params = current_names(params)  # older specs name the atom count `atoms`
    except ValueError as exc:
        raise SpecError(f"parameters.{exc}") from None
    bad = sorted(set(params) - set(PARAMETERS))
    if bad:
        raise SpecError(f"parameters.{bad[0]}: unknown parameter; allowed: {', '.join(PARAMETERS)}")
    if "eta" in params and "schedule" in params:
        raise SpecError("parameters.eta: give eta or schedule, not both (eta = 6 means eta=6)")
    seeds = _seeds(head["seeds"])
    names = sorted(params)
    grids = [_values(f"parameters.{n}", params[n]) for n in names]
    runs = []
    checked: set[tuple] = set()
    for combo in itertools.product(*grids):
        base = dict(zip(names, combo, strict=True))
        if "eta" in base:
            eta = base.pop("eta")
            base["schedule"] = f"eta={eta}" if _is_number(eta) else eta
        key = tuple(sorted((k, repr(v)) for k, v in base.items()))
        if key not in checked:  # check each combination once, with the first seed
            _check(base, seeds[0])
            checked.add(key)
        for seed in seeds:
            runs.append(asdict(LabConfig(**base, seed=seed).validated()))
    return runs


def _check(base: dict, seed: int) -> None:
    try:
        LabConfig(**base, seed=seed).validated()
    except (ValueError, TypeError) as exc:
        msg = str(exc)
        field = exc.parameter if isinstance(exc, ParameterError) else ""
        name = "eta" if field == "schedule" and "eta" in base.get("schedule", "") else field
        prefix = f"parameters.{name}: " if name in PARAMETERS else ""
        raise SpecError(prefix + msg) from None


def run_id(params: Mapping) -> str:
    """The run's key: a hash of its parameters (the same run always gets the same id).

    Hashed under the parameters' first names (`atoms` for n_atoms), so a sweep folder of an
    older version resumes: its runs keep their ids."""
    first_name = {new: old for old, new in RENAMED_PARAMETERS.items()}
    named = {first_name.get(k, k): v for k, v in params.items()}
    text = json.dumps({k: named[k] for k in sorted(named)}, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


# -- one run (on a worker) --------------------------------------------------------------------


def run_one(params: dict) -> tuple[dict, dict | None]:
    """One lab run: (its row of the runs table, its records as columns, None if it failed)."""
    from evapcool.lab.cluster import worker_environment
    from evapcool.lab.experiment import run_experiment

    row: dict = {"run_id": run_id(params), **params}
    row.update(worker_environment())
    row["worker"] = _worker_name()
    wall, cpu = time.perf_counter(), time.process_time()
    records = None
    try:
        result = run_experiment(progress=False, **params)
    except Exception as exc:  # recorded, and the sweep goes on
        row.update(status="failed", error=f"{type(exc).__name__}: {exc}")
    else:
        row.update(status="ok", error="", **_summary(result))
        records = {"run_id": [row["run_id"]] * len(result), **result.columns}
    row["cpu_seconds"] = time.process_time() - cpu
    row["wall_seconds"] = time.perf_counter() - wall
    return row, records


def _worker_name() -> str:
    try:
        from distributed import get_worker

        return str(get_worker().address)
    except (ImportError, ValueError):
        return "local"


def _summary(result) -> dict:
    from evapcool.physics.simulation import FPS

    c = result.columns
    n, t = c["n_trapped"], c["temperature"]
    frames = int(result.metadata["frames_done"])
    seconds = frames / FPS
    n_mean = float(n.mean()) if len(n) else math.nan
    won = result.metadata.get("won_frame")
    if len(n) and n[-1] > 0 and n[-1] != n[0] and t[-1] > 0:
        efficiency = math.log(t[-1] / t[0]) / math.log(n[-1] / n[0])
    else:
        efficiency = math.nan
    per = seconds if seconds > 0 else math.nan
    return {
        "completed": bool(result.completed),
        "frames_done": frames,
        "won_frame": -1 if won is None else int(won),
        "n_initial": int(n[0]),
        "n_final": int(n[-1]),
        "temperature_initial": float(t[0]),
        "temperature_final": float(t[-1]),
        "critical_temperature_final": float(c["critical_temperature"][-1]),
        "escaped": int(c["escaped"][-1]),
        "pair_collisions": int(c["pair_collisions"][-1]),
        "wall_collisions": int(c["wall_collisions"][-1]),
        "escape_rate": float(c["escaped"][-1]) / per,
        "pair_collision_rate": float(c["pair_collisions"][-1]) / per / n_mean,
        "wall_collision_rate": float(c["wall_collisions"][-1]) / per / n_mean,
        "cooling_efficiency": efficiency,
        "phase_space_density_gain": float(c["phase_space_density"][-1]),
    }


# -- tables on disk ---------------------------------------------------------------------------


@dataclass
class SweepResult:
    """The sweep's tables: runs (one row per run) and records (one row per record)."""

    runs: object  # pandas.DataFrame
    records: object  # pandas.DataFrame
    out: Path | None = None
    ran: int = 0
    skipped: int = 0

    @property
    def failed(self) -> int:
        return int((self.runs["status"] != "ok").sum()) if len(self.runs) else 0


def _parquet_bytes(frame) -> bytes:
    import io

    buf = io.BytesIO()
    frame.to_parquet(buf, index=False)
    return buf.getvalue()


def _read_table(path: Path, notices: list[str]):
    import pandas as pd

    try:
        # An older version's table names some parameters as they were called then.
        return pd.read_parquet(path).rename(columns=RENAMED_PARAMETERS)
    except FileNotFoundError:  # a part another sweep merged meanwhile: its runs are merged
        return None
    except Exception as exc:  # a damaged file: set aside, never lost, never fatal
        moved = set_aside(path)
        notices.append(f"{path.name} could not be read ({type(exc).__name__}); kept as {moved}")
        return None


def _load(out: Path, notices: list[str], parts_read: list[Path] | None = None) -> tuple:
    """Runs and records already in the output folder (tables plus unmerged parts);
    the part files read are added to parts_read."""
    import pandas as pd

    runs, records = [], []
    for name, bucket in ((RUNS_FILE, runs), (RECORDS_FILE, records)):
        if (out / name).exists():
            t = _read_table(out / name, notices)
            if t is not None:
                bucket.append(t)
    parts = out / PARTS_DIR
    if parts.is_dir():
        for path in sorted(parts.glob("*.parquet")):
            t = _read_table(path, notices)
            if t is not None:
                (runs if path.name.startswith("runs-") else records).append(t)
                if parts_read is not None:
                    parts_read.append(path)
    return _merge(runs, "runs"), _merge(records, "records") if records else pd.DataFrame()


def _merge(tables: list, kind: str):
    import pandas as pd

    tables = [t for t in tables if len(t)]
    if not tables:
        return pd.DataFrame()
    frame = pd.concat(tables, ignore_index=True)
    keys = ["run_id"] if kind == "runs" else ["run_id", "frame"]
    return frame.drop_duplicates(keys, keep="last").reset_index(drop=True)


def _ordered(runs):
    """Runs table columns in a fixed order: results, parameters, environment."""
    params = [f.name for f in fields(LabConfig)]
    cols = [c for c in (*RESULT_COLUMNS, *params, *ENV_COLUMNS) if c in runs.columns]
    cols += [c for c in runs.columns if c not in cols]
    return runs[cols]


class _Writer:
    """Collects finished runs; with a folder, writes them as part files every few seconds.

    Without a folder every run stays in memory (the tables `sweep` returns); with one,
    only runs not yet written do, and the tables are read back from the files at the end.
    """

    def __init__(self, out: Path | None) -> None:
        self.out = out
        self.rows: list[dict] = []
        self.records: list[dict] = []
        self.failed = 0
        self.last = time.monotonic()
        self.serial = 0

    def add(self, row: dict, records: dict | None) -> None:
        self.rows.append(row)
        if records is not None:
            self.records.append(records)
        self.failed += row["status"] != "ok"
        if self.out is not None and time.monotonic() - self.last > CHECKPOINT_SECONDS:
            self.flush()

    def flush(self) -> None:
        if self.out is None or not self.rows:
            return
        import pandas as pd

        parts = self.out / PARTS_DIR
        tag = f"{os.getpid()}-{time.time_ns()}-{self.serial}"
        runs = _parquet_bytes(pd.DataFrame(self.rows))
        records = _parquet_bytes(_records(self.records)) if self.records else None
        for attempt in range(5):  # another sweep's merge may remove the empty folder
            parts.mkdir(parents=True, exist_ok=True)
            try:
                # Records first: a run whose row is on disk always has its records too.
                if records is not None:
                    atomic_write_bytes(parts / f"records-{tag}.parquet", records)
                atomic_write_bytes(parts / f"runs-{tag}.parquet", runs)
                break
            except FileNotFoundError:
                if attempt == 4:
                    raise
        self.rows, self.records = [], []
        self.serial += 1
        self.last = time.monotonic()


def _records(chunks: list[dict]):
    import pandas as pd

    if not chunks:
        return pd.DataFrame()
    return pd.concat([pd.DataFrame(c) for c in chunks], ignore_index=True)


def _consolidate(out: Path, csv: bool, notices: list[str]) -> tuple:
    """Merge the part files into runs.parquet and records.parquet (and CSV), then drop them.

    Under the folder's lock, and only the parts it read are dropped: another sweep into
    the same folder may write parts meanwhile, and merges after this one (issue 18).
    """
    with locked(out / RUNS_FILE, timeout=MERGE_LOCK_SECONDS):
        parts_read: list[Path] = []
        runs, records = _load(out, notices, parts_read)
        if len(runs):
            runs = _ordered(runs)
        atomic_write_bytes(out / RUNS_FILE, _parquet_bytes(runs))
        atomic_write_bytes(out / RECORDS_FILE, _parquet_bytes(records))
        if csv:
            atomic_write_text(out / "runs.csv", runs.to_csv(index=False))
            atomic_write_text(out / "records.csv", records.to_csv(index=False))
        for path in parts_read:
            path.unlink(missing_ok=True)
        with contextlib.suppress(OSError):  # another process's parts may still be there
            (out / PARTS_DIR).rmdir()
    return runs, records


def check_out(out: str | os.PathLike[str]) -> Path:
    """The output folder, if it is (or can be made) a writable folder; SpecError-free ValueError."""
    p = Path(out)
    if p.exists() and not p.is_dir():
        raise ValueError(f"out must be a folder (got the file {str(p)!r})")
    parent = p
    while not parent.exists():
        parent = parent.parent
    if not os.access(parent, os.W_OK | os.X_OK):
        raise ValueError(f"out must be a writable folder (got {str(p)!r})")
    return p


# -- the sweep -------------------------------------------------------------------------------


def plan(spec, out: str | os.PathLike[str] | None = None) -> tuple[list[dict], list[dict]]:
    """(every run of the spec, the ones still to do given what out already holds)."""
    runs = expand(load_spec(spec))
    if out is None or not Path(out).is_dir():
        return runs, runs
    done, _ = _load(Path(out), [])
    ok = set(done.loc[done["status"] == "ok", "run_id"]) if len(done) else set()
    return runs, [r for r in runs if run_id(r) not in ok]


def sweep(
    spec: str | os.PathLike[str] | Mapping,
    out: str | os.PathLike[str] | None = None,
    *,
    scheduler: str | None = None,
    workers: int | None = None,
    csv: bool = False,
    progress: bool | None = False,
    on_run: Callable[[dict], None] | None = None,
    log: Callable[[str], None] | None = None,
) -> SweepResult:
    """Run every combination of the spec as Dask tasks; pandas tables of runs and records.

    spec: a TOML file or a dict of the same shape. out: a folder for runs.parquet and
    records.parquet (runs already there are skipped; a copy of the spec is kept beside
    them); None keeps everything in memory. scheduler / workers: as in lab.cluster.connect.
    Bad input raises ValueError (a SpecError names the spec's field) before anything runs.
    """
    from evapcool.lab.cluster import check_scheduler, check_workers, require_extra

    require_extra("sweep")
    check_scheduler(scheduler)
    check_workers(workers)
    runs, todo = plan(spec, out)
    target = check_out(out) if out is not None else None
    notices: list[str] = []
    writer = _Writer(target)

    def start() -> None:  # once the cluster is there: nothing is written before
        if target is not None:
            target.mkdir(parents=True, exist_ok=True)
            if isinstance(spec, Mapping):
                atomic_write_text(target / "spec.json", json.dumps(spec, indent=2, default=repr))
            else:
                atomic_write_bytes(target / SPEC_FILE, Path(spec).read_bytes())

    if not todo:
        start()
    try:
        if todo:
            _execute(todo, writer, scheduler, workers, progress, on_run, log, start)
    finally:  # also on Ctrl-C: what finished is merged into the tables
        if target is not None and target.is_dir():
            writer.flush()
            all_runs, all_records = _consolidate(target, csv, notices)
    if target is not None:
        ids = {run_id(r) for r in runs}
        result_runs = all_runs[all_runs["run_id"].isin(ids)] if len(all_runs) else all_runs
        result_records = (
            all_records[all_records["run_id"].isin(ids)] if len(all_records) else all_records
        )
    else:
        import pandas as pd

        result_runs = _ordered(pd.DataFrame(writer.rows)) if writer.rows else pd.DataFrame()
        result_records = _records(writer.records)
    for text in notices:
        if log is not None:
            log(text)
    return SweepResult(
        result_runs.reset_index(drop=True),
        result_records.reset_index(drop=True),
        target,
        ran=len(todo),
        skipped=len(runs) - len(todo),
    )


def _execute(todo, writer: _Writer, scheduler, workers, progress, on_run, log, start) -> None:
    from evapcool.lab.cluster import StopRequest, TaskError, connect, run_tasks

    bar = None
    try:
        with StopRequest() as stop, connect(scheduler, workers) as engine:
            start()
            bar = _bar(len(todo), progress)
            if log is not None:
                log(f"{len(todo)} runs on {engine.description}")

            def got(i: int, value: object) -> None:
                if isinstance(value, TaskError):
                    row = {"run_id": run_id(todo[i]), **todo[i], "status": "failed",
                           "error": value.message}  # fmt: skip
                    writer.add(row, None)
                else:
                    row, records = value
                    writer.add(row, records)
                if on_run is not None:
                    on_run(row)
                bar.update(1)
                if writer.failed:
                    bar.set_postfix_str(f"{writer.failed} failed", refresh=False)

            run_tasks(engine, run_one, [(p,) for p in todo], got, stop=stop)
    finally:
        if bar is not None:
            bar.close()
        writer.flush()


def _bar(total: int, progress: bool | None):
    from tqdm import tqdm

    disable = None if progress is None else not progress  # None: only on a terminal
    return tqdm(total=total, unit="run", desc="runs", disable=disable, dynamic_ncols=True)


def per_run_costs(runs) -> dict:
    """Median CPU and wall seconds per successful run (for docs/cluster.md's estimates)."""
    ok = runs[runs["status"] == "ok"]
    return {
        "runs": len(ok),
        "cpu_seconds_median": float(ok["cpu_seconds"].median()) if len(ok) else math.nan,
        "wall_seconds_median": float(ok["wall_seconds"].median()) if len(ok) else math.nan,
    }
