"""`evapcool sweep` and `evapcool.lab.sweep`: specs, tables, resume, failures, bad input.

The runs are tiny (a few atoms, a few hundred frames); the cluster is a local one with two
workers. Runs against a real scheduler and a worker killed mid-sweep: test_cluster.py.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("distributed")

from clusterhelp import Cluster, evapcool  # noqa: E402

from evapcool.lab import COLUMNS, run_experiment, sweep  # noqa: E402
from evapcool.lab.sweeps import ENV_COLUMNS, SpecError, expand, run_id  # noqa: E402

SPEC = """
[sweep]
seeds = { from = 1, to = 3 }
[parameters]
n_atoms = [8, 12]
radius = 5
schedule = ["200@0,40@300", "eta=5"]
frames = 300
every = 50
engine = "fast"
"""


def write(tmp_path, text: str, name: str = "spec.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


# -- the spec ----------------------------------------------------------------------------------


def test_every_combination_times_every_seed_is_one_run():
    runs = expand(
        {
            "sweep": {"seeds": [4, 5]},
            "parameters": {
                "n_atoms": [10, 20, 30],
                "radius": {"from": 4, "to": 6, "step": 1},
                "eta": [4, 6],
                "escape": "knife",
            },
        }
    )
    assert len(runs) == 3 * 3 * 2 * 2
    assert {r["schedule"] for r in runs} == {"eta=4", "eta=6"}
    assert {r["radius"] for r in runs} == {4.0, 5.0, 6.0}
    assert {r["seed"] for r in runs} == {4, 5}
    assert all(r["escape"] == "knife" for r in runs)
    assert len({run_id(r) for r in runs}) == len(runs)


def test_ranges_by_step_count_and_log():
    def values(rng):
        return sorted(
            {
                r["curvature"]
                for r in expand({"sweep": {"seeds": 1}, "parameters": {"curvature": rng}})
            }
        )

    assert values({"from": 0.01, "to": 0.02, "step": 0.005}) == [0.01, 0.015, 0.02]
    assert values({"from": 0.01, "to": 0.03, "num": 3}) == pytest.approx([0.01, 0.02, 0.03])
    assert values({"from": 0.001, "to": 0.1, "num": 3, "log": True}) == pytest.approx(
        [0.001, 0.01, 0.1]
    )
    seeds = expand({"sweep": {"seeds": {"from": 3, "to": 7}}, "parameters": {}})
    assert [r["seed"] for r in seeds] == [3, 4, 5, 6, 7]


def test_run_id_is_the_parameters():
    a = expand({"sweep": {"seeds": 1}, "parameters": {"atoms": 10}})[0]
    b = dict(reversed(list(a.items())))
    assert run_id(a) == run_id(b)
    assert run_id(a) != run_id({**a, "seed": 2})


@pytest.mark.parametrize(
    ("spec", "named"),
    [
        ({"parameters": {"atoms": 10}}, "sweep.seeds is missing"),
        ({"sweep": {"seeds": [1, 1]}}, "sweep.seeds"),
        ({"sweep": {"seeds": [-1]}}, "sweep.seeds"),
        ({"sweep": {"seeds": 1, "when": 3}}, "sweep.when"),
        ({"sweep": {"seeds": 1}, "parameters": {"atom": 10}}, "parameters.atom"),
        ({"sweep": {"seeds": 1}, "parameters": {"n_atoms": 0}}, "parameters.n_atoms"),
        ({"sweep": {"seeds": 1}, "parameters": {"n_atoms": []}}, "parameters.n_atoms"),
        ({"sweep": {"seeds": 1}, "parameters": {"radius": -2}}, "parameters.radius"),
        ({"sweep": {"seeds": 1}, "parameters": {"schedule": "fast"}}, "parameters.schedule"),
        ({"sweep": {"seeds": 1}, "parameters": {"eta": -3}}, "parameters.eta"),
        ({"sweep": {"seeds": 1}, "parameters": {"eta": 3, "schedule": "400"}}, "parameters.eta"),
        ({"sweep": {"seeds": 1}, "parameters": {"engine": "warp"}}, "parameters.engine"),
        (
            {"sweep": {"seeds": 1}, "parameters": {"radius": {"from": 1, "to": 2.5}}},
            "parameters.radius",
        ),
        (
            {"sweep": {"seeds": 1}, "parameters": {"radius": {"from": 1, "to": 2, "by": 1}}},
            "parameters.radius",
        ),
        (
            {
                "sweep": {"seeds": 1},
                "parameters": {"radius": {"from": 0, "to": 2, "num": 3, "log": True}},
            },
            "parameters.radius",
        ),
        ({"sweep": {"seeds": 1}, "extra": {}}, "extra"),
    ],
)
def test_bad_specs_name_the_field(spec, named):
    with pytest.raises(SpecError, match=named.replace(".", r"\.")):
        expand(spec)


@pytest.mark.parametrize(
    ("text", "named"),
    [
        ("[sweep]\nseeds = [1]\n[parameters]\nn_atoms = -4\n", "parameters.n_atoms"),
        ("[sweep]\nseeds = [1\n", "not valid TOML"),
        ("[parameters]\natoms = 4\n", "sweep.seeds"),
    ],
)
def test_bad_spec_files_exit_2_with_one_line_and_write_nothing(tmp_path, text, named):
    spec = write(tmp_path, text)
    out = tmp_path / "results"
    r = evapcool("sweep", str(spec), "--out", str(out), cwd=tmp_path)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and named in lines[0] and lines[0].startswith("evapcool sweep: error")
    assert "Traceback" not in r.stderr
    assert not out.exists()


@pytest.mark.parametrize(
    ("args", "named"),
    [
        (["--workers", "0"], "--workers"),
        (["--scheduler", "nowhere"], "--scheduler"),
        (["--frobnicate"], "unrecognized"),
    ],
)
def test_bad_options_exit_2(tmp_path, args, named):
    spec = write(tmp_path, SPEC)
    r = evapcool("sweep", str(spec), *args, cwd=tmp_path)
    assert r.returncode == 2 and named in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "spec-results").exists()


def test_missing_spec_and_out_that_is_a_file(tmp_path):
    r = evapcool("sweep", "nothere.toml", cwd=tmp_path)
    assert r.returncode == 2 and "nothere.toml" in r.stderr
    spec = write(tmp_path, SPEC)
    (tmp_path / "file").write_text("x")
    r = evapcool("sweep", str(spec), "--out", "file", cwd=tmp_path)
    assert r.returncode == 2 and "out must be a folder" in r.stderr


def test_dry_run_counts_and_writes_nothing(tmp_path):
    spec = write(tmp_path, SPEC)
    r = evapcool("sweep", str(spec), "--dry-run", cwd=tmp_path)
    assert r.returncode == 0 and r.stdout.startswith("12 runs")
    assert not (tmp_path / "spec-results").exists()


# -- running -------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A `dask scheduler` and two workers: quicker than a new local cluster per command."""
    c = Cluster(tmp_path_factory.mktemp("dask"), workers=2)
    yield c
    c.close()


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    """The SPEC swept once on a local cluster of two workers, into a folder, with CSV too."""
    folder = tmp_path_factory.mktemp("sweep")
    spec = write(folder, SPEC)
    seen = []
    result = sweep(spec, folder / "out", workers=2, csv=True, on_run=seen.append)
    return result, folder, seen


