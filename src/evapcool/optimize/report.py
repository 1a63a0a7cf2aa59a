"""After the search: pick the best strategy honestly and say how good it is.

1. The top `finalists` trials (and the top linear ramps, the baseline) are played again on
   re-rank seeds the search never saw; the best of each on those seeds is chosen. This undoes
   most of the luck that lifted a trial to the top of a noisy search.
2. The two chosen ones are played on held-out seeds seen by nothing before (validation): the
   report gives their means and spreads, their no-win counts and the paired difference.

Files written (atomically) into the output folder: best.json (the strategy file the lab and
the applet read; best.txt with the bare schedule for a ramp), trials.csv, pareto.csv,
summary.json and optimize.png.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from evapcool.fileio import atomic_write_bytes, atomic_write_text
from evapcool.game.autopilot import GameSetup, parse_strategy, play, save_strategy
from evapcool.lab.cluster import Engine, StopRequest, TaskError, run_tasks
from evapcool.optimize.evaluate import Paired, Summary, chunks, play_seeds
from evapcool.optimize.families import params_of
from evapcool.optimize.study import Problem, completed_trials, result_of

if TYPE_CHECKING:
    from matplotlib.figure import Figure

RERANK_START = 2_000_000
HOLDOUT_START = 1_000_000
DEFAULT_FINALISTS = 5
DEFAULT_VALIDATE = 200
#: A study with fewer linear-ramp trials also re-ranks a grid of linear ramps as baseline.
MIN_LINEAR_TRIALS = 20


def linear_grid(budget: int) -> list[str]:
    """Linear ramps over the whole budget: the baseline when a study searched no linear ramps."""
    return [f"{h0}@0,{h1}@{budget}" for h0 in (400, 450) for h1 in range(80, 241, 20)]


def evaluate(
    engine: Engine,
    texts: Sequence[str],
    seeds: Sequence[int],
    problem: Problem,
    stop: StopRequest | None = None,
) -> list[Summary]:
    """Each strategy on every seed (as Dask tasks); Summaries in the order of texts.

    Ctrl-C or SIGTERM (through stop, or caught here if None) stops at a safe point with
    KeyboardInterrupt; nothing stored is touched.
    """
    seed_chunks = chunks(list(seeds), problem.chunk)
    args = [(t, c, problem.budget, problem.setup) for t in texts for c in seed_chunks]
    rows: list[list] = [[] for _ in texts]
    errors: list[str] = []

    def got(i: int, value: object) -> None:
        if isinstance(value, TaskError):
            errors.append(value.message)
        else:
            rows[i // len(seed_chunks)].extend(value[0])

    if stop is None:
        with StopRequest() as own:
            run_tasks(engine, play_seeds, args, got, stop=own)
    else:
        run_tasks(engine, play_seeds, args, got, stop=stop)
    if errors:
        raise RuntimeError(f"validation games failed: {errors[0]}")
    return [Summary.of(r, problem.budget) for r in rows]


def pareto(points: Sequence[tuple[float, float, object]]) -> list[tuple[float, float, object]]:
    """Points (score, time, tag) not beaten in both (higher score, shorter time); by time."""
    front = []
    for s, t, tag in sorted(points, key=lambda p: (p[1], -p[0])):
        if not front or s > front[-1][0]:
            front.append((s, t, tag))
    return front


@dataclass
class Choice:
    """A strategy chosen for validation: where it came from and its scores on each seed set."""

    family: str
    text: str
    trial: int | None
    search: Summary | None
    rerank: Summary | None = None
    holdout: Summary | None = None


def _top(trials: list, k: int) -> list:
    ranked = sorted(trials, key=lambda t: (-result_of(t)["score_mean"], result_of(t)["time_mean"]))
    seen: set[str] = set()
    out = []
    for t in ranked:
        text = result_of(t)["strategy"]
        if text not in seen:
            seen.add(text)
            out.append(t)
        if len(out) == k:
            break
    return out


def _summary_of_trial(t, budget: int, seeds: list[int]) -> Summary:
    a = result_of(t)
    rows = list(zip(seeds, a["scores"], a["won_frames"], strict=True))
    return Summary.of(rows, budget)


def _choices(trials: list, problem: Problem) -> list[Choice]:
    out = []
    for t in trials:
        family, _ = params_of(t.params)
        out.append(
            Choice(
                family=result_of(t).get("family", family or problem.families[0]),
                text=result_of(t)["strategy"],
                trial=t.number,
                search=_summary_of_trial(t, problem.budget, problem.search_seeds),
            )
        )
    return out


def choose(
    study,
    problem: Problem,
    engine: Engine,
    finalists: int,
    validate: int,
    baseline: str | None = None,
    log=print,
) -> tuple[Choice, Choice, dict]:
    """The best strategy and the best linear ramp, re-ranked and validated (validate > 0).

    baseline: a strategy text to compare with instead of the study's best linear ramps.
    """
    trials = completed_trials(study)
    if not trials:
        raise ValueError("the study has no finished trials yet")
    top = _choices(_top(trials, finalists), problem)
    linear = [t for t in trials if result_of(t).get("family") == "linear"]
    if baseline is not None:
        base = [Choice("baseline", baseline, None, None)]
    else:
        base = _choices(_top(linear, finalists), problem)
        if len(linear) < MIN_LINEAR_TRIALS:  # too few to stand for the best linear ramp
            base += [Choice("linear", text, None, None) for text in linear_grid(problem.budget)]
    info: dict = {"finalists": len(top), "baseline_candidates": len(base)}
    if validate <= 0:
        return top[0], base[0], info
    with StopRequest() as stop:  # Ctrl-C or SIGTERM anywhere in here: KeyboardInterrupt
        best, baseline = _validate(top, base, problem, engine, validate, stop, log)
    info["rerank_seeds"] = [RERANK_START, RERANK_START + validate - 1]
    info["holdout_seeds"] = [HOLDOUT_START, HOLDOUT_START + validate - 1]
    return best, baseline, info


def _validate(
    top: list[Choice],
    base: list[Choice],
    problem: Problem,
    engine: Engine,
    validate: int,
    stop: StopRequest,
    log,
) -> tuple[Choice, Choice]:
    """Re-rank the finalists and the ramps on new seeds, then validate the best two."""
    rerank_seeds = list(range(RERANK_START, RERANK_START + validate))
    log(f"re-ranking {len(top)} finalists and {len(base)} linear ramps on {validate} new seeds")
    texts = list(dict.fromkeys(c.text for c in top + base))  # each strategy once
    scored = dict(zip(texts, evaluate(engine, texts, rerank_seeds, problem, stop), strict=True))
    for c in top + base:
        c.rerank = scored[c.text]
    best = max(top, key=lambda c: (c.rerank.mean, -c.rerank.time_mean))
    baseline = max(base, key=lambda c: (c.rerank.mean, -c.rerank.time_mean))
    holdout = list(range(HOLDOUT_START, HOLDOUT_START + validate))
    log(f"validating on {validate} held-out seeds {holdout[0]}..{holdout[-1]}")
    texts = list(dict.fromkeys((best.text, baseline.text)))
    scored = dict(zip(texts, evaluate(engine, texts, holdout, problem, stop), strict=True))
    best.holdout, baseline.holdout = scored[best.text], scored[baseline.text]
    return best, baseline


def _stats(s: Summary | None) -> dict | None:
    if s is None:
        return None
    return {
        "seeds": s.n,
        "mean": round(s.mean, 4),
        "se": round(s.se, 4),
        "no_wins": s.no_wins,
        "time_mean_s": round(s.time_mean, 3),
        "time_se_s": round(s.time_se, 3),
    }


def _choice_dict(c: Choice) -> dict:
    return {
        "family": c.family,
        "strategy": c.text,
        "trial": c.trial,
        "search": _stats(c.search),
        "rerank": _stats(c.rerank),
        "holdout": _stats(c.holdout),
    }


def comparison(best: Choice, baseline: Choice) -> dict | None:
    if best.holdout is None or baseline.holdout is None:
        return None
    p = Paired(best.holdout, baseline.holdout)
    lo, hi = p.interval()
    w, losses, ties = p.wins_losses_ties
    return {
        "seeds": best.holdout.n,
        "difference_mean": round(p.mean, 4),
        "difference_se": round(p.se, 4),
        "ci95": [round(lo, 4), round(hi, 4)],
        "better_worse_equal": [w, losses, ties],
        "no_wins": [best.holdout.no_wins, baseline.holdout.no_wins],
        "target_met": bool(p.mean >= 1.0 and best.holdout.no_wins <= baseline.holdout.no_wins),
    }


def trial_rows(study) -> list[dict]:
    rows = []
    for t in completed_trials(study):
        a = result_of(t)
        rows.append(
            {
                "trial": t.number,
                "family": a.get("family"),
                "score_mean": a["score_mean"],
                "score_se": a["score_se"],
                "time_mean_s": a["time_mean"],
                "time_se_s": a["time_se"],
                "no_wins": a["no_wins"],
                "seeds": a["n"],
                "strategy": a["strategy"],
            }
        )
    return rows


def fronts(rows: list[dict]) -> dict[str, list[dict]]:
    """The Pareto front of score against time to win: all trials, and linear ramps alone."""
    out = {}
    for name, subset in (("all", rows), ("linear", [r for r in rows if r["family"] == "linear"])):
        front = pareto([(r["score_mean"], r["time_mean_s"], r) for r in subset])
        out[name] = [r for _, _, r in front]
    return out


def _csv(rows: list[dict], columns: list[str]) -> str:
    import pandas as pd

    return pd.DataFrame(rows, columns=columns).to_csv(index=False)


def write_outputs(
    out: Path,
    study,
    problem: Problem,
    best: Choice,
    baseline: Choice,
    info: dict,
    run_info: dict,
) -> dict:
    """Every file of the report; returns the summary dict (also summary.json)."""
    out.mkdir(parents=True, exist_ok=True)
    rows = trial_rows(study)
    cols = ["trial", "family", "score_mean", "score_se", "time_mean_s", "time_se_s", "no_wins",
            "seeds", "strategy"]  # fmt: skip
    atomic_write_text(out / "trials.csv", _csv(rows, cols))
    fr = fronts(rows)
    front_rows = [{"front": k, **r} for k, v in fr.items() for r in v]
    atomic_write_text(out / "pareto.csv", _csv(front_rows, ["front", *cols]))
    summary = {
        "problem": problem.to_attr(),
        "trials": len(rows),
        "trials_by_family": {f: sum(r["family"] == f for r in rows) for f in problem.families},
        **run_info,
        **info,
        "best": _choice_dict(best),
        "baseline": _choice_dict(baseline),
        "comparison": comparison(best, baseline),
    }
    atomic_write_text(out / "summary.json", json.dumps(summary, indent=2) + "\n")
    strategy = parse_strategy(best.text)
    save_strategy(
        out / "best.json",
        strategy,
        family=best.family,
        budget=problem.budget,
        game={k: v for k, v in problem.setup.items() if k != "engine"},
        search=_choice_dict(best),
        baseline=_choice_dict(baseline),
        comparison=summary["comparison"],
    )
    if not strategy.closed_loop:
        atomic_write_text(out / "best.txt", strategy.text + "\n")
    figure(out / "optimize.png", rows, fr, best, baseline, problem)
    return summary


def figure(
    path: Path, rows: list[dict], fr: dict, best: Choice, baseline: Choice, problem: Problem
) -> None:
    """Score against trial, the Pareto fronts, the best strategy's H(t) over the linear ramp's,
    and the held-out paired differences."""
    import io

    buf = io.BytesIO()
    draw_figure(rows, fr, best, baseline, problem).savefig(buf, format="png", dpi=110)
    atomic_write_bytes(path, buf.getvalue())


def draw_figure(
    rows: list[dict], fr: dict, best: Choice, baseline: Choice, problem: Problem
) -> Figure:
    """The report's four panels, each legend beside its plot (never over a point)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    fig = Figure(figsize=(13, 8.5), layout="constrained")
    ax = fig.subplots(2, 2)
    _panel_trials(ax[0, 0], rows, problem)
    _panel_front(ax[0, 1], rows, fr)
    _panel_heights(ax[1, 0], best, baseline, problem)
    _panel_holdout(ax[1, 1], best, baseline)
    for a in ax.flat:
        if a.get_legend_handles_labels()[0]:
            a.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    return fig


