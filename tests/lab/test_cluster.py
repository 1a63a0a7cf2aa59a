"""The Dask side, for real: a `dask scheduler` and two `dask worker` processes on 127.0.0.1.

Sweeps and searches give the same results there as on the default local cluster; a worker
killed mid-sweep loses no finished run; several processes work on one study; an interrupted
search resumes; bad options get one line and exit 2 with nothing written.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

pd = pytest.importorskip("pandas")
optuna = pytest.importorskip("optuna")
pytest.importorskip("distributed")

from clusterhelp import Cluster, evapcool  # noqa: E402

from evapcool.extras import install_hint  # noqa: E402
from evapcool.lab import sweep  # noqa: E402
from evapcool.lab.sweeps import ENV_COLUMNS  # noqa: E402
from evapcool.optimize.study import result_of  # noqa: E402

VARYING = [*ENV_COLUMNS]  # where and how long: the rest must be identical
SPEC = """
[sweep]
seeds = { from = 1, to = 4 }
[parameters]
n_atoms = [10, 14]
radius = 5
schedule = ["200@0,40@300", "eta=5"]
frames = 300
every = 60
engine = "fast"
"""
SEARCH = ["--budget", "600", "--seeds", "4", "--batch", "2", "--chunk", "2", "--sampler-seed",
          "5", "--validate", "0", "--family", "linear,feedback"]  # fmt: skip


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    c = Cluster(tmp_path_factory.mktemp("dask"), workers=2)
    yield c
    c.close()


def _params(trial) -> dict:
    """A trial's parameters; a queued one keeps them as fixed parameters until it runs."""
    return trial.params or dict(trial.system_attrs.get("fixed_params", {}))


def _trials(db) -> list[tuple]:
    study = optuna.load_study(study_name="evapcool", storage=f"sqlite:///{db}")
    return [
        (t.number, t.state.name, tuple(sorted(_params(t).items())), t.values,
         result_of(t).get("scores"))
        for t in sorted(study.trials, key=lambda t: t.number)
    ]  # fmt: skip


# -- sweeps --------------------------------------------------------------------------------------