def test_sweep_returns_tidy_tables_and_writes_them(swept):
    result, folder, seen = swept
    runs, records = result.runs, result.records
    assert len(runs) == 12 == len(seen) and result.ran == 12 and result.skipped == 0
    assert (runs["status"] == "ok").all() and result.failed == 0
    assert set(records.columns) == {"run_id", *COLUMNS}
    assert set(records["run_id"]) == set(runs["run_id"])
    for name in ("runs.parquet", "records.parquet", "runs.csv", "records.csv", "spec.toml"):
        assert (folder / "out" / name).is_file()
    assert not (folder / "out" / "parts").exists()
    on_disk = pd.read_parquet(folder / "out" / "runs.parquet")
    pd.testing.assert_frame_equal(on_disk, runs)
    for col in ("numpy_version", "evapcool_version", "core_compiler", "python_version", "host"):
        assert runs[col].notna().all()


def test_any_row_repeats_bit_for_bit_from_its_parameters(swept):
    result, _, _ = swept
    row = result.runs.iloc[5]
    params = {k: row[k] for k in ("n_atoms", "radius", "curvature", "gravity", "seed", "engine",
                                  "frames", "every", "escape", "schedule", "tc_law", "start",
                                  "stop_at_win")}  # fmt: skip
    params = {k: (v.item() if hasattr(v, "item") else v) for k, v in params.items()}
    again = run_experiment(**params)
    rec = result.records[result.records["run_id"] == row["run_id"]].sort_values("frame")
    for c in COLUMNS:
        assert np.array_equal(rec[c].to_numpy(), again.columns[c]), c
    assert row["n_final"] == again.n_trapped[-1]
    assert row["won_frame"] == (again.metadata["won_frame"] or -1)


