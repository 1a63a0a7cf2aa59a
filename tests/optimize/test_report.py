"""The report's choice of finalists on a tiny in-memory study (no cluster: validate=0)."""

from __future__ import annotations

import pytest

from evapcool.optimize import report
from evapcool.optimize.study import RESULT_ATTR, Problem

optuna = pytest.importorskip("optuna")
optuna.logging.set_verbosity(optuna.logging.WARNING)

PROBLEM = Problem(seeds=2, budget=1800)


def _trial(family: str, text: str, scores: list[int], frames: list[int]):
    dist = optuna.distributions.FloatDistribution(0.0, 500.0)
    result = {
        "family": family,
        "strategy": text,
        "score_mean": sum(scores) / len(scores),
        "time_mean": sum(frames) / len(frames) / 30.0,
        "scores": scores,
        "won_frames": frames,
    }
    return optuna.trial.create_trial(
        params={f"{family}.h0": 400.0},
        distributions={f"{family}.h0": dist},
        value=result["score_mean"],
        user_attrs={RESULT_ATTR: result},
    )


def _study(trials) -> object:
    study = optuna.create_study(direction="maximize")
    for t in trials:
        study.add_trial(t)
    return study


def test_finalists_are_ranked_by_score_then_time_each_strategy_once() -> None:
    study = _study(
        [
            _trial("guarded", "guarded:h0=420", [31, 29], [1500, 1500]),
            _trial("linear", "400@0,140@1800", [29, 29], [1300, 1300]),
            _trial("guarded", "guarded:h0=420", [31, 29], [1500, 1500]),  # the same again
            _trial("feedback", "feedback:eta0=6", [29, 29], [1200, 1200]),  # as good, faster
        ]
    )
    best, base, info = report.choose(study, PROBLEM, engine=None, finalists=3, validate=0)
    assert (best.family, best.text) == ("guarded", "guarded:h0=420")
    assert best.search.scores == (31, 29) and best.search.seeds == (0, 1)
    assert info["finalists"] == 3  # the duplicate counted once
    assert base.text == "400@0,140@1800"
    # Fewer linear trials than MIN_LINEAR_TRIALS: the straight-ramp grid stands in beside them.
    assert info["baseline_candidates"] == 1 + len(report.linear_grid(1800))
    top = report._top(report.completed_trials(study), 3)
    assert [report.result_of(t)["strategy"] for t in top] == [
        "guarded:h0=420",
        "feedback:eta0=6",
        "400@0,140@1800",
    ]


def test_a_study_without_finished_trials_is_refused() -> None:
    with pytest.raises(ValueError, match="no finished trials"):
        report.choose(_study([]), PROBLEM, engine=None, finalists=3, validate=0)


def test_a_given_baseline_replaces_the_linear_ramps() -> None:
    study = _study([_trial("guarded", "guarded:h0=420", [31, 29], [1500, 1500])])
    _, base, info = report.choose(study, PROBLEM, None, 3, 0, baseline="400@0,140@1800")
    assert (base.family, base.text, info["baseline_candidates"]) == (
        "baseline",
        "400@0,140@1800",
        1,
    )


def test_no_legend_of_the_figure_covers_a_point() -> None:
    """Each panel's legend sits beside its plot (issue 49.9: it covered trials 6 and 7)."""
    pytest.importorskip("matplotlib")
    from evapcool.optimize.evaluate import Summary

    rows = [
        {"trial": k, "family": "linear", "score_mean": 2.0 + k, "time_mean_s": 30.0 + k}
        for k in range(8)
    ]
    hold = Summary((1, 2, 3), (30, 28, 27), (1200, 1300, 1250), 1800)
    base = Summary((1, 2, 3), (29, 28, 25), (1100, 1300, 1250), 1800)
    best = report.Choice("linear", "400@0,140@1800", 7, None, holdout=hold)
    baseline = report.Choice("linear", "425@0,162@1788", 6, None, holdout=base)
    fig = report.draw_figure(rows, report.fronts(rows), best, baseline, PROBLEM)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig.set_dpi(110)  # as the report saves it
    renderer = FigureCanvasAgg(fig).get_renderer()
    fig.draw(renderer)  # lays the panels out
    panels = [a for a in fig.axes if a.get_legend() is not None]
    assert len(panels) == 4
    legends = [a.get_legend().get_window_extent(renderer) for a in panels]
    points = 0
    for a in panels:
        box = a.get_window_extent(renderer)
        for legend in legends:
            assert not box.overlaps(legend), (a.get_title(), legend, box)
        # Every point drawn (markers, lines' vertices, the histogram's bars) outside every legend.
        for line in a.get_lines():
            for x, y in line.get_transform().transform(line.get_xydata()):
                points += 1
                assert not any(lg.contains(x, y) for lg in legends), (a.get_title(), x, y)
        for bar in a.patches:
            corners = bar.get_window_extent(renderer).corners()
            assert not any(lg.contains(x, y) for lg in legends for x, y in corners)
    assert points > 2 * len(rows), "the trials were drawn"
    whole = fig.bbox
    for legend in legends:  # and no legend cut off by the figure's edge
        assert whole.x0 <= legend.x0 and legend.x1 <= whole.x1, (legend, whole)
        assert whole.y0 <= legend.y0 and legend.y1 <= whole.y1, (legend, whole)
