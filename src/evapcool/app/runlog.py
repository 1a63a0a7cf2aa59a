"""Save this run (issue 48): the game just played as a lab CSV, to take home.

Every whole frame of the game in play is noted (N, T, Tc, the trap, the atoms that left);
"Save this run" (key W, Shift+W for every frame, or the button) writes one row a second
(30 frames) or one a frame, with the settings and the replay code in the header, in the
columns of `evapcool lab` (lab/io.py): `evapcool lab`'s plot and `load_result` read it.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

from evapcool.about import __version__
from evapcool.game.replay import encode
from evapcool.game.rules import Game
from evapcool.labformat import COLUMNS, CSV_MAGIC, INT_COLUMNS
from evapcool.limits import RECORDS_MAX

RUNS_FOLDER = "runs"
PROGRAM = "evapcool"  # the file's 'program' line (data, as the lab's)
SCHEDULE = "by hand"  # the lab's schedule column: a person moved the trap
#: One row a second: the game's 30 physics frames.
FRAMES_PER_SECOND = 30


@dataclass
class _Ledger:
    """Atoms that left and the energy they took: evaporated while the trap stood still,
    spilled in a frame that lowered it (lab/experiment.py's ledger, seen from outside)."""

    evaporated: int = 0
    evaporated_energy: float = 0.0
    excess_energy: float = 0.0
    spilled: int = 0
    spilled_energy: float = 0.0


@dataclass
class RunLog:
    """The rows of the game in play, one per whole frame (frame 0 at the start)."""

    rows: list[tuple[float, ...]] = field(default_factory=list)
    ledger: _Ledger = field(default_factory=_Ledger)
    generation: int = -1
    won_frame: int | None = None
    _last: tuple[int, float, float] = (0, 0.0, math.nan)  # N, energy, height at the last row

    def attach(self, game: Game) -> None:
        game.on_frame.append(lambda height: self.frame(game, height))
        self.start(game)

    def start(self, game: Game) -> None:
        """A new game: its first row, the start."""
        self.rows.clear()
        self.ledger = _Ledger()
        self.generation = game.generation
        self.won_frame = None
        sim = game.sim
        self._last = (sim.n_trapped, sim.total_energy(), sim.trap_height)
        self._row(game)

    def frame(self, game: Game, height: float) -> None:
        """One more whole frame played, `height` held during it."""
        if game.generation != self.generation:
            self.start(game)
        if len(self.rows) > RECORDS_MAX * FRAMES_PER_SECOND:
            return  # hours of play: the rows so far are kept
        sim = game.sim
        n0, e0, h0 = self._last
        n, e = sim.n_trapped, sim.total_energy()
        if n < n0:
            led, lost, cut = self.ledger, e0 - e, sim.gravity * height
            if height < h0:  # the trap came down: the atoms over it spilled
                led.spilled += n0 - n
                led.spilled_energy += lost
            else:
                led.evaporated += n0 - n
                led.evaporated_energy += lost
                led.excess_energy += lost - (n0 - n) * cut
        self._last = (n, e, height)
        self._row(game)

    def _row(self, game: Game) -> None:
        sim = game.sim
        n = sim.n_trapped
        t = sim.temperature
        led = self.ledger
        self.rows.append(
            (
                len(self.rows),
                n,
                t,
                sim.critical_temperature if n else 0.0,
                sim.trap_height,
                sim.total_energy(),
                sim.pair_collision_count,
                sim.wall_collision_count,
                sim.n_atoms - n,
                led.evaporated,
                led.evaporated_energy,
                led.excess_energy,
                led.spilled,
                led.spilled_energy,
                n * t**-2.5 if n and t > 0.0 else 0.0,
                int(sim.won),
            )
        )
        if sim.won and self.won_frame is None:
            self.won_frame = len(self.rows) - 1

    def picked(self, every: int) -> list[tuple[float, ...]]:
        """A row every `every` frames and the last one; phase-space density over its first."""
        picked = self.rows[::every]
        if self.rows and (len(self.rows) - 1) % every:
            picked.append(self.rows[-1])
        k = COLUMNS.index("phase_space_density")
        first = picked[0][k] if picked and picked[0][k] > 0 else 0.0
        return [(*row[:k], row[k] / first if first else 0.0, *row[k + 1 :]) for row in picked]

    def csv_text(self, game: Game, code: str | None, every: int) -> str:
        """The CSV: the settings and the replay code as '#' lines, then the rows."""
        sim, config = game.sim, game.config
        parameters = {
            "n_atoms": config.n_atoms,
            "radius": config.radius,
            "seed": sim.seed,
            "escape": config.escape,
            "tc_law": "seed" if config.tc_exponent > 0.5 else "cup",
            "schedule": SCHEDULE,
            "gravity": sim.gravity,
            "curvature": sim.curvature,
            "frames": len(self.rows) - 1,
            "every": every,
            "start_height": config.start_height,
            "speed": game.speed,
        }
        metadata = {
            "program": PROGRAM,
            "version": __version__,
            "parameters": parameters,
            "mass": 1.0,
            "tc_exponent": sim.tc_exponent,
            "columns": list(COLUMNS),
            "completed": True,
            "frames_done": len(self.rows) - 1,
            "won_frame": self.won_frame,
            "replay_code": code,
            "saved": time.strftime("%Y-%m-%dT%H:%M:%S"),
        }
        lines = [CSV_MAGIC]
        lines += [f"# {key}: {json.dumps(value)}" for key, value in metadata.items()]
        lines.append(f"# final_energies: {json.dumps([float(e) for e in sim.energies()])}")
        lines.append(",".join(COLUMNS))
        for row in self.picked(every):
            lines.append(",".join(_cell(c, v) for c, v in zip(COLUMNS, row, strict=True)))
        return "\n".join(lines) + "\n"


def _cell(name: str, value: float) -> str:
    """As the lab writes it: whole numbers plain, floats as their shortest exact repr."""
    return str(int(value)) if name in INT_COLUMNS else repr(float(value))


def replay_code(game: Game, recorder_code: str | None, recorder) -> str | None:
    """The won game's kept code, else the code of the heights played so far (not won)."""
    if recorder_code is not None:
        return recorder_code
    if recorder is None or not game.sim.moves():
        return None
    return encode(recorder.finish(game))


def run_file(folder: Path, game: Game) -> Path:
    """Where a run is saved: the data folder's runs/, by date, atoms and seed."""
    stamp = time.strftime("%Y%m%d-%H%M%S")
    return folder / f"run-{stamp}-{game.config.n_atoms}-atoms-seed-{game.sim.seed}.csv"
