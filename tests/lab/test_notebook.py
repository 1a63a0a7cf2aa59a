"""Notebook users: one-line reprs, the result's HTML table with its figure, to_pandas,
the recorded versions, and a real notebook executed in a fresh kernel (issue 16)."""

from __future__ import annotations

import base64
import platform
import re

import numpy as np
import pytest

from evapcool import Simulation, __version__
from evapcool.lab import COLUMNS, load_result, run_experiment


@pytest.fixture(scope="module")
def result():
    return run_experiment(
        n_atoms=30, radius=8.0, frames=60, every=20, seed=3, engine="reference", schedule="300"
    )


def test_simulation_repr_is_one_line_with_atoms_t_tc_frame_engine():
    sim = Simulation.classic(seed=1, engine="reference")
    sim.advance(2.5)
    text = repr(sim)
    assert "\n" not in text
    expected = (
        f"Simulation(atoms {sim.n_trapped} of 49, T {sim.temperature:.4g}, "
        f"Tc {sim.critical_temperature:.4g}, frame 2.5, engine reference)"
    )
    assert text == expected


def test_result_repr_is_one_line(result):
    text = repr(result)
    assert "\n" not in text
    n, t = result.n_trapped, result.temperature
    assert text.startswith(f"LabResult(atoms {n[0]} -> {n[-1]}, T {t[0]:.4g} -> {t[-1]:.4g}")
    assert f"Tc {result.critical_temperature[-1]:.4g}" in text
    assert "frame 60 of 60" in text and "engine reference" in text


def test_metadata_records_engine_and_versions(result, tmp_path):
    meta = result.metadata
    assert meta["engine"] == "reference"
    versions = meta["versions"]
    assert versions["python"] == platform.python_version()
    assert versions["evapcool"] == __version__
    assert versions["numpy"] == np.__version__
    assert set(versions) >= {"core", "matplotlib"}
    path = tmp_path / "run.csv"
    result.save(path)  # survives the file and comes back
    assert load_result(path).metadata["versions"] == versions


def test_html_has_a_table_and_the_figure_inline(result):
    pytest.importorskip("matplotlib")
    page = result._repr_html_()
    assert "<table>" in page and "<th style='text-align:left'>atoms (start, end)</th>" in page
    png = re.search(r"src='data:image/png;base64,([A-Za-z0-9+/=]+)'", page)
    assert png is not None
    assert base64.b64decode(png.group(1)).startswith(b"\x89PNG\r\n\x1a\n")


def test_to_pandas_has_every_column_and_row(result):
    pd = pytest.importorskip("pandas")
    df = result.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == list(result.columns)
    assert len(df) == len(result)
    np.testing.assert_array_equal(df["temperature"].to_numpy(), result.temperature)
    assert df.attrs["metadata"]["engine"] == "reference"


NOTEBOOK_CELLS = [
    "from evapcool.lab import run_experiment\n"
    "r = run_experiment(n_atoms=20, radius=8, frames=20, every=10, seed=1, engine='reference')\n"
    "r",
    "r.plot()",
    "r.to_pandas().shape",
    "from evapcool import Simulation\nSimulation.classic(seed=1, engine='reference')",
]


def test_a_fresh_kernel_shows_results_inline():
    """A notebook run by a real Jupyter kernel: the figure comes back as a PNG."""
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    pytest.importorskip("matplotlib")
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(src) for src in NOTEBOOK_CELLS]
    nbclient.NotebookClient(nb, timeout=300, kernel_name="python3").execute()
    outputs = [cell.outputs for cell in nb.cells]
    first = outputs[0][0]["data"]
    assert first["text/plain"].startswith("LabResult(atoms 20 -> ")
    assert "<table>" in first["text/html"] and "data:image/png;base64," in first["text/html"]
    figure = outputs[1][0]["data"]
    assert base64.b64decode(figure["image/png"]).startswith(b"\x89PNG")
    assert outputs[2][0]["data"]["text/plain"] == f"(3, {len(COLUMNS)})"
    assert outputs[3][0]["data"]["text/plain"].startswith("Simulation(atoms 49 of 49, T ")
