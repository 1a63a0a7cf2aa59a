"""The optimizer's families, its evaluation of a strategy on seeds, and its statistics (26.5)."""

from __future__ import annotations

import math

import pytest

from evapcool.game.autopilot import parse_strategy
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN
from evapcool.optimize import families
from evapcool.optimize.evaluate import Paired, Summary, chunks, play_seeds
from evapcool.optimize.report import pareto

optuna = pytest.importorskip("optuna")
optuna.logging.set_verbosity(optuna.logging.WARNING)

SMALL = {"n_atoms": 12, "engine": "reference"}


@pytest.mark.parametrize("name", sorted(families.FAMILIES))
def test_each_family_suggests_within_its_space_and_builds_a_playable_strategy(name: str) -> None:
    study = optuna.create_study(sampler=optuna.samplers.RandomSampler(seed=3))
    for _ in range(5):
        trial = study.ask()
        family, params = families.suggest(trial, (name,), 1800, families.DEFAULT_KNOTS)
        assert family == name
        for key, value in trial.params.items():
            assert key.startswith(f"{name}.")  # one study can hold every family
            assert trial.distributions[key]._contains(
                trial.distributions[key].to_internal_repr(value)
            )
        strategy = families.build(family, params, 1800, families.DEFAULT_KNOTS)
        assert strategy.closed_loop == families.FAMILIES[name].closed_loop
        assert parse_strategy(strategy.text).text == strategy.text  # written as it was scored
        if not strategy.closed_loop:
            hs = [strategy.height_at(f) for f in range(0, 1801, 30)]
            assert all(HEIGHT_MIN <= h <= HEIGHT_MAX for h in hs)
        study.tell(trial, 0.0)


def test_an_unknown_family_is_refused_by_name() -> None:
    with pytest.raises(ValueError, match="famil"):
        families.parse_families("linear,nosuch")


def test_play_seeds_scores_each_seed_the_same_every_time() -> None:
    rows, cpu = play_seeds("400@0,60@300", [1, 2], 300, SMALL)
    again, _ = play_seeds("400@0,60@300", [1, 2], 300, SMALL)
    assert [r[0] for r in rows] == [1, 2] and rows == again and cpu >= 0.0
    for _, score, won in rows:
        assert (won == -1 and score == 0) or (0 < won <= 300 and 0 < score <= 12)
    never, _ = play_seeds("450", [1, 2], 300, SMALL)  # the rim never comes down: no win
    assert [r[1:] for r in never] == [(0, -1), (0, -1)]


def test_chunks_cover_every_seed_once() -> None:
    assert chunks(list(range(7)), 3) == [[0, 1, 2], [3, 4, 5], [6]]


def test_summary_and_paired_statistics() -> None:
    a = Summary.of([(2, 10, 60), (1, 12, -1), (3, 8, 90)], budget=1800)
    b = Summary.of([(1, 11, 30), (2, 10, 30), (3, 9, 30)], budget=1800)
    assert a.seeds == (1, 2, 3) and a.no_wins == 1 and a.mean == 10.0
    assert a.times == [60.0, 2.0, 3.0]
    p = Paired(a, b)
    assert p.differences == [1, 0, -1] and p.wins_losses_ties == (1, 1, 1)
    lo, hi = p.interval()
    assert lo < p.mean == 0.0 < hi and math.isclose(hi - lo, 2 * 1.96 * p.se)
    with pytest.raises(ValueError, match="same seeds"):
        Paired(a, Summary.of([(1, 1, 1)], 1800))


def test_the_pareto_front_keeps_what_nothing_beats_in_score_and_time() -> None:
    points = [
        (20.0, 30.0, "fast"),
        (25.0, 40.0, "mid"),
        (24.0, 45.0, "beaten"),
        (29.0, 50.0, "slow"),
    ]
    assert [tag for _, _, tag in pareto(points)] == ["fast", "mid", "slow"]
