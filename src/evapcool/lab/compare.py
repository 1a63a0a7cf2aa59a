"""A lab run beside the truncated-Boltzmann model of evaporation (docs/lab.md, "Evaporation").

For every record the model cloud is solved from what was measured there (atoms N, mean
energy per atom, cut m g H); its rates are then set against the counts between records,
over a window that starts once the gas has had `settle` collisions per atom.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from evapcool.lab.theory import Cup, TruncatedCloud

#: Collisions per atom before the window opens: the cut tail relaxes to its quasi-steady shape.
SETTLE_COLLISIONS = 10.0


@dataclass(frozen=True)
class Comparison:
    """One measured figure beside the model's prediction for the same stretch of the run."""

    quantity: str
    symbol: str
    measured: float
    predicted: float
    events: int  # how many events the measured figure rests on (its Poisson statistics)

    @property
    def ratio(self) -> float:
        return self.measured / self.predicted if self.predicted else math.nan


@dataclass(frozen=True)
class ModelTrack:
    """The model's values at each record (nan where it does not apply)."""

    frame: np.ndarray
    kt: np.ndarray
    eta: np.ndarray
    peak_packing: np.ndarray
    pair_rate: np.ndarray  # pair collisions per frame
    evaporation_per_collision: np.ndarray  # Gamma_ev / gamma_el
    kappa: np.ndarray
    efficiency: np.ndarray  # alpha


@dataclass(frozen=True)
class TheoryReport:
    """Measured beside predicted over frames first..last of a run (LabResult.theory())."""

    rows: tuple[Comparison, ...]
    first_frame: int
    last_frame: int
    track: ModelTrack
    window: np.ndarray  # bool per record: inside the window
    note: str = ""

    def __getitem__(self, symbol: str) -> Comparison:
        for row in self.rows:
            if row.symbol == symbol:
                return row
        raise KeyError(symbol)

    def __str__(self) -> str:
        t, w = self.track, self.window
        head = (
            f"frames {self.first_frame}-{self.last_frame}: eta {np.nanmin(t.eta[w]):.3g}-"
            f"{np.nanmax(t.eta[w]):.3g}, kT {np.nanmin(t.kt[w]):.4g}-{np.nanmax(t.kt[w]):.4g}, "
            f"peak packing fraction up to {np.nanmax(t.peak_packing[w]):.3f}"
        )
        columns = f"{'quantity':<46} {'measured':>10} {'model':>10} {'ratio':>7} {'events':>8}"
        lines = [head, columns]
        for r in self.rows:
            lines.append(
                f"{r.quantity + ' ' + r.symbol:<46} {r.measured:>10.4g} {r.predicted:>10.4g} "
                f"{r.ratio:>7.3f} {r.events:>8d}"
            )
        if self.note:
            lines.append(self.note)
        return "\n".join(lines)


def _track(result, cup: Cup) -> ModelTrack:
    n = result.n_trapped.astype(float)
    cut = cup.mass * cup.gravity * result.trap_height
    values = np.full((7, len(n)), np.nan)
    for i, (atoms, mean, c) in enumerate(zip(n, result.temperature, cut, strict=True)):
        if atoms < 2:
            continue
        try:
            cloud = TruncatedCloud.from_measured(cup, atoms, float(mean), float(c))
            finite = math.isfinite(cloud.eta)
            values[:, i] = (
                cloud.kt,
                cloud.eta,
                cloud.peak_packing,
                cloud.pair_collision_rate,
                cloud.evaporation_per_collision if finite else 0.0,
                cloud.kappa_excess if finite else math.nan,
                cloud.efficiency if finite else math.nan,
            )
        except ValueError:  # no truncated law fits, or outside the model's range
            continue
    return ModelTrack(result.frame.copy(), *values)


def _mid(x: np.ndarray) -> np.ndarray:
    """Trapezoid: the mean of each interval's two ends."""
    return 0.5 * (x[1:] + x[:-1])


