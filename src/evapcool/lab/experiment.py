"""run_experiment: one evaporation run with a trap-height schedule, recorded as time series."""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from evapcool import limits
from evapcool.extras import check
from evapcool.fileio import check_writable
from evapcool.lab import notebook
from evapcool.lab.io import (
    COLUMNS,
    as_arrays,
    current_names,
    output_format,
    read_result,
    write_result,
)
from evapcool.lab.progress import Progress
from evapcool.lab.schedule import Schedule, parse_schedule
from evapcool.lab.theory import eta_from_cut, thermal_cloud
from evapcool.physics.config import SimulationConfig, check_engine_size
from evapcool.physics.room import CLASSIC_ROOM
from evapcool.physics.simulation import (
    ATOM_RADIUS,
    CURVATURE,
    ENGINES,
    GRAVITY,
    N_ATOMS,
    TC_LAWS,
    Simulation,
)
from evapcool.physics.world import ESCAPE_RULES

ESCAPES = ESCAPE_RULES
MASS = 1.0
START_HELP = (
    f"'cup' (the game's loading) or 'thermal=KT' (a thermal cloud at kT {limits.START_KT.span()})"
)


def _choice(name: str, value: object, options: tuple[str, ...] | dict) -> str:
    if not isinstance(value, str) or value not in options:
        raise limits.bad_value(name, "one of " + ", ".join(options), value)
    return value


def parse_start(text: str) -> float | None:
    """None for 'cup', kT for 'thermal=KT'; ValueError otherwise."""
    if text == "cup":
        return None
    if isinstance(text, str) and text.startswith("thermal="):
        try:
            kt = float(text[len("thermal=") :])
        except ValueError:
            kt = math.nan
        if limits.START_KT.contains(kt):
            return kt
    raise limits.bad_value("start", START_HELP, text)


@dataclass(frozen=True)
class LabConfig:
    """Every parameter of a lab run; together with the version it fixes the result bit for bit."""

    n_atoms: int = N_ATOMS
    radius: float = ATOM_RADIUS
    curvature: float = CURVATURE
    gravity: float = GRAVITY
    seed: int | None = None
    engine: str = "auto"
    frames: int = 1800
    every: int = 30
    escape: str = "rim"
    schedule: str = "400"
    tc_law: str = "seed"
    start: str = "cup"
    stop_at_win: bool = True
    win: bool = True

    def validated(self) -> LabConfig:
        """A copy with checked, normalised values and a concrete seed; ValueError on bad input."""
        return self.checked()[0]

    def checked(self) -> tuple[LabConfig, Schedule]:
        """validated() and the schedule it parsed (a strategy file is read once)."""
        seed = self.seed
        if seed is None:
            # Draw a seed now so that the file records it and the run can be repeated.
            seed = int(np.random.SeedSequence().entropy % (2**32))
        n_atoms = limits.N_ATOMS.check_int("n_atoms", self.n_atoms)
        _choice("engine", self.engine, ENGINES)
        if self.engine == "reference" and n_atoms > limits.REFERENCE_MAX_ATOMS:
            raise limits.ParameterError(
                "n_atoms",
                f"must be at most {limits.REFERENCE_MAX_ATOMS} with engine reference "
                f"(got {n_atoms}); use engine fast or auto",
            )
        _choice("escape", self.escape, ESCAPES)
        _choice("tc_law", self.tc_law, TC_LAWS)
        schedule = parse_schedule(self.schedule)
        if len(schedule.points) > limits.SCHEDULE_POINTS_MAX:
            raise limits.ParameterError(
                "schedule",
                f"must have at most {limits.SCHEDULE_POINTS_MAX} points "
                f"(got {limits.shown(self.schedule)})",
            )
        parse_start(self.start)
        if not isinstance(self.stop_at_win, bool):
            raise limits.bad_value("stop_at_win", "True or False", self.stop_at_win)
        if not isinstance(self.win, bool):
            raise limits.bad_value("win", "True or False", self.win)
        frames = limits.FRAMES.check("frames", self.frames)
        every = limits.EVERY.check("every", self.every)
        if frames // every + 2 > limits.RECORDS_MAX:
            raise limits.ParameterError(
                "every",
                f"must be at least {frames // (limits.RECORDS_MAX - 2) + 1} for "
                f"{frames} frames: a run keeps at most {limits.RECORDS_MAX} records (got {every})",
            )
        config = LabConfig(
            n_atoms=n_atoms,
            radius=limits.RADIUS.check("radius", self.radius),
            curvature=limits.CURVATURE.check("curvature", self.curvature),
            gravity=limits.GRAVITY.check("gravity", self.gravity),
            seed=limits.SEED.check("seed", seed),
            engine=self.engine,
            frames=frames,
            every=every,
            escape=self.escape,
            schedule=self.schedule.strip(),
            tc_law=self.tc_law,
            start=self.start,
            stop_at_win=self.stop_at_win,
            win=self.win,
        )
        return config, schedule