def test_summary_columns_follow_the_records(swept):
    runs, records = swept[0].runs, swept[0].records
    for _, row in runs.iterrows():
        rec = records[records["run_id"] == row["run_id"]].sort_values("frame")
        assert row["n_final"] == rec["n_trapped"].iloc[-1]
        assert row["escaped"] == row["n_initial"] - row["n_final"]
        assert row["frames_done"] == rec["frame"].iloc[-1]
        assert row["escape_rate"] == pytest.approx(row["escaped"] / (row["frames_done"] / 30))


def test_a_second_sweep_skips_what_is_done_and_adds_the_rest(swept, cluster, tmp_path):
    result, folder, _ = swept
    import shutil

    out = tmp_path / "out"
    shutil.copytree(folder / "out", out)
    bigger = write(tmp_path, SPEC.replace("to = 3", "to = 4"))
    again = sweep(bigger, out, scheduler=cluster.address)
    assert again.skipped == 12 and again.ran == 4 and len(again.runs) == 16
    assert again.runs["run_id"].is_unique
    old = result.runs.set_index("run_id")
    new = again.runs.set_index("run_id").loc[old.index]
    pd.testing.assert_series_equal(new["n_final"], old["n_final"])


def test_failed_runs_are_recorded_and_the_others_go_on(cluster, tmp_path):
    spec = write(
        tmp_path,
        "[sweep]\nseeds = [1, 2]\n[parameters]\natoms = [6, 2000]\nradius = 20\nframes = 30\n"
        'engine = "fast"\n',
    )
    r = evapcool("sweep", str(spec), "--scheduler", cluster.address, cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    runs = pd.read_parquet(tmp_path / "spec-results" / "runs.parquet")
    assert len(runs) == 4
    bad = runs[runs["status"] == "failed"]
    assert set(bad["n_atoms"]) == {2000} and len(bad) == 2
    assert bad["error"].str.contains("do not fit").all()
    assert (runs.loc[runs["n_atoms"] == 6, "status"] == "ok").all()
    assert "2 failed" in r.stderr


def _interrupted_sweep(spec, out, delay: float):
    """`evapcool sweep SPEC` stopped by SIGINT `delay` seconds after its runs start: the
    runs it kept (exit status 130, as after Ctrl+C)."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "evapcool", "sweep", str(spec), "--workers", "2"],
        cwd=spec.parent,
        stderr=subprocess.PIPE,
        text=True,
    )
    for line in proc.stderr:  # wait for the cluster
        if " runs on " in line:
            break
    time.sleep(delay)
    os.kill(proc.pid, signal.SIGINT)
    rest = proc.stderr.read()
    assert proc.wait(timeout=120) == 130, rest
    table = out / "runs.parquet"
    return pd.read_parquet(table) if table.exists() else pd.DataFrame()


def test_ctrl_c_keeps_finished_runs_and_the_same_command_goes_on(cluster, tmp_path):
    spec = write(
        tmp_path,
        "[sweep]\nseeds = { from = 1, to = 120 }\n[parameters]\natoms = 150\nradius = 4\n"
        'frames = 900\nevery = 100\nengine = "fast"\nschedule = "300@0,30@900"\n',
    )
    out = tmp_path / "spec-results"
    # Ctrl+C a few seconds into the runs (about 8 a second on 2 idle cores: 120 take 15 s).
    # On a loaded machine none may have finished yet: then again, later (the same command
    # starts over, nothing kept), never more than three times.
    for delay in (3.0, 6.0, 12.0):
        first = _interrupted_sweep(spec, out, delay)
        if len(first):
            break
    assert 0 < len(first) < 120 and (first["status"] == "ok").all()
    r = evapcool("sweep", str(spec), "--scheduler", cluster.address, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert f"{120 - len(first)} runs in" in r.stderr and f"{len(first)} already done" in r.stderr
    runs = pd.read_parquet(out / "runs.parquet")
    assert (
        len(runs) == 120
        and runs["run_id"].is_unique
        and sorted(runs["seed"]) == list(range(1, 121))
    )


def test_env_columns_are_present(swept):
    assert set(ENV_COLUMNS) <= set(swept[0].runs.columns)


def test_the_example_spec_is_valid_and_doc_cluster_shows_it(tmp_path):
    from pathlib import Path

    from evapcool.lab.sweeps import EXAMPLE_SPEC, load_spec

    r = evapcool("sweep", "--example", "ex.toml", cwd=tmp_path)
    assert r.returncode == 0 and (tmp_path / "ex.toml").read_text() == EXAMPLE_SPEC
    assert len(expand(load_spec(tmp_path / "ex.toml"))) == 20
    r = evapcool("sweep", "--example", "ex.toml", cwd=tmp_path)
    assert r.returncode == 2 and "exists" in r.stderr
    doc = (Path(__file__).parents[2] / "docs" / "cluster.md").read_text()
    assert "```text\n" + EXAMPLE_SPEC + "```" in doc
