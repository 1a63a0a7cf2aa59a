"""Lab result files: CSV with '#' metadata lines, or JSON; exact float round trip, atomic writes."""

from __future__ import annotations

import json
import math
import os
import warnings
from collections.abc import Iterator, Mapping
from pathlib import Path

import numpy as np

from evapcool.fileio import atomic_write_text, check_writable, read_user_text
from evapcool.labformat import COLUMNS, CSV_MAGIC, INT_COLUMNS
from evapcool.limits import LAB_FILE_MAX_BYTES, N_ATOMS, RECORDS_MAX, ParameterError

#: Parameters renamed since: old name -> name now (files, specs and calls with the old one
#: are still read, issue 26.2: one name for the atom count, n_atoms, as Simulation's).
RENAMED_PARAMETERS = {"atoms": "n_atoms"}


def current_names(params: Mapping[str, object], warn: bool = False) -> dict[str, object]:
    """params with every old name (RENAMED_PARAMETERS) under its name now; an old name
    beside its new one is a ValueError naming both."""
    out = dict(params)
    for old, new in RENAMED_PARAMETERS.items():
        if old in out:
            if new in out:
                raise ParameterError(old, f"is the old name of {new}: give one of them")
            if warn:
                warnings.warn(f"{old}= is now {new}=", DeprecationWarning, stacklevel=3)
            out[new] = out.pop(old)
    return out


#: The ledger columns (evaporated and spilled atoms and their energies) that files written
#: before version 0.1.0's ledger lack; such files load with these derived or NaN.
LEDGER_COLUMNS = ("evaporated", "evaporated_energy", "excess_energy", "spilled", "spilled_energy")
OLD_COLUMNS = tuple(c for c in COLUMNS if c not in LEDGER_COLUMNS)
FORMATS = (".csv", ".json")
#: Commas a lab file may hold: every record's columns, every atom's final energy, and room
#: for the metadata. A file within its size cap could otherwise be 64 million zeros,
#: several GB once parsed (issue 18: memory of any accepted input under 1 GB).
VALUES_MAX = RECORDS_MAX * (len(COLUMNS) + 1) + int(N_ATOMS.high) + 100_000


def output_format(path: str | os.PathLike[str]) -> str:
    """'.csv' or '.json' from the file name; ValueError otherwise."""
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise ParameterError(
            "out", f"must be a file name ending in .csv or .json (got {str(path)!r})"
        )
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
    return str(int(value)) if name in INT_COLUMNS and value == value else repr(float(value))


def _json_value(name: str, value: object) -> int | float:
    return int(value) if name in INT_COLUMNS and value == value else float(value)


def as_arrays(columns: dict[str, list]) -> dict[str, np.ndarray]:
    """The columns as int64 / float64 arrays, in COLUMNS order (an integer column that an
    older file could not fill is float64 NaN)."""
    out = {}
    for name in COLUMNS:
        values = columns[name]
        unknown = name in INT_COLUMNS and any(v != v for v in values)
        int_col = name in INT_COLUMNS and not unknown
        out[name] = np.asarray(values, dtype=np.int64 if int_col else np.float64)
    return out


def _whole(v: object) -> bool:
    return (isinstance(v, int) and not isinstance(v, bool)) or (isinstance(v, float) and v != v)


def _checked_arrays(columns: object) -> dict[str, np.ndarray]:
    """as_arrays of a file's columns: ValueError unless every column is there, as numbers
    of one length (ints where INT_COLUMNS says so, or NaN for an unknown ledger)."""
    if not isinstance(columns, dict):
        raise ValueError("'columns' is not an object")
    missing = [c for c in COLUMNS if not isinstance(columns.get(c), list)]
    if missing:
        raise ValueError(f"column {missing[0]!r} is missing")
    for c in INT_COLUMNS:
        if not all(_whole(v) for v in columns[c]):
            raise ValueError(f"column {c!r} holds something other than whole numbers")
    try:
        arrays = as_arrays(columns)
    except (TypeError, ValueError, OverflowError):
        raise ValueError("a column holds something other than numbers") from None
    if len({len(a) for a in arrays.values()}) != 1 or any(a.ndim != 1 for a in arrays.values()):
        raise ValueError("the columns differ in length")
    return arrays


def _constant_height(metadata: dict) -> float | None:
    """The trap height of a run whose schedule never moved it, else None."""
    from evapcool.lab.schedule import parse_schedule

    try:
        schedule = parse_schedule(metadata["parameters"]["schedule"])
    except (KeyError, TypeError, ValueError):
        return None
    heights = {h for _, h in schedule.points}
    return heights.pop() if schedule.kind == "ramp" and len(heights) == 1 else None