class LabResult:
    """Time series of a run (NumPy arrays by column name), its metadata and final energies."""

    def __init__(self, metadata: dict, columns: dict[str, np.ndarray], energies: np.ndarray):
        self.metadata = metadata
        self.columns = columns
        self.final_energies = np.asarray(energies, dtype=float)

    def __getattr__(self, name: str) -> np.ndarray:
        columns = self.__dict__.get("columns", {})
        if name in columns:
            return columns[name]
        raise AttributeError(name)

    def __len__(self) -> int:
        return len(self.columns["frame"])

    # -- notebooks (lab/notebook.py) ---------------------------------------------
    def __repr__(self) -> str:
        return notebook.summary(self)

    def _repr_html_(self) -> str:
        return notebook.to_html(self)

    def to_pandas(self):
        """The records as a pandas DataFrame, metadata in `.attrs` (needs pandas)."""
        return notebook.to_pandas(self)

    @property
    def parameters(self) -> dict:
        """The run's parameters: run_experiment(**result.parameters) repeats it."""
        return dict(self.metadata.get("parameters", {}))

    @property
    def completed(self) -> bool:
        return bool(self.metadata.get("completed", False))

    @property
    def eta(self) -> np.ndarray:
        """Truncation parameter m g H / kT at each record, kT from the law cut at m g H.

        The law E^(3/2) exp(-E/kT) cut at eta kT whose mean energy is the temperature
        column (docs/lab.md); inf without a cut, nan where no such law has that mean.
        """
        cut = MASS * self.metadata["parameters"]["gravity"] * self.trap_height
        return np.array(
            [eta_from_cut(float(t), float(c)) for t, c in zip(self.temperature, cut, strict=True)]
        )

    def theory(self, *, settle: float | None = None):
        """The run's measured rates beside the truncated-Boltzmann model (docs/lab.md).

        Returns a TheoryReport: print it for the table; report["alpha"] etc. for a row.
        The window opens after `settle` collisions per atom (default 10).
        """
        from evapcool.lab.compare import SETTLE_COLLISIONS, compare_with_theory

        return compare_with_theory(self, settle=SETTLE_COLLISIONS if settle is None else settle)

    def save(self, path: str | os.PathLike[str]) -> None:
        """Write as CSV or JSON (by extension), atomically."""
        write_result(path, self.metadata, self.columns, self.final_energies)

    def plot(self, path: str | os.PathLike[str] | None = None, *, theory=None):
        """The four-panel figure (docs/lab.md); saved to path if given; returns the Figure.

        theory=True (or a report from self.theory()) draws the model over the measurement
        and adds two panels: the collision rate and the evaporated atoms against time.
        """
        check("matplotlib", "LabResult.plot")
        from evapcool.lab.plot import plot_result

        notebook.show_figures_inline()
        if theory is True:
            theory = self.theory()
        return plot_result(self, path, theory=theory or None)


def load_result(path: str | os.PathLike[str]) -> LabResult:
    """Read a CSV or JSON file written by the lab."""
    return LabResult(*read_result(path))


def _new_columns() -> dict[str, list]:
    return {c: [] for c in COLUMNS}


