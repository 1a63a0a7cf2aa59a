"""Lab result files: CSV with '#' metadata lines, or JSON; exact float round trip, atomic writes."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np

from evapcool.fileio import atomic_write_text

#: Output columns, one row per record (docs/lab.md explains each).
COLUMNS = (
    "frame",
    "n_trapped",
    "temperature",
    "critical_temperature",
    "trap_height",
    "total_energy",
    "pair_collisions",
    "wall_collisions",
    "escaped",
    "evaporated",
    "evaporated_energy",
    "excess_energy",
    "spilled",
    "spilled_energy",
    "phase_space_density",
    "won",
)
INT_COLUMNS = frozenset(
    {
        "frame",
        "n_trapped",
        "pair_collisions",
        "wall_collisions",
        "escaped",
        "evaporated",
        "spilled",
        "won",
    }
)
FORMATS = (".csv", ".json")
CSV_MAGIC = "# evapcool lab results"


def output_format(path: str | os.PathLike[str]) -> str:
    """'.csv' or '.json' from the file name; ValueError otherwise."""
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(f"out must be a file name ending in .csv or .json (got {str(path)!r})")
    return suffix


def check_writable(path: str | os.PathLike[str], name: str) -> None:
    """ValueError unless a file can be created at path (checked before a long run)."""
    p = Path(path)
    parent = p.parent if str(p.parent) else Path(".")
    if p.is_dir():
        raise ValueError(f"{name} must be a writable file path, not a directory (got {str(p)!r})")
    if not parent.is_dir():
        raise ValueError(f"{name} must be in an existing directory (got {str(p)!r})")
    if not os.access(parent, os.W_OK | os.X_OK) or (p.exists() and not os.access(p, os.W_OK)):
        raise ValueError(f"{name} must be a writable file path (got {str(p)!r})")


def _encode(value: object) -> object:
    """JSON-safe copy: non-finite floats become the strings 'inf', '-inf', 'nan'."""
    if isinstance(value, float) and not math.isfinite(value):
        return repr(value)
    if isinstance(value, dict):
        return {k: _encode(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_encode(v) for v in value]
    return value


_NONFINITE = {"inf": math.inf, "-inf": -math.inf, "nan": math.nan}


def _decode(value: object) -> object:
    if isinstance(value, str) and value in _NONFINITE:
        return _NONFINITE[value]
    if isinstance(value, dict):
        return {k: _decode(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_decode(v) for v in value]
    return value


def _cell(name: str, value: object) -> str:
    # repr of a float is the shortest string that reads back to the same bits.
    return str(int(value)) if name in INT_COLUMNS else repr(float(value))


def as_arrays(columns: dict[str, list]) -> dict[str, np.ndarray]:
    """The columns as int64 / float64 arrays, in COLUMNS order."""
    return {
        name: np.asarray(columns[name], dtype=np.int64 if name in INT_COLUMNS else np.float64)
        for name in COLUMNS
    }


def to_csv_text(metadata: dict, columns: dict[str, np.ndarray], energies: np.ndarray) -> str:
    """CSV: '# key: <json>' metadata lines, then a header row, then one row per record."""
    lines = [CSV_MAGIC]
    for key, value in metadata.items():
        lines.append(f"# {key}: {json.dumps(_encode(value), allow_nan=False)}")
    lines.append(
        "# final_energies: " + json.dumps(_encode([float(e) for e in energies]), allow_nan=False)
    )
    lines.append(",".join(COLUMNS))
    n = len(columns[COLUMNS[0]])
    for i in range(n):
        lines.append(",".join(_cell(c, columns[c][i]) for c in COLUMNS))
    return "\n".join(lines) + "\n"


def to_json_text(metadata: dict, columns: dict[str, np.ndarray], energies: np.ndarray) -> str:
    """JSON: {'metadata', 'columns': {name: [...]}, 'final_energies'}."""
    cols = {c: [int(v) if c in INT_COLUMNS else float(v) for v in columns[c]] for c in COLUMNS}
    doc = {
        "metadata": metadata,
        "columns": cols,
        "final_energies": [float(e) for e in energies],
    }
    return json.dumps(_encode(doc), allow_nan=False, indent=1) + "\n"


def write_result(
    path: str | os.PathLike[str],
    metadata: dict,
    columns: dict[str, np.ndarray],
    energies: np.ndarray,
) -> None:
    """Write atomically as CSV or JSON by extension."""
    fmt = output_format(path)
    text = (to_csv_text if fmt == ".csv" else to_json_text)(metadata, columns, energies)
    atomic_write_text(path, text)


def read_result(path: str | os.PathLike[str]) -> tuple[dict, dict[str, np.ndarray], np.ndarray]:
    """Read a file written by write_result: (metadata, columns, final energies)."""
    fmt = output_format(path)
    text = Path(path).read_text(encoding="utf-8")
    if fmt == ".json":
        doc = _decode(json.loads(text))
        energies = np.asarray(doc.get("final_energies", []), dtype=np.float64)
        return doc["metadata"], as_arrays(doc["columns"]), energies
    metadata: dict = {}
    energies = np.empty(0)
    rows: list[list[str]] = []
    header: list[str] | None = None
    for line in text.splitlines():
        if line.startswith("#"):
            key, sep, value = line[1:].strip().partition(": ")
            if not sep:
                continue
            if key == "final_energies":
                energies = np.asarray(_decode(json.loads(value)), dtype=np.float64)
            else:
                metadata[key] = _decode(json.loads(value))
        elif header is None:
            header = line.split(",")
        elif line:
            rows.append(line.split(","))
    if header is None or tuple(header) != COLUMNS:
        raise ValueError(f"{path}: not an evapcool lab CSV file (unexpected header)")
    columns = {name: [r[i] for r in rows] for i, name in enumerate(header)}
    parsed = {
        c: [int(v) for v in columns[c]] if c in INT_COLUMNS else [float(v) for v in columns[c]]
        for c in COLUMNS
    }
    return metadata, as_arrays(parsed), energies
