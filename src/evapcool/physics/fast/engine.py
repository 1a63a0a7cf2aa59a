"""`FastEngine`: the Python face of the compiled engine, a drop-in for ReferenceEngine."""

from __future__ import annotations

from typing import Any

import numpy as np

from evapcool.physics.fast import calendar, driver, grid, warmup
from evapcool.physics.fast.lookahead import DEEP_MIN_ATOMS
from evapcool.physics.fast.tables import (
    HEAP_ENTRY,
    LOG_LINE,
    PLAN,
    QUEUED,
    RUN,
    STATE,
    Spares,
    Tables,
    aligned,
)
from evapcool.physics.world import TRAPPED, World

#: Lines of the event log buffer (it is emptied into the World when full).
LOG_CAPACITY = 1 << 16
#: Upkeep (driver.maintain) every this many events per atom.
UPKEEP_EVENTS_PER_ATOM = 8


def make_tables(world: World, cells: grid.Grid) -> Tables:
    """Empty tables for the World's atoms on this grid, with the fixed parameters set."""
    n = len(world.radius)
    ring = calendar.ring_size(n)
    tb = Tables(
        state=aligned(n, STATE),
        queued=aligned(n, QUEUED),
        plan=aligned(n, PLAN),
        heap=np.zeros(n, dtype=HEAP_ENTRY),
        bins=np.full(ring + 2, -1, dtype=np.int64),
        cells=np.full(cells.nx * cells.ny + n, -1, dtype=np.int32),
        run=np.zeros(1, dtype=RUN),
        tc_table=np.zeros(n + 1),
        log=np.zeros(LOG_CAPACITY if world.record_events else 1, dtype=LOG_LINE),
    )
    tb.state["radius"] = world.radius
    tb.state["atom"] = np.arange(n)
    tb.plan["atom"] = np.arange(n)
    tb.queued["mass"] = world.mass
    every = UPKEEP_EVENTS_PER_ATOM * n
    fixed = {
        "gravity": world.gravity, "curvature": world.curvature,
        "grid_x0": cells.x0, "grid_y0": cells.y0, "cell": cells.cell,
        "nx": cells.nx, "ny": cells.ny,
        "x_left": world.x_left, "x_right": world.x_right, "y_bottom": world.y_bottom,
        "knife": world.knife, "record": world.record_events,
        "maintain_every": every, "since_maintain": every,  # upkeep at the first event
        "deep": n >= DEEP_MIN_ATOMS, "n_bins": ring,
    }  # fmt: skip
    for name, value in fixed.items():
        tb.run[name] = value
    return tb