@dataclass
class _Ledger:
    """Atoms that left the trap and the energy they took, by how they left (docs/lab.md).

    Evaporated: during flight (a collision pushed it over the knife, or it flew over the
    rim), with its energy at that moment; spilled: when the schedule lowered the cut.
    Collisions and bounces conserve energy, so what the trapped atoms lose is exactly what
    the leavers took (before the win, whose damped bounces lose energy too).
    """

    evaporated: int = 0
    evaporated_energy: float = 0.0
    excess_energy: float = 0.0  # sum of E - m g H over the evaporated atoms
    spilled: int = 0
    spilled_energy: float = 0.0

    def evaporate(self, count: int, energy: float, cut: float) -> None:
        if count:
            self.evaporated += count
            self.evaporated_energy += energy
            self.excess_energy += energy - count * cut

    def spill(self, count: int, energy: float) -> None:
        if count:
            self.spilled += count
            self.spilled_energy += energy


def _make_simulation(cfg: LabConfig, schedule: Schedule) -> Simulation:
    kt = parse_start(cfg.start)
    pos = vel = None
    if kt is not None:
        rng = np.random.default_rng(cfg.seed)
        try:
            pos, vel = thermal_cloud(
                cfg.n_atoms,
                cfg.radius,
                kt,
                mass=MASS,
                gravity=cfg.gravity,
                curvature=cfg.curvature,
                rng=rng,
            )
        except ValueError:
            raise limits.ParameterError(
                "start",
                f"a thermal cloud at kT {kt:g} is too dense for {cfg.n_atoms} atoms of "
                f"radius {cfg.radius:g} (a larger kT, fewer or smaller atoms fit)",
                sep=": ",
            ) from None
    h0 = schedule.fixed_height(0.0) if schedule.kind == "ramp" else math.inf
    check_engine_size(cfg.engine, cfg.n_atoms)  # the one check LabConfig leaves: auto, no core
    # cfg was checked once (LabConfig.checked); the physics trusts it. A thermal start is new
    # data: its positions are checked (in the cup, apart) as they join the config.
    config = SimulationConfig(
        n_atoms=cfg.n_atoms,
        radii=np.full(cfg.n_atoms, cfg.radius),
        masses=np.full(cfg.n_atoms, MASS),
        curvature=cfg.curvature,
        gravity=cfg.gravity,
        trap_height=h0,
        tc_exponent=TC_LAWS[cfg.tc_law],
        room=CLASSIC_ROOM,
        seed=cfg.seed,
        engine=cfg.engine,
        escape=cfg.escape,
        record_events=False,
        win=cfg.win,
    )
    if pos is not None and vel is not None:
        config = config.with_start(pos, vel)
    return Simulation.from_config(config)


def _check_run_options(out, plot, progress, checkpoint_seconds, on_record) -> None:
    """ValueError naming the first bad one of run_experiment's own keywords."""
    for name, path in (("out", out), ("plot", plot)):
        if path is not None and not isinstance(path, (str, os.PathLike)):
            raise limits.bad_value(name, "a file path or None", path)
    if out is not None:
        output_format(out)
        check_writable(out, "out")
    if plot is not None:
        check("matplotlib", "plot")
        if Path(plot).suffix.lower() != ".png":
            raise limits.ParameterError(
                "plot", f"must be a file name ending in .png (got {str(plot)!r})"
            )
        check_writable(plot, "plot")
    if progress is not None and not isinstance(progress, bool):
        raise ValueError(f"progress must be True, False or None (got {limits.shown(progress)})")
    limits.CHECKPOINT_SECONDS.check("checkpoint_seconds", checkpoint_seconds)
    if on_record is not None and not callable(on_record):
        raise ValueError(f"on_record must be a function or None (got {limits.shown(on_record)})")