def test_sweep_on_a_scheduler_matches_the_local_cluster(cluster, tmp_path):
    spec = tmp_path / "spec.toml"
    spec.write_text(SPEC)
    local = sweep(spec, tmp_path / "local", workers=2)
    r = evapcool("sweep", str(spec), "--scheduler", cluster.address, "--out", "remote",
                 cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    remote = pd.read_parquet(tmp_path / "remote" / "runs.parquet")
    key = "run_id"
    a = local.runs.drop(columns=VARYING).sort_values(key).reset_index(drop=True)
    b = remote.drop(columns=VARYING).sort_values(key).reset_index(drop=True)
    pd.testing.assert_frame_equal(a, b)
    ra = local.records.sort_values([key, "frame"]).reset_index(drop=True)
    rb = pd.read_parquet(tmp_path / "remote" / "records.parquet")
    pd.testing.assert_frame_equal(ra, rb.sort_values([key, "frame"]).reset_index(drop=True))
    assert set(remote["worker"]) <= {w for w in _worker_addresses(cluster)}


def _worker_addresses(cluster) -> set[str]:
    from dask.distributed import Client

    with Client(cluster.address, timeout="20s") as c:
        return set(c.scheduler_info()["workers"])


def test_a_worker_killed_mid_sweep_loses_no_finished_run(tmp_path):
    c = Cluster(tmp_path / "dask", workers=2)
    try:
        spec = tmp_path / "spec.toml"
        spec.write_text(
            "[sweep]\nseeds = { from = 1, to = 24 }\n[parameters]\natoms = 120\nradius = 4\n"
            'frames = 600\nevery = 100\nengine = "fast"\nschedule = "300@0,30@600"\n'
        )
        done: list[dict] = []
        killed = threading.Event()

        def on_run(row: dict) -> None:
            done.append(row)
            if len(done) == 4 and not killed.is_set():
                killed.set()
                c.kill(c.workers[0])

        result = sweep(spec, tmp_path / "out", scheduler=c.address, on_run=on_run)
        assert killed.is_set()
        assert len(result.runs) == 24 and (result.runs["status"] == "ok").all()
        assert result.runs["run_id"].is_unique and sorted(result.runs["seed"]) == list(range(1, 25))
        # The runs finished before the kill are in the table unchanged.
        before = {r["run_id"]: r["n_final"] for r in done[:4]}
        table = result.runs.set_index("run_id")
        assert all(table.loc[k, "n_final"] == v for k, v in before.items())
        # And every run is the run it would have been anywhere.
        again = sweep(spec, None, workers=2)
        a = again.runs.drop(columns=VARYING).sort_values("run_id").reset_index(drop=True)
        b = result.runs.drop(columns=VARYING).sort_values("run_id").reset_index(drop=True)
        pd.testing.assert_frame_equal(a, b)
    finally:
        c.close()


def test_search_on_a_scheduler_matches_the_local_cluster(cluster, tmp_path):
    r1 = evapcool("optimize", "--study", "a.db", "--trials", "6", "--workers", "2", *SEARCH,
                  cwd=tmp_path)  # fmt: skip
    assert r1.returncode == 0, r1.stderr
    r2 = evapcool("optimize", "--study", "b.db", "--trials", "6", "--scheduler",
                  cluster.address, *SEARCH, cwd=tmp_path)  # fmt: skip
    assert r2.returncode == 0, r2.stderr
    a, b = _trials(tmp_path / "a.db"), _trials(tmp_path / "b.db")
    assert len(a) == 6 and all(t[1] == "COMPLETE" for t in a)
    assert a == b
    out = tmp_path / "a-results"
    for name in ("best.json", "pareto.csv", "trials.csv", "summary.json", "optimize.png"):
        assert (out / name).is_file(), name
    best = json.loads((out / "best.json").read_text())
    trials = pd.read_csv(out / "trials.csv")
    assert best["strategy"] in set(trials["strategy"])
    assert trials["score_mean"].max() == pytest.approx(best["search"]["search"]["mean"], abs=1e-3)


def test_several_processes_work_on_one_study(cluster, tmp_path):
    r = evapcool("optimize", "--study", "s.db", "--trials", "2", "--scheduler", cluster.address,
                 *SEARCH, cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    cmd = [sys.executable, "-m", "evapcool", "optimize", "--resume", "s.db", "--trials", "3",
           "--scheduler", cluster.address, "--validate", "0"]  # fmt: skip
    procs = [subprocess.Popen(cmd, cwd=tmp_path, stderr=subprocess.PIPE, text=True)
             for _ in range(2)]  # fmt: skip
    for p in procs:
        assert p.wait(timeout=600) == 0, p.stderr.read()
        p.stderr.close()
    trials = _trials(tmp_path / "s.db")
    assert [t[1] for t in trials] == ["COMPLETE"] * 8
    assert [t[0] for t in trials] == list(range(8))


def test_ctrl_c_keeps_finished_trials_and_resume_plays_the_unfinished_first(tmp_path):
    args = ["--budget", "1800", "--seeds", "6", "--batch", "2", "--chunk", "3", "--sampler-seed",
            "2", "--validate", "0", "--family", "feedback", "--workers", "2"]  # fmt: skip
    proc = subprocess.Popen(
        [sys.executable, "-m", "evapcool", "optimize", "--study", "s.db", "--trials", "400", *args],
        cwd=tmp_path,
        stderr=subprocess.PIPE,
        text=True,
    )
    for line in proc.stderr:
        if "trials so far" in line:
            break
    db = tmp_path / "s.db"
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline:  # at least one trial told, then interrupt
        time.sleep(1.0)
        if sum(t[1] == "COMPLETE" for t in _trials(db)) >= 1:
            break
    os.kill(proc.pid, signal.SIGINT)
    rest = proc.stderr.read()
    assert proc.wait(timeout=120) == 130, rest
    assert "--resume" in rest and "Traceback" not in rest
    before = _trials(db)
    complete = [t for t in before if t[1] == "COMPLETE"]
    failed = [t for t in before if t[1] == "FAIL"]
    waiting = [t for t in before if t[1] == "WAITING"]
    # Stopped mid-batch, the unfinished trials are failed and queued again (stopped between
    # batches, there are none: test_an_interrupted_batch_is_queued_again covers that case).
    assert complete and len(failed) == len(waiting)
    assert {t[2] for t in failed} == {t[2] for t in waiting}  # queued again, same parameters
    more = str(max(len(waiting), 1))
    r = evapcool("optimize", "--resume", "s.db", "--trials", more, "--validate", "0",
                 "--workers", "2", cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    after = _trials(db)
    assert {t[2] for t in after if t[1] == "COMPLETE"} >= {t[2] for t in waiting}
    assert not [t for t in after if t[1] in ("WAITING", "RUNNING")]
    by_number = {t[0]: t for t in after}
    assert all(by_number[t[0]] == t for t in complete)  # nothing finished was lost or changed


def test_an_interrupted_batch_is_queued_again(tmp_path, monkeypatch):
    """Ctrl-C while a batch is out: the finished trial is kept, the others queued again."""
    from evapcool.optimize import study as study_mod

    problem = study_mod.Problem(budget=300, seeds=2, batch=3, chunk=2, sampler_seed=1,
                                families=("linear",))  # fmt: skip
    study = study_mod.create_study(problem, f"sqlite:///{tmp_path / 's.db'}")

    def first_then_ctrl_c(engine, function, arguments, on_result, stop=None):
        on_result(0, function(*arguments[0]))  # one trial's only chunk, played here
        raise KeyboardInterrupt

    monkeypatch.setattr(study_mod, "run_tasks", first_then_ctrl_c)
    with pytest.raises(KeyboardInterrupt):
        study_mod.Search(study, problem, engine=None).run(10)
    trials = _trials(tmp_path / "s.db")
    assert [t[1] for t in trials] == ["COMPLETE", "FAIL", "FAIL", "WAITING", "WAITING"]
    assert [t[2] for t in trials[1:3]] == [t[2] for t in trials[3:]]


@pytest.mark.parametrize(
    ("args", "named"),
    [
        (["--budget", "0"], "--budget"),
        (["--seeds", "1"], "--seeds"),
        (["--family", "spline"], "--family"),
        (["--objectives", "time"], "--objectives"),
        (["--sampler", "grid"], "--sampler"),
        (["--sampler", "cmaes"], "sampler cmaes"),
        (["--scheduler", "localhost"], "--scheduler"),
        (["--workers", "0"], "--workers"),
        (["--radius", "nan"], "--radius"),
        (["--escape", "up"], "--escape"),
        (["--baseline", "sideways"], "--baseline"),
        (["--resume", "missing.db"], "--resume"),
    ],
)
def test_bad_options_get_one_line_exit_2_and_nothing_written(tmp_path, args, named):
    r = evapcool("optimize", *args, cwd=tmp_path)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and named in lines[0], r.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("command", ["optimize", "sweep"])
def test_an_unreachable_scheduler_is_one_line_and_nothing_written(tmp_path, command):
    (tmp_path / "s.toml").write_text(SPEC)
    args = ["s.toml"] if command == "sweep" else []
    r = evapcool(command, *args, "--scheduler", "tcp://127.0.0.1:9", cwd=tmp_path)
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [r.stderr.strip()] and "--scheduler" in r.stderr
    assert [p.name for p in tmp_path.iterdir()] == ["s.toml"]


def test_resume_keeps_the_problem_and_a_study_is_not_overwritten(cluster, tmp_path):
    at = ["--scheduler", cluster.address]
    # Two seeds a trial: what is checked is the study's bookkeeping, not the scores.
    search = [*SEARCH[: SEARCH.index("--seeds") + 1], "2", *SEARCH[SEARCH.index("--seeds") + 2 :]]
    r = evapcool("optimize", "--study", "s.db", "--trials", "2", *at, *search,
                 cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    r = evapcool("optimize", "--study", "s.db", cwd=tmp_path)
    assert r.returncode == 2 and "--resume" in r.stderr
    r = evapcool("optimize", "--resume", "s.db", "--budget", "900", cwd=tmp_path)
    assert r.returncode == 2 and "--budget" in r.stderr and "600" in r.stderr
    r = evapcool("optimize", "--resume", "s.db", "--trials", "2", *at,
                 "--budget", "600", cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert len(_trials(tmp_path / "s.db")) == 4


@pytest.mark.parametrize("sampler", ["cmaes", "nsga2"])
def test_other_samplers_and_the_time_objective(cluster, tmp_path, sampler):
    objectives = ["--objectives", "score,time"] if sampler == "nsga2" else []
    r = evapcool("optimize", "--study", "s.db", "--trials", "4", "--scheduler",
                 cluster.address, "--sampler", sampler, "--budget", "600", "--seeds", "3",
                 "--chunk", "3", "--validate", "0", "--family", "power", *objectives,
                 cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    trials = _trials(tmp_path / "s.db")
    assert len(trials) == 4 and all(t[1] == "COMPLETE" for t in trials)
    assert all(len(t[3]) == (2 if objectives else 1) for t in trials)
    front = pd.read_csv(tmp_path / "s-results" / "pareto.csv")
    scores = front[front["front"] == "all"].sort_values("time_mean_s")["score_mean"].tolist()
    assert scores == sorted(scores) and len(set(scores)) == len(scores)


# -- the optional extra ---------------------------------------------------------------------------


@pytest.mark.parametrize("command", ["optimize", "sweep"])
def test_without_the_extra_one_line_says_what_to_install(tmp_path, command, monkeypatch, capsys):
    import importlib.util

    from evapcool.cli import main

    real = importlib.util.find_spec

    def find_spec(name, *args):
        return None if name == "distributed" else real(name, *args)

    monkeypatch.setattr(importlib.util, "find_spec", find_spec)
    spec = tmp_path / "s.toml"
    spec.write_text(SPEC)
    argv = [command] + ([str(spec)] if command == "sweep" else [])
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"evapcool {command} needs distributed: {install_hint('cluster')}"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.toml"]


def test_importing_evapcool_and_the_applet_pulls_in_no_cluster_library():
    code = (
        "import sys, evapcool, evapcool.lab, evapcool.game.autopilot, evapcool.app.applet, "
        "evapcool.optimize, evapcool.lab.sweeps, evapcool.lab.cluster, evapcool.cli\n"
        "print(sorted(m for m in ('optuna', 'dask', 'distributed', 'pandas', 'pyarrow') "
        "if m in sys.modules))"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "[]"


@pytest.mark.parametrize(("n_linear", "candidates"), [(3, 3 + 18), (20, 5)])
def test_a_study_with_few_linear_ramps_adds_a_grid_of_them_to_the_baseline(
    tmp_path, n_linear, candidates
):
    from evapcool.optimize.report import choose, linear_grid
    from evapcool.optimize.study import RESULT_ATTR, Problem, create_study

    problem = Problem(seeds=2, families=("linear", "guarded"))
    study = create_study(problem, f"sqlite:///{tmp_path / 's.db'}")

    def add(family: str, text: str, score: float) -> None:
        result = {"family": family, "strategy": text, "score_mean": score, "time_mean": 40.0,
                  "scores": [score, score], "won_frames": [1200, 1200]}  # fmt: skip
        study.add_trial(optuna.trial.create_trial(value=score, user_attrs={RESULT_ATTR: result}))

    add("guarded", "guarded:h0=420,h1=175,duration=1723", 29.0)
    for k in range(n_linear):
        add("linear", f"{400 + k}@0,140@1800", 28.0 - k / 100)
    best, base, info = choose(study, problem, None, finalists=5, validate=0)
    assert best.family == "guarded" and base.text == "400@0,140@1800"
    # Too few linear trials to stand for the best linear ramp: the grid is re-ranked too.
    assert info["baseline_candidates"] == candidates
    assert len(linear_grid(1800)) == 18