class FastEngine:
    """Event-driven hard disks in the cup: Numba, cells, one pending event per atom."""

    name = "fast"

    def __init__(self, world: World) -> None:
        # The first engine of a process compiles (or loads) what its first frame needs,
        # with progress on the terminal if that takes long.
        warmup.run((*warmup.FIRST_FRAME, *(("knife",) if world.knife else ())), None, FastEngine)
        self.w = world
        self.spares: Spares | None = None
        self.grid = grid.geometry(world, world.trap_height)
        self._tc_key: tuple[float, float, bool] | None = None
        self._start()

    def _start(self) -> None:
        """New tables on self.grid, set up from the World's state."""
        old = getattr(self, "tb", None)
        self.tb = make_tables(self.w, self.grid)
        self.rows = np.arange(len(self.w.radius), dtype=np.int64)  # World atom k is in row rows[k]
        if old is not None:  # the counts go on
            for name in ("crossings", "stale"):
                self.tb.run[name] = old.run[name]
        self._tc_key = None
        self._update_tc_table()
        driver.start(self._scalars(), self._arrays(), *self.tb)

    # -- World <-> engine -----------------------------------------------------------
    def _scalars(self) -> tuple[float, ...]:
        """The World's scalars in the order driver._pull takes them."""
        w = self.w
        return (
            w.time, w.energy_sum, w.rim_half_width, w.trap_height, bool(w.won), w.n_trapped,
            w.pair_count, w.wall_count,
        )  # fmt: skip

    def _arrays(self) -> tuple[np.ndarray, ...]:
        """The World's arrays, then rows (the row of each World atom), for driver._pull."""
        w = self.w
        return w.pos, w.vel, w.t_atom, w.status, w.counter, self.rows

    def _update_tc_table(self) -> None:
        w = self.w
        key = (w.tc0, w.tc_exponent, w.win_rule)
        if key != self._tc_key:
            # Tc(N) for every N, by the World's own expression (same float pow).
            self.tb.tc_table[:] = [w.win_threshold_of(m) for m in range(w.n_initial + 1)]
            self._tc_key = key

    def _take(self, result: tuple[Any, ...]) -> int:
        """Store what driver._push returned in the World; returns the status."""
        status, n_log, time, energy_sum, won, n_trapped, pairs, walls = result
        w = self.w
        w.time = time
        w.energy_sum = energy_sum
        w.won = won
        w.n_trapped = n_trapped
        w.pair_count = pairs
        w.wall_count = walls
        if n_log:
            w.log.extend(tuple(line) for line in self.tb.log[:n_log].tolist())
        return int(status)

    def _spares(self) -> Spares:
        n = len(self.tb.state)
        if self.spares is None or len(self.spares.state) != n:
            self.spares = Spares(
                aligned(n, STATE), aligned(n, QUEUED), aligned(n, PLAN), np.zeros(n, np.int64)
            )
        return self.spares

    # -- public -------------------------------------------------------------------
    def advance_to(self, t_end: float) -> None:
        """Process every event with time <= t_end in time order, then set the clock."""
        self._update_tc_table()
        arrays = self._arrays()
        while True:
            result = driver.run_until(float(t_end), self._scalars(), arrays, *self.tb)
            status = self._take(result)
            if status == driver.DONE:
                return
            if status == driver.UPKEEP:
                driver.maintain(self._spares(), self.rows, *self.tb)

    def set_trap_height(self, height: float) -> None:
        """New rim height; with the knife rule, atoms above m g H go at once."""
        w = self.w
        w.trap_height = height
        new = grid.regrid_for(w, self.grid, height)
        if new is not None:  # the rim rose above the grid (or left it far too big)
            self.grid = new
            self._start()
        if not w.knife:
            return
        n = len(w.radius)
        if w.record_events and len(self.tb.log) < n + driver.LOG_ROOM:
            self.tb = self.tb._replace(log=np.zeros(n + driver.LOG_ROOM, dtype=LOG_LINE))
        self._update_tc_table()
        self._take(driver.knife_now(self._scalars(), self._arrays(), *self.tb))

    # -- diagnostics --------------------------------------------------------------
    @property
    def crossing_count(self) -> int:
        """Cell-crossing events processed so far."""
        return int(self.tb.run["crossings"][0])

    @property
    def stale_count(self) -> int:
        """Pair events found stale (partner changed) and re-predicted so far."""
        return int(self.tb.run["stale"][0])

    @property
    def grid_shape(self) -> tuple[int, int, float]:
        """(columns, rows, cell edge in px) of the cell grid (the attic is its top row)."""
        return self.grid.nx, self.grid.ny, self.grid.cell

    @property
    def off_grid_count(self) -> int:
        """Trapped atoms above the grid's top now (flying in the attic)."""
        w = self.w
        trapped = np.flatnonzero(w.status == TRAPPED)
        pos, _ = w.state_at(trapped, w.time)
        return int(np.count_nonzero(pos[:, 1] > self.grid.top))

    def grid_errors(self) -> int:
        """Trapped atoms filed more than one cell away from where they are now (0 if sound)."""
        if self.w.won:
            return 0
        return int(driver.grid_errors(float(self.w.time), *self.tb))