def run_experiment(
    *,
    out: str | os.PathLike[str] | None = None,
    plot: str | os.PathLike[str] | None = None,
    progress: bool | None = False,
    checkpoint_seconds: float = 10.0,
    on_record: Callable[[LabResult], None] | None = None,
    **params: object,
) -> LabResult:
    """Run one evaporation experiment; ValueError on bad input, before any simulation work.

    params are the LabConfig fields (n_atoms, radius, curvature, gravity, seed, engine,
    frames, every, escape, schedule, tc_law, start, stop_at_win, win). The trap height
    follows the schedule frame by frame; a record (a row) is taken every `every`
    frames and at the end, which is the frame where T < Tc unless stop_at_win=False.
    win=False turns the game's win rule off: the gas stays a gas below Tc (no stop).
    Ctrl-C stops the run early and returns (and writes) the rows so far, marked
    completed=False. progress=None draws a bar only if stderr is a terminal.
    """
    params = current_names(params, warn=True)
    unknown = sorted(set(params) - set(LabConfig.__dataclass_fields__))
    if unknown:
        raise ValueError(
            f"unknown parameter {unknown[0]!r}; allowed: "
            + ", ".join(LabConfig.__dataclass_fields__)
        )
    cfg, schedule = LabConfig(**params).checked()  # type: ignore[arg-type]
    _check_run_options(out, plot, progress, checkpoint_seconds, on_record)
    sim = _make_simulation(cfg, schedule)

    from evapcool import __version__

    metadata: dict = {
        "program": "evapcool lab",
        "version": __version__,
        "parameters": asdict(cfg),
        "mass": MASS,
        "tc_exponent": sim.tc_exponent,
        "columns": list(COLUMNS),
        "completed": False,
        "frames_done": 0,
        "won_frame": None,
        **notebook.run_info(sim),
    }
    cols = _new_columns()
    n0 = sim.n_atoms
    ledger = _Ledger()
    psd0: list[float] = []  # N T^-5/2 at the first record, for the normalisation

    def snapshot() -> LabResult:
        arrays = {c: np.asarray(v) for c, v in cols.items()}
        return LabResult(dict(metadata), as_arrays(arrays), sim.energies())

    def record(frame: int) -> None:
        n = sim.n_trapped
        t = sim.temperature
        psd = n * t**-2.5 if n and t > 0.0 else 0.0
        if not psd0:
            psd0.append(psd)
        cols["frame"].append(frame)
        cols["n_trapped"].append(n)
        cols["temperature"].append(t)
        cols["critical_temperature"].append(sim.critical_temperature if n else 0.0)
        cols["trap_height"].append(sim.trap_height)
        cols["total_energy"].append(sim.total_energy())
        cols["pair_collisions"].append(sim.pair_collision_count)
        cols["wall_collisions"].append(sim.wall_collision_count)
        cols["escaped"].append(n0 - n)
        for name, value in asdict(ledger).items():
            cols[name].append(value)
        cols["phase_space_density"].append(psd / psd0[0] if psd0[0] > 0.0 else 0.0)
        cols["won"].append(int(sim.won))

    bar = Progress(cfg.frames, enabled=progress)
    last_write = time.monotonic()
    try:
        if schedule.kind != "ramp":
            schedule.apply(sim, 0.0)
        energy = sim.total_energy()
        ledger.spill(n0 - sim.n_trapped, n0 * sim.initial_temperature - energy)
        record(0)
        for frame in range(1, cfg.frames + 1):
            n, cut = sim.n_trapped, MASS * cfg.gravity * sim.trap_height
            sim.advance(1.0)
            flown = sim.total_energy()
            ledger.evaporate(n - sim.n_trapped, energy - flown, cut)
            n = sim.n_trapped
            schedule.apply(sim, float(frame))
            energy = sim.total_energy()
            ledger.spill(n - sim.n_trapped, flown - energy)
            won_now = sim.won and metadata["won_frame"] is None
            if won_now:
                metadata["won_frame"] = frame
            metadata["frames_done"] = frame
            # After T < Tc the game's rules take over (no pair collisions, damped
            # bounces), which is no longer an evaporation experiment: stop there.
            stop = won_now and cfg.stop_at_win
            if frame % cfg.every == 0 or frame == cfg.frames or stop:
                record(frame)
                if on_record is not None:
                    on_record(snapshot())
                if out is not None and time.monotonic() - last_write > checkpoint_seconds:
                    snapshot().save(out)
                    last_write = time.monotonic()
            bar.update(frame, f"N={sim.n_trapped}")
            if stop:
                metadata["stopped_at_win"] = True
                break
        metadata["completed"] = True
    except KeyboardInterrupt:
        metadata["interrupted_at_frame"] = metadata["frames_done"]
    finally:
        bar.close()
    result = snapshot()
    if out is not None:
        result.save(out)
    if plot is not None:
        result.plot(plot)
    return result
