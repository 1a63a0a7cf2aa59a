"""The lab's CSV format, shared by the lab (lab/io.py) and the game's "Save this run"
(app/runlog.py), which may not import each other: its first line and its columns."""

from __future__ import annotations

#: The first line of a lab CSV file.
CSV_MAGIC = "# evapcool lab results"
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
#: The columns written as whole numbers.
INT_COLUMNS = frozenset(
    {"frame", "n_trapped", "pair_collisions", "wall_collisions", "escaped", "evaporated"}
    | {"spilled", "won"}
)