def compare_with_theory(result, *, settle: float = SETTLE_COLLISIONS) -> TheoryReport:
    """Measured rates of a run beside the model's; ValueError if the run cannot be compared."""
    p = result.parameters
    if len(result) < 3:
        raise ValueError("theory needs a run with at least 3 records")
    cup = Cup(
        radius=float(p["radius"]),
        mass=float(result.metadata.get("mass", 1.0)),
        gravity=float(p["gravity"]),
        curvature=float(p["curvature"]),
    )
    track = _track(result, cup)
    pairs = result.pair_collisions.astype(float)
    per_atom = 2.0 * pairs / float(p["n_atoms"])  # collisions per atom so far (about)
    usable = np.isfinite(track.pair_rate)
    if result.metadata.get("won_frame") is not None:  # the game's rules stop collisions
        usable &= result.frame < result.metadata["won_frame"]
    start = int(np.argmax(per_atom >= settle)) if np.any(per_atom >= settle) else len(pairs)
    # From there on, up to the first record the model cannot describe.
    stop = start + int(np.argmin(usable[start:])) if not np.all(usable[start:]) else len(pairs)
    window = np.zeros(len(pairs), dtype=bool)
    window[start:stop] = True
    if np.count_nonzero(window) < 3:
        raise ValueError(
            f"theory needs at least 3 records after {settle:g} collisions per atom "
            "(run longer, or record more often with every=)"
        )
    idx = np.flatnonzero(window)
    lo, hi = idx[0], idx[-1]
    sl = slice(lo, hi + 1)
    rows = [_pair_row(result, track, sl)]
    note = ""
    if p.get("escape") != "knife":
        note = "the model assumes the knife (escape='knife'); over the rim evaporation is slower"
    if np.all(np.isfinite(track.eta[sl])):
        rows += _evaporation_rows(result, track, sl)
    return TheoryReport(
        tuple(rows), int(result.frame[lo]), int(result.frame[hi]), track, window, note
    )


def _pair_row(result, track: ModelTrack, sl: slice) -> Comparison:
    dt = np.diff(result.frame[sl].astype(float))
    d_pairs = np.diff(result.pair_collisions[sl])
    span = float(np.sum(dt))
    predicted = float(np.sum(_mid(track.pair_rate[sl]) * dt)) / span
    return Comparison(
        "pair collisions per frame",
        "Gamma_pair",
        float(np.sum(d_pairs)) / span,
        predicted,
        int(np.sum(d_pairs)),
    )


def _evaporation_rows(result, track: ModelTrack, sl: slice) -> list[Comparison]:
    d_pairs = np.diff(result.pair_collisions[sl]).astype(float)
    d_evap = np.diff(result.evaporated[sl]).astype(float)
    d_excess = np.diff(result.excess_energy[sl])
    evaporated = float(np.sum(d_evap))
    ratio = Comparison(
        "evaporation per collision",
        "Gamma_ev/gamma_el",
        evaporated / (2.0 * float(np.sum(d_pairs))),
        float(np.sum(_mid(track.evaporation_per_collision[sl]) * d_pairs) / np.sum(d_pairs)),
        int(evaporated),
    )
    rows = [ratio]
    if evaporated > 0:
        kt_mid = _mid(track.kt[sl])
        rows.append(
            Comparison(
                "energy above the cut per atom / kT",
                "kappa",
                float(np.sum(d_excess / kt_mid)) / evaporated,
                float(np.sum(_mid(track.kappa[sl]) * d_evap)) / evaporated,
                int(evaporated),
            )
        )
    log_n = np.log(result.n_trapped[sl].astype(float))
    log_t = np.log(track.kt[sl])
    if log_n[0] - log_n[-1] > 0.05:
        slope = float(np.polyfit(log_n, log_t, 1)[0])
        weight = np.abs(np.diff(log_n))
        alpha = float(np.sum(_mid(track.efficiency[sl]) * weight) / np.sum(weight))
        lost = int(result.n_trapped[sl][0] - result.n_trapped[sl][-1])
        rows.append(Comparison("efficiency d ln T / d ln N", "alpha", slope, alpha, lost))
    return rows
