"""The lab: headless evaporation experiments checked against kinetic theory (docs/lab.md).

from evapcool.lab import run_experiment
res = run_experiment(n_atoms=49, schedule="400@0,60@1800", frames=1800, seed=1)
res.n_trapped, res.temperature, res.metadata
tables = sweep("spec.toml")  # many runs on Dask: tables.runs, tables.records (pandas)
"""

from evapcool.lab import theory
from evapcool.lab.experiment import LabConfig, LabResult, load_result, run_experiment
from evapcool.lab.io import COLUMNS
from evapcool.lab.schedule import Schedule, parse_schedule
from evapcool.lab.sweeps import SweepResult, sweep

__all__ = [
    "COLUMNS",
    "LabConfig",
    "LabResult",
    "Schedule",
    "SweepResult",
    "load_result",
    "parse_schedule",
    "run_experiment",
    "sweep",
    "theory",
]