def _with_ledger(metadata: dict, columns: dict) -> None:
    """Fill the ledger columns of a file written before them (in place), and say so.

    Only the escaped total was recorded. Under a constant trap height atoms spill only at
    the start, so the ledger follows from it exactly (its energies until the win, after
    which damped bounces lose energy too); otherwise it is unknown: NaN.
    """
    n = len(columns["frame"])
    nan = [math.nan] * n
    filled = dict.fromkeys(LEDGER_COLUMNS, nan)
    height = _constant_height(metadata)
    derived = height is not None and n > 0 and all(_whole(v) for v in columns["escaped"])
    if derived:
        escaped = [int(v) for v in columns["escaped"]]
        won = np.cumsum(np.asarray(columns["won"], dtype=float)) > 0
        energy = np.asarray(columns["total_energy"], dtype=float)
        try:
            cut = float(metadata["mass"]) * float(metadata["parameters"]["gravity"]) * height
        except (KeyError, TypeError, ValueError):
            cut = math.nan
        evaporated = [e - escaped[0] for e in escaped]
        flown = np.where(won, math.nan, energy[0] - energy)
        filled.update(
            evaporated=evaporated,
            spilled=[escaped[0]] * n,
            evaporated_energy=flown.tolist(),
            excess_energy=(flown - np.asarray(evaporated) * cut).tolist(),
            spilled_energy=[0.0] * n if escaped[0] == 0 else nan,
        )
    columns.update(filled)
    how = (
        "derived from the escaped count (the trap height was constant)"
        if derived
        else "filled with NaN (only the escaped total was recorded)"
    )
    metadata["note"] = f"an older lab file without the columns {', '.join(LEDGER_COLUMNS)}: {how}"
    metadata["columns"] = list(COLUMNS)


def _columns_of(metadata: dict, columns: object) -> dict[str, np.ndarray]:
    """Checked arrays of a file's columns; an older file's missing ledger is filled."""
    if (
        isinstance(columns, dict)
        and all(isinstance(columns.get(c), list) for c in OLD_COLUMNS)
        and not any(c in columns for c in LEDGER_COLUMNS)
    ):
        columns = dict(columns)
        _with_ledger(metadata, columns)
    return _checked_arrays(columns)


def _energies(value: object) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):
        arr = np.empty((0, 0))
    if arr.ndim != 1:
        raise ValueError("'final_energies' is not a list of numbers")
    if len(arr) > N_ATOMS.high:
        raise ValueError(f"'final_energies' holds more than {int(N_ATOMS.high)} atoms")
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
    cols = {c: [_json_value(c, v) for v in columns[c]] for c in COLUMNS}
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
    if text.count(",") > VALUES_MAX:
        raise ValueError(f"more values than a lab result holds (over {VALUES_MAX} commas)")
    try:
        parse = _parse_json if Path(path).suffix.lower() == ".json" else _parse_csv
        metadata, columns, energies = parse(text)
    except RecursionError:
        raise ValueError("nested too deeply") from None
    if isinstance(metadata.get("parameters"), dict):  # older files name some differently
        metadata["parameters"] = current_names(metadata["parameters"])
    return metadata, columns, energies


def _parse_json(text: str) -> tuple[dict, dict[str, np.ndarray], np.ndarray]:
    doc = _decode(json.loads(text))
    if not isinstance(doc, dict):
        raise ValueError("not a JSON object")
    metadata = doc.get("metadata")
    if not isinstance(metadata, dict):
        raise ValueError("no 'metadata' object")
    columns = _columns_of(metadata, doc.get("columns"))
    if len(columns["frame"]) > RECORDS_MAX:
        raise ValueError(f"more than {RECORDS_MAX} records")
    return metadata, columns, _energies(doc.get("final_energies", []))


def _parse_csv(text: str) -> tuple[dict, dict[str, np.ndarray], np.ndarray]:
    metadata: dict = {}
    energies = np.empty(0)
    rows: list[list[str]] = []
    header: tuple[str, ...] | None = None
    for number, line in enumerate(_lines(text), start=1):
        if line.startswith("#"):
            key, sep, value = line[1:].strip().partition(": ")
            if not sep:
                continue
            if key == "final_energies":
                energies = _energies(_decode(json.loads(value)))
            else:
                metadata[key] = _decode(json.loads(value))
        elif header is None:
            header = tuple(line.split(","))
            if header not in (COLUMNS, OLD_COLUMNS):
                raise ValueError("not an evapcool lab CSV file (unexpected header)")
        elif line:
            row = line.split(",")
            if len(row) != len(header):
                raise ValueError(f"line {number} has {len(row)} fields, not {len(header)}")
            if len(rows) == RECORDS_MAX:
                raise ValueError(f"more than {RECORDS_MAX} records")
            rows.append(row)
    if header is None:
        raise ValueError("not an evapcool lab CSV file (no header)")
    try:
        parsed = {c: [_number(c, r[i]) for r in rows] for i, c in enumerate(header)}
    except ValueError:
        raise ValueError("a row holds something other than numbers") from None
    return metadata, _columns_of(metadata, parsed), energies


def _lines(text: str) -> Iterator[str]:
    """The lines of text one at a time (a list of them all could be GBs of short lines)."""
    start = 0
    while start < len(text):
        end = text.find("\n", start)
        end = len(text) if end < 0 else end
        yield text[start:end].rstrip("\r")
        start = end + 1


def _number(name: str, text: str) -> int | float:
    return int(text) if name in INT_COLUMNS and text != "nan" else float(text)


__all__ = ["COLUMNS", "check_writable", "output_format", "read_result", "write_result"]