def _panel_trials(ax, rows: list[dict], problem: Problem) -> None:
    for fam in problem.families:
        pts = [(r["trial"], r["score_mean"]) for r in rows if r["family"] == fam]
        if pts:
            # Over the "best so far" line, which would hide the trials that set it.
            ax.plot(*zip(*pts, strict=True), ".", ms=4, label=fam, alpha=0.8, zorder=3)
    best = -math.inf
    run = []
    for r in sorted(rows, key=lambda r: r["trial"]):
        best = max(best, r["score_mean"])
        run.append((r["trial"], best))
    if run:
        ax.plot(*zip(*run, strict=True), "k-", lw=1.2, label="best so far")
    ax.set_xlabel("trial")
    ax.set_ylabel(f"mean score on {problem.seeds} search seeds")
    ax.set_title("Search")


def _panel_front(ax, rows: list[dict], fr: dict) -> None:
    ax.plot([r["time_mean_s"] for r in rows], [r["score_mean"] for r in rows], ".",
            color="0.75", ms=3, label="trials")  # fmt: skip
    for name, style in (("all", "C3o-"), ("linear", "C0s--")):
        pts = fr.get(name) or []
        if pts:
            label = "front, every family" if name == "all" else "front, linear ramps"
            ax.plot([r["time_mean_s"] for r in pts], [r["score_mean"] for r in pts], style,
                    ms=4, lw=1.2, label=label)  # fmt: skip
    ax.set_xlabel("mean time to win, s (no win counts the whole budget)")
    ax.set_ylabel("mean score")
    ax.set_title("Score against time to win (Pareto front)")


