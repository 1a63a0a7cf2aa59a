"""Constant-eta evaporation over several seeds, pooled against the model (docs/lab.md's table).

    python -m evapcool.lab.campaign --eta 4 5 6 7 --seeds 24

runs, for each eta, `seeds` knife runs of a thermal cloud at eta= with the win rule off,
compares each with the truncated-Boltzmann model (LabResult.theory()) and pools them.

    python -m evapcool.lab.campaign --eta 4 7 --quench 1000

cuts 1000 equilibrium clouds per eta once and follows the evaporation per collision from
the moment of the cut (see quench()), and

    python -m evapcool.lab.campaign --equilibrium 0.5 1 1.5 2 --seeds 3

sets the pair-collision rate of uncut gases against the model (see equilibrium()).
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass

import numpy as np

from evapcool.lab.compare import SETTLE_COLLISIONS, TheoryReport
from evapcool.lab.experiment import run_experiment
from evapcool.lab.theory import Cup, TruncatedCloud, gamma_p_half, thermal_cloud
from evapcool.physics.simulation import CURVATURE, GRAVITY, Simulation

#: The runs of docs/lab.md: 300 disks of radius 0.5 px from kT = 60 (peak packing ~1 %).
RUN = dict(n_atoms=300, radius=0.5, start="thermal=60", every=20, escape="knife", win=False)
#: Frames in which about half the atoms evaporate, by eta.
FRAMES = {4.0: 600, 5.0: 800, 6.0: 1400, 7.0: 3000}
DEFAULT_FRAMES = 1500


@dataclass(frozen=True)
class Pooled:
    """One quantity over all runs: pooled measured and model values, spread of the runs."""

    symbol: str
    measured: float
    predicted: float
    spread: float  # standard error of the per-run ratio measured / model
    events: int

    @property
    def ratio(self) -> float:
        return self.measured / self.predicted


def run_eta(eta: float, seeds: range | list[int], *, frames: int | None = None, **overrides):
    """TheoryReports of one knife run per seed at constant eta (RUN's gas unless overridden)."""
    params = {**RUN, **overrides}
    frames = frames or FRAMES.get(float(eta), DEFAULT_FRAMES)
    reports = []
    for seed in seeds:
        result = run_experiment(schedule=f"eta={eta:g}", frames=frames, seed=seed, **params)
        reports.append(result.theory(settle=SETTLE_COLLISIONS))
    return reports


def pool(reports: list[TheoryReport]) -> dict[str, Pooled]:
    """Counts added over runs; each model value weighted by the events it predicts."""
    out = {}
    pairs = np.array([r["Gamma_pair"].events for r in reports], dtype=float)
    for symbol in ("Gamma_pair", "Gamma_ev/gamma_el", "kappa", "alpha"):
        rows = [r[symbol] for r in reports if symbol in {x.symbol for x in r.rows}]
        if not rows:
            continue
        m = np.array([r.measured for r in rows])
        p = np.array([r.predicted for r in rows])
        events = np.array([r.events for r in rows], dtype=float)
        if symbol == "Gamma_pair":  # rate = pairs / span: add pairs and spans
            span = events / m
            measured, predicted = events.sum() / span.sum(), (p * span).sum() / span.sum()
        elif symbol == "Gamma_ev/gamma_el":  # evaporated / (2 pairs): add both
            measured = events.sum() / (2.0 * pairs.sum())
            predicted = (p * pairs).sum() / pairs.sum()
        else:  # kappa per evaporated atom, alpha per atom lost
            measured, predicted = (
                (m * events).sum() / events.sum(),
                (p * events).sum() / events.sum(),
            )
        ratios = m / p
        spread = float(ratios.std(ddof=1) / math.sqrt(len(rows))) if len(rows) > 1 else math.nan
        out[symbol] = Pooled(symbol, float(measured), float(predicted), spread, int(events.sum()))
    return out


def table(results: dict[float, dict[str, Pooled]]) -> str:
    """Markdown table: one row per eta and quantity."""
    lines = [
        "| eta | quantity | measured | model | measured / model | events |",
        "|---|---|---|---|---|---|",
    ]
    for eta, pooled in results.items():
        for q in pooled.values():
            lines.append(
                f"| {eta:g} | {q.symbol} | {q.measured:.4g} | {q.predicted:.4g} | "
                f"{q.ratio:.3f} +- {q.spread:.3f} | {q.events} |"
            )
    return "\n".join(lines)


#: Collision times after the cut at which the quench counts are read.
QUENCH_TIMES = (0.1, 0.2, 0.4, 0.7, 1.0, 1.5)


def _thermal_gas(
    n: int, radius: float, kt: float, seed: int, engine: str, **rules: object
) -> Simulation:
    """n unit-mass atoms drawn from the equilibrium cloud at kT (lab.theory) in the classic
    cup, the trap wide open (H = inf); rules (escape, win) as Simulation takes them."""
    rng = np.random.default_rng(seed)
    pos, vel = thermal_cloud(n, radius, kt, gravity=GRAVITY, curvature=CURVATURE, rng=rng)
    return Simulation(
        n,
        radius,
        1.0,
        curvature=CURVATURE,
        gravity=GRAVITY,
        trap_height=math.inf,
        seed=seed,
        engine=engine,
        positions=pos,
        velocities=vel,
        **rules,
    )


def quench(
    eta: float, runs: int, *, times=QUENCH_TIMES, n=1000, radius=0.3, kt=60.0, engine="fast"
) -> list[tuple[float, float, int, float]]:
    """Cut equilibrium clouds at a fixed eta kT and count, between the given times after the
    cut (in collision times 1/gamma_el), the atoms that collisions push over it and the pair
    collisions. At the cut the gas below it is exactly the truncated Boltzmann law; it then
    departs from it. Rows (from, to, evaporated, measured / model Gamma_ev/gamma_el)."""
    cup = Cup(radius=radius, mass=1.0, gravity=GRAVITY, curvature=CURVATURE)
    model = TruncatedCloud(cup, n * float(gamma_p_half(2.5, eta)), kt, eta)
    tau = 1.0 / model.elastic_collision_rate
    edges = np.concatenate(([0.0], times)) * tau
    counts = np.zeros((len(times), 2))
    for seed in range(runs):
        sim = _thermal_gas(n, radius, kt, seed, engine, escape="knife", win=False)
        sim.trap_height = eta * kt / GRAVITY
        for i, dt in enumerate(np.diff(edges)):
            atoms, pairs = sim.n_trapped, sim.pair_collision_count
            sim.advance(float(dt))
            counts[i] += (atoms - sim.n_trapped, sim.pair_collision_count - pairs)
    per_collision = model.evaporation_per_collision
    return [
        (float(a), float(b), int(ev), ev / (2.0 * pairs) / per_collision)
        for a, b, (ev, pairs) in zip(edges[:-1] / tau, edges[1:] / tau, counts, strict=True)
    ]


def equilibrium(
    radius: float, seeds, *, n=300, kt=30.0, settle=600.0, frames=3000.0, engine="fast"
) -> tuple[float, float, float]:
    """Pair collisions per frame of an uncut equilibrium gas over the model's, with the
    local-density profile and with the barometric one; and the peak packing fraction."""
    cup = Cup(radius=radius, mass=1.0, gravity=GRAVITY, curvature=CURVATURE)
    ratios = []
    for seed in seeds:
        sim = _thermal_gas(n, radius, kt, seed, engine)
        sim.advance(settle)
        pairs, means = sim.pair_collision_count, []
        for _ in range(int(frames / 10)):
            sim.advance(10.0)
            means.append(sim.temperature)
        rate = (sim.pair_collision_count - pairs) / frames
        mean = float(np.mean(means))
        dense = TruncatedCloud.from_measured(cup, n, mean, math.inf)
        ideal = TruncatedCloud.from_measured(cup, n, mean, math.inf, dense=False)
        ratios.append(
            (rate / dense.pair_collision_rate, rate / ideal.pair_collision_rate, dense.peak_packing)
        )
    return tuple(float(x) for x in np.mean(ratios, axis=0))


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m evapcool.lab.campaign", description=__doc__)
    p.add_argument("--eta", type=float, nargs="+", default=[4.0, 5.0, 6.0, 7.0])
    p.add_argument("--seeds", type=int, default=8, help="runs per eta (seeds 0 .. n-1)")
    p.add_argument("--engine", default="fast", choices=("auto", "reference", "fast"))
    p.add_argument("--quench", type=int, metavar="RUNS", help="instead: the quench, RUNS clouds")
    p.add_argument(
        "--equilibrium",
        type=float,
        nargs="+",
        metavar="R",
        help="instead: uncut gases of disks of these radii against the model",
    )
    args = p.parse_args(sys.argv[1:] if argv is None else argv)
    if args.seeds < 2 or any(not (math.isfinite(e) and e > 0) for e in args.eta):
        p.error("--seeds must be >= 2 and every --eta > 0")
    if args.equilibrium:
        print("| R | peak packing | measured / model | measured / barometric model |")
        print("|---|---|---|---|")
        for radius in args.equilibrium:
            dense, ideal, phi = equilibrium(radius, range(args.seeds), engine=args.engine)
            print(f"| {radius:g} | {phi:.3f} | {dense:.3f} | {ideal:.3f} |")
        return 0
    if args.quench is not None:
        if args.quench < 1:
            p.error("--quench must be >= 1")
        print("| eta | collision times after the cut | evaporated | measured / model |")
        print("|---|---|---|---|")
        for eta in args.eta:
            for a, b, events, ratio in quench(eta, args.quench, engine=args.engine):
                error = ratio / math.sqrt(events) if events else math.nan
                print(f"| {eta:g} | {a:.1f} - {b:.1f} | {events} | {ratio:.3f} +- {error:.3f} |")
        return 0
    results = {}
    for eta in args.eta:
        results[eta] = pool(run_eta(eta, range(args.seeds), engine=args.engine))
        print(f"eta = {eta:g} done", file=sys.stderr, flush=True)
    print(table(results))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
