"""What a lab result shows in a notebook: a one-line repr, an HTML table with the figure
inline, a pandas DataFrame, and the figure displayed by IPython in a fresh kernel.

Kept apart from the experiment's physics; `LabResult` calls these. pandas, matplotlib and
IPython are optional: nothing here imports them until asked.
"""

from __future__ import annotations

import base64
import html
import io
import sys
from typing import TYPE_CHECKING, Any, Protocol

from evapcool.about import versions
from evapcool.extras import check
from evapcool.physics.core import compiled

if TYPE_CHECKING:
    import numpy as np

    from evapcool.physics.simulation import Simulation


class LabResult(Protocol):
    """What is shown of a lab result (experiment.LabResult; typed here so that this module
    need not import the experiment, which calls it)."""

    metadata: dict[str, Any]
    columns: dict[str, np.ndarray]

    @property
    def parameters(self) -> dict[str, Any]: ...

    @property
    def completed(self) -> bool: ...

    def __len__(self) -> int: ...

    def __getattr__(self, name: str) -> np.ndarray: ...

    def plot(self) -> Any: ...


def run_info(sim: Simulation) -> dict[str, Any]:
    """Metadata a run records besides its parameters: the engine that ran it and the
    versions of Python, evapcool and the numeric libraries; "core": the compiler that built
    the engine core (None where it was not built)."""
    module = compiled()
    found = {**versions(), "core": None if module is None else str(module.COMPILER)}
    return {"engine": sim.engine, "versions": found}


def _engine(result: LabResult) -> str:
    meta = result.metadata
    return str(meta.get("engine") or meta.get("parameters", {}).get("engine", "?"))


def summary(result: LabResult) -> str:
    """One line: atoms, T, Tc, frame and engine at the first and last records."""
    if len(result) == 0:
        return "LabResult(no records)"
    n, t, tc = result.n_trapped, result.temperature, result.critical_temperature
    frames = result.parameters.get("frames", "?")
    state = "" if result.completed else ", interrupted"
    if result.metadata.get("won_frame") is not None:
        state += f", T < Tc from frame {result.metadata['won_frame']}"
    return (
        f"LabResult(atoms {n[0]} -> {n[-1]}, T {t[0]:.4g} -> {t[-1]:.4g}, "
        f"Tc {tc[-1]:.4g}, frame {result.frame[-1]} of {frames}, "
        f"engine {_engine(result)}{state})"
    )


def _rows(result: LabResult) -> list[tuple[str, str]]:
    meta, p = result.metadata, result.parameters
    n, t, tc = result.n_trapped, result.temperature, result.critical_temperature
    rows = [
        ("atoms (start, end)", f"{n[0]} → {n[-1]}"),
        ("T (start, end)", f"{t[0]:.4g} → {t[-1]:.4g}"),
        ("Tc (start, end)", f"{tc[0]:.4g} → {tc[-1]:.4g}"),
        ("frames", f"{result.frame[-1]} of {p.get('frames', '?')} ({len(result)} records)"),
        ("T < Tc from frame", str(meta.get("won_frame"))),
        ("schedule", str(p.get("schedule"))),
        ("escape, Tc law", f"{p.get('escape')}, {p.get('tc_law')}"),
        ("engine, seed", f"{_engine(result)}, {p.get('seed')}"),
    ]
    versions = meta.get("versions") or {}
    if versions:
        rows.append(("versions", ", ".join(f"{k} {v}" for k, v in versions.items() if v)))
    return rows


def figure_png(fig: Any) -> bytes:
    """A matplotlib Figure as PNG bytes (what IPython shows inline)."""
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=80, bbox_inches="tight")
    return buffer.getvalue()


def to_html(result: LabResult) -> str:
    """A small table of the run and, with matplotlib installed, its figure inline."""
    cells = "".join(
        f"<tr><th style='text-align:left'>{html.escape(k)}</th>"
        f"<td style='text-align:left'>{html.escape(v)}</td></tr>"
        for k, v in (_rows(result) if len(result) else [("records", "none")])
    )
    parts = [f"<table>{cells}</table>"]
    if len(result):
        try:
            check("matplotlib", "the figure")
        except ImportError as exc:
            parts.append(f"<p>{html.escape(str(exc))}</p>")
        else:
            png = base64.b64encode(figure_png(result.plot())).decode("ascii")
            alt = "N(t), T(t) with Tc, the path T(N), the energy histogram"
            parts.append(f"<img alt='{alt}' src='data:image/png;base64,{png}'>")
    return "<div>" + "".join(parts) + "</div>"


def to_pandas(result: LabResult) -> Any:
    """The records as a pandas DataFrame (one row per record); metadata in `df.attrs`."""
    check("pandas", "LabResult.to_pandas", hint="pip install pandas")
    import pandas as pd

    df = pd.DataFrame({name: result.columns[name] for name in result.columns})
    df.attrs["metadata"] = result.metadata
    return df


def show_figures_inline() -> None:
    """In IPython, let a bare matplotlib Figure display as a PNG (the lab never imports
    pyplot, so a fresh kernel has no inline backend to do it). Elsewhere: nothing."""
    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None else None
    if shell is None:
        return
    from matplotlib.figure import Figure

    formatter = shell.display_formatter.formatters["image/png"]
    try:
        formatter.lookup_by_type(Figure)
    except KeyError:
        formatter.for_type(Figure, figure_png)
