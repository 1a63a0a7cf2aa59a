"""Lab result files written before the ledger columns (evaporated, spilled and their
energies) still load: `evapcool lab --from` and load_result, with a one-line note.

The files in tests/lab/data were written by the lab as it was at commit 4e02312^ (version
0.1.0, eleven columns): a knife at a constant height (ledger derived) and a ramp (NaN).
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from evapcool.lab import cli as lab_cli
from evapcool.lab.experiment import load_result
from evapcool.lab.io import COLUMNS, LEDGER_COLUMNS, OLD_COLUMNS

DATA = Path(__file__).with_name("data")
CONSTANT = DATA / "lab-0.1.0-constant-knife.csv"
RAMP = DATA / "lab-0.1.0-ramp.json"

# The same run (atoms=30, radius=5, seed=5, engine reference, schedule 120, knife, 300
# frames every 60) by the current lab, which records the ledger as it goes.
RECORDED = {
    "evaporated": [0, 7, 8, 9, 9, 9],
    "spilled": [0, 0, 0, 0, 0, 0],
    "evaporated_energy": [0.0, 298.7216202145679, 338.84406720171955, *[385.78271427693386] * 3],
    "excess_energy": [0.0, 18.721620214567906, 18.844067201719554, *[25.78271427693386] * 3],
    "spilled_energy": [0.0] * 6,
}


def test_the_files_are_in_the_old_format() -> None:
    assert CONSTANT.read_text().splitlines()[11] == ",".join(OLD_COLUMNS)
    assert set(OLD_COLUMNS) | set(LEDGER_COLUMNS) == set(COLUMNS)


def test_a_constant_height_file_gets_its_ledger_derived() -> None:
    result = load_result(CONSTANT)
    assert list(result.columns) == list(COLUMNS) and len(result) == 6
    assert result.escaped.tolist() == [0, 7, 8, 9, 9, 9]
    for name, values in RECORDED.items():
        assert result.columns[name] == pytest.approx(values, rel=1e-12, abs=1e-12), name
    assert result.evaporated.dtype == np.int64
    assert "derived from the escaped count" in result.metadata["note"]
    assert math.isfinite(result.theory()["alpha"].measured)  # the ledger is usable


def test_a_ramp_file_loads_with_the_ledger_unknown() -> None:
    result = load_result(RAMP)
    assert result.trap_height.tolist() == [400.0, 300.0, 200.0]
    assert all(np.isnan(result.columns[c]).all() for c in LEDGER_COLUMNS)
    assert result.metadata["note"].startswith("an older lab file without the columns")


@pytest.mark.parametrize("ext", [".csv", ".json"])
def test_an_old_file_saved_again_reads_back_the_same(tmp_path, ext) -> None:
    for source in (CONSTANT, RAMP):
        before = load_result(source)
        before.save(tmp_path / f"again{ext}")
        after = load_result(tmp_path / f"again{ext}")
        for name in COLUMNS:
            np.testing.assert_array_equal(after.columns[name], before.columns[name])
            assert after.columns[name].dtype == before.columns[name].dtype, name


@pytest.mark.parametrize("source", [CONSTANT, RAMP], ids=["csv", "json"])
def test_lab_from_an_old_file_runs_with_a_note(source, tmp_path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    shutil.copy(source, tmp_path / source.name)
    assert lab_cli.main(["--from", source.name, "--frames", "3", "--out", "again.csv"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith(f"evapcool lab: note: --from {source.name}: an older lab file")
    assert len(err) == 2 and "wrote again.csv" in err[1]
    assert "note" not in load_result(tmp_path / "again.csv").metadata  # a new run: full ledger


def test_the_old_name_of_the_atom_count_is_read_under_its_name_now() -> None:
    # Issue 26.2: one name, n_atoms; files, calls and specs of older versions say "atoms".
    from evapcool.lab import run_experiment
    from evapcool.lab.sweeps import expand

    params = load_result(CONSTANT).metadata["parameters"]
    assert params["n_atoms"] == 30 and "atoms" not in params
    with pytest.warns(DeprecationWarning, match="atoms= is now n_atoms="):
        old = run_experiment(atoms=5, frames=2, every=1, seed=1, engine="reference")
    assert old.metadata["parameters"]["n_atoms"] == 5
    with pytest.raises(ValueError, match="atoms is the old name of n_atoms"):
        run_experiment(atoms=5, n_atoms=6, frames=2, every=1, seed=1, engine="reference")
    runs = expand({"sweep": {"seeds": 1}, "parameters": {"atoms": 10}})
    assert runs[0]["n_atoms"] == 10 and "atoms" not in runs[0]
