"""The bundled demo against the straight ramp on fresh seeds, paired (issue 25.3).

Plays three strategies on the same seeds with the fast engine: the demo as shipped (with
its guard), the demo without its guard (the search's strategy, rescue off) and the straight
ramp 400 -> 140 px. The applet has no time limit, so a game runs until the win or until
--budget frames (default 3600, two minutes); wins within the search's 60 s budget are
counted too. Prints per strategy: mean, sd, wins out of N; and the paired differences with
their 95 % intervals (demo minus ramp; demo minus the unguarded demo = the guard's cost).

    nice python scripts/demo_check.py --first 4000000 --seeds 1000
"""

from __future__ import annotations

import argparse
import statistics
import time

from evapcool.game.autopilot import Policy, Ramp, Strategy, load_strategy, parse_strategy, play
from evapcool.optimize.evaluate import Paired, Summary

STRAIGHT_RAMP = "400@0,140@1800"
SEARCH_BUDGET = 1800
LINE = (
    "{name:<16} mean {mean:6.2f}  sd {sd:5.2f}  wins {wins}/{n}  within 60 s {fast}/{n}"
    "  latest win {late:.1f} s"
)
PAIR = (
    "{name:<32} {mean:+.2f} +- {se:.2f} (95 % CI {lo:+.2f} .. {hi:+.2f});"
    " better/worse/equal {b}/{w}/{e}"
)


def unguarded(demo: Strategy) -> Strategy:
    """The demo with its guard off: the strategy the search found."""
    if isinstance(demo, Ramp):
        return demo
    return Policy(demo.family, {**demo.params, "rescue_rate": 0.0})


def summary(strategy: Strategy, seeds: range, budget: int) -> Summary:
    rows = []
    for seed in seeds:
        o = play(strategy, seed, budget)
        rows.append((seed, o.score, -1 if o.won_frame is None else o.won_frame))
    return Summary.of(rows, budget)


def describe(name: str, s: Summary) -> str:
    won = [f for f in s.won_frames if f >= 0]
    return LINE.format(
        name=name,
        mean=s.mean,
        sd=statistics.stdev(s.scores),
        wins=len(won),
        n=s.n,
        fast=sum(f <= SEARCH_BUDGET for f in won),
        late=max(won, default=0) / 30.0,
    )


def pair(name: str, a: Summary, b: Summary) -> str:
    p = Paired(a, b)
    lo, hi = p.interval()
    better, worse, equal = p.wins_losses_ties
    return PAIR.format(name=name, mean=p.mean, se=p.se, lo=lo, hi=hi, b=better, w=worse, e=equal)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--first", type=int, default=4_000_000, help="first seed (default 4000000)")
    ap.add_argument("--seeds", type=int, default=1000, help="number of seeds (default 1000)")
    ap.add_argument("--budget", type=int, default=3600, help="frames per game at most")
    args = ap.parse_args()
    seeds = range(args.first, args.first + args.seeds)
    demo = load_strategy("demo")
    start = time.perf_counter()
    runs = {
        "demo": summary(demo, seeds, args.budget),
        "demo, no guard": summary(unguarded(demo), seeds, args.budget),
        "straight ramp": summary(parse_strategy(STRAIGHT_RAMP), seeds, args.budget),
    }
    print(f"seeds {seeds.start}..{seeds.stop - 1}, budget {args.budget} frames, fast engine")
    for name, s in runs.items():
        print(describe(name, s))
    print(pair("demo - straight ramp", runs["demo"], runs["straight ramp"]))
    print(pair("demo - demo without guard", runs["demo"], runs["demo, no guard"]))
    print(f"{time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