def _heights(text: str, seed: int, problem: Problem) -> tuple[list[float], list[float]]:
    trace: list = []
    play(parse_strategy(text), seed, problem.budget, GameSetup(**problem.setup), trace=trace)
    return [f / 30.0 for f, *_ in trace], [h for _, h, *_ in trace]


def _panel_heights(ax, best: Choice, baseline: Choice, problem: Problem) -> None:
    closed = parse_strategy(best.text).closed_loop
    seeds = range(HOLDOUT_START, HOLDOUT_START + (6 if closed else 1))
    for k, seed in enumerate(seeds):
        t, h = _heights(best.text, seed, problem)
        ax.plot(t, h, "C3-", lw=0.8 if closed else 1.8, alpha=0.8,
                label=f"best ({best.family})" if k == 0 else None)  # fmt: skip
    t, h = _heights(baseline.text, HOLDOUT_START, problem)
    ax.plot(t, h, "C0--", lw=1.5, label="best linear ramp")
    ax.set_xlabel("time, s (until the win)")
    ax.set_ylabel("trap height H, px")
    ax.set_title("Strategies" + (" (one line per held-out seed)" if closed else ""))


def _panel_holdout(ax, best: Choice, baseline: Choice) -> None:
    if best.holdout is None or baseline.holdout is None:
        ax.text(0.5, 0.5, "no validation run", ha="center", va="center", transform=ax.transAxes)
        ax.set_axis_off()
        return
    p = Paired(best.holdout, baseline.holdout)
    d = p.differences
    lo, hi = min(d), max(d)
    ax.hist(d, bins=range(lo, hi + 2), align="left", color="0.6")
    ax.axvline(p.mean, color="C3", label=f"mean {p.mean:+.2f} ± {p.se:.2f}")
    ax.axvline(0.0, color="k", lw=0.8)
    ax.set_xlabel("score difference, best - linear (same seed)")
    ax.set_ylabel("held-out seeds")
    ax.yaxis.get_major_locator().set_params(integer=True)  # counts of seeds: no 2.5
    ax.set_title(f"Held-out validation, {p.a.n} paired seeds")
