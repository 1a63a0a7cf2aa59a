"""Lab result files: CSV with '#' metadata lines, or JSON; exact float round trip, atomic writes."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np

from evapcool.fileio import atomic_write_text, check_writable, read_user_text
from evapcool.limits import LAB_FILE_MAX_BYTES

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


def _checked_arrays(columns: object) -> dict[str, np.ndarray]:
    """as_arrays of a file's columns: ValueError unless every column is there, as numbers
    of one length (ints where INT_COLUMNS says so)."""
    if not isinstance(columns, dict):
        raise ValueError("'columns' is not an object")
    missing = [c for c in COLUMNS if not isinstance(columns.get(c), list)]
    if missing:
        raise ValueError(f"column {missing[0]!r} is missing")
    for c in INT_COLUMNS:
        if not all(isinstance(v, int) and not isinstance(v, bool) for v in columns[c]):
            raise ValueError(f"column {c!r} holds something other than whole numbers")
    try:
        arrays = as_arrays(columns)
    except (TypeError, ValueError, OverflowError):
        raise ValueError("a column holds something other than numbers") from None
    if len({len(a) for a in arrays.values()}) != 1 or any(a.ndim != 1 for a in arrays.values()):
        raise ValueError("the columns differ in length")
    return arrays


def _energies(value: object) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):
        arr = np.empty((0, 0))
    if arr.ndim != 1:
        raise ValueError("'final_energies' is not a list of numbers")
    return arr


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
    """Read a file written by write_result: (metadata, columns, final energies).

    OSError if it cannot be read (a FIFO or device is refused without waiting);
    ValueError, saying what is wrong, for anything that is not such a file.
    """
    if Path(path).suffix.lower() not in FORMATS:
        raise ValueError(f"{str(path)!r} does not end in .csv or .json")
    text = read_user_text(path, LAB_FILE_MAX_BYTES)  # a UnicodeDecodeError is a ValueError
    try:
        if Path(path).suffix.lower() == ".json":
            return _parse_json(text)
        return _parse_csv(text)
    except RecursionError:
        raise ValueError("nested too deeply") from None


def _parse_json(text: str) -> tuple[dict, dict[str, np.ndarray], np.ndarray]:
    doc = _decode(json.loads(text))
    if not isinstance(doc, dict):
        raise ValueError("not a JSON object")
    metadata = doc.get("metadata")
    if not isinstance(metadata, dict):
        raise ValueError("no 'metadata' object")
    return metadata, _checked_arrays(doc.get("columns")), _energies(doc.get("final_energies", []))


def _parse_csv(text: str) -> tuple[dict, dict[str, np.ndarray], np.ndarray]:
    metadata: dict = {}
    energies = np.empty(0)
    rows: list[list[str]] = []
    header: list[str] | None = None
    for number, line in enumerate(text.splitlines(), start=1):
        if line.startswith("#"):
            key, sep, value = line[1:].strip().partition(": ")
            if not sep:
                continue
            if key == "final_energies":
                energies = _energies(_decode(json.loads(value)))
            else:
                metadata[key] = _decode(json.loads(value))
        elif header is None:
            header = line.split(",")
            if tuple(header) != COLUMNS:
                raise ValueError("not an evapcool lab CSV file (unexpected header)")
        elif line:
            row = line.split(",")
            if len(row) != len(COLUMNS):
                raise ValueError(f"line {number} has {len(row)} fields, not {len(COLUMNS)}")
            rows.append(row)
    if header is None:
        raise ValueError("not an evapcool lab CSV file (no header)")
    try:
        parsed = {
            c: [int(r[i]) if c in INT_COLUMNS else float(r[i]) for r in rows]
            for i, c in enumerate(COLUMNS)
        }
    except ValueError:
        raise ValueError("a row holds something other than numbers") from None
    return metadata, _checked_arrays(parsed), energies


__all__ = ["COLUMNS", "check_writable", "output_format", "read_result", "write_result"]
