"""Strategy families the optimizer searches, as Optuna search spaces.

Each family turns a dict of parameters into a strategy of `game.autopilot`: open-loop
families become ramps (the exponential and power-law curves sampled every SAMPLE_FRAMES
frames, so the ramp written to the file is exactly the one that was scored), closed-loop
families become policies. Parameter names carry the family as a prefix so one study can
hold several families.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from evapcool.game.autopilot import Policy, Ramp, Strategy
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN

#: Open-loop curves are written as ramps with a point every this many frames (1 s).
SAMPLE_FRAMES = 30
DEFAULT_KNOTS = 4


@dataclass(frozen=True)
class Family:
    """A family: what it is, its kind, how to suggest parameters and build a strategy."""

    name: str
    closed_loop: bool
    doc: str
    suggest: Callable[..., dict[str, float]]
    build: Callable[[Mapping[str, float], int, int], Strategy]


def _h(trial, name: str, low: float = HEIGHT_MIN, high: float = HEIGHT_MAX) -> float:
    return trial.suggest_float(name, low, high)


# -- open loop ---------------------------------------------------------------------------


def _suggest_linear(trial, budget: int, knots: int) -> dict[str, float]:
    return {
        "h0": _h(trial, "linear.h0"),
        "h1": _h(trial, "linear.h1"),
        "duration": trial.suggest_float("linear.duration", 0.2 * budget, float(budget)),
    }


def _build_linear(p: Mapping[str, float], budget: int, knots: int) -> Strategy:
    return Ramp(((0.0, round(p["h0"], 3)), (float(round(p["duration"])), round(p["h1"], 3))))


def _suggest_knots(trial, budget: int, knots: int) -> dict[str, float]:
    p = {"h0": _h(trial, "knots.h0"), "end": trial.suggest_float("knots.end", 0.2, 1.0)}
    for k in range(1, knots + 1):
        p[f"drop{k}"] = trial.suggest_float(f"knots.drop{k}", 0.0, 1.0)
        p[f"gap{k}"] = trial.suggest_float(f"knots.gap{k}", 0.05, 1.0)
    return p


def _build_knots(p: Mapping[str, float], budget: int, knots: int) -> Strategy:
    """Monotone: knot k lowers H by drop_k of what is left above the slider's bottom."""
    gaps = [p[f"gap{k}"] for k in range(1, knots + 1)]
    total = sum(gaps)
    h = p["h0"]
    points = [(0.0, round(h, 3))]
    t = 0.0
    for k in range(1, knots + 1):
        t += gaps[k - 1] / total
        h -= p[f"drop{k}"] * (h - HEIGHT_MIN)
        frame = float(round(t * p["end"] * budget))
        if frame > points[-1][0]:
            points.append((frame, round(h, 3)))
    return Ramp(tuple(points))


def _sampled(curve: Callable[[float], float], budget: int) -> Ramp:
    frames = [*range(0, budget, SAMPLE_FRAMES), budget]
    points = [(float(f), min(HEIGHT_MAX, max(HEIGHT_MIN, round(curve(f), 3)))) for f in frames]
    return Ramp(tuple(points))


def _suggest_exponential(trial, budget: int, knots: int) -> dict[str, float]:
    return {
        "h0": _h(trial, "exponential.h0"),
        "h_end": _h(trial, "exponential.h_end", HEIGHT_MIN, 300.0),
        "tau": trial.suggest_float("exponential.tau", 0.05 * budget, 3.0 * budget, log=True),
    }


def _build_exponential(p: Mapping[str, float], budget: int, knots: int) -> Strategy:
    """H = h_end + (h0 - h_end) exp(-t/tau): the classic exponential ramp."""
    return _sampled(lambda t: p["h_end"] + (p["h0"] - p["h_end"]) * math.exp(-t / p["tau"]), budget)


def _suggest_power(trial, budget: int, knots: int) -> dict[str, float]:
    return {
        "h0": _h(trial, "power.h0"),
        "tau": trial.suggest_float("power.tau", 0.005 * budget, 2.0 * budget, log=True),
        "alpha": trial.suggest_float("power.alpha", 0.05, 3.0),
    }


def _build_power(p: Mapping[str, float], budget: int, knots: int) -> Strategy:
    """H = h0 (1 + t/tau)^-alpha: the scaling-law ramp (O'Hara et al., PRA 64, 051403 (2001))."""
    return _sampled(lambda t: p["h0"] * (1.0 + t / p["tau"]) ** -p["alpha"], budget)


# -- closed loop -------------------------------------------------------------------------


def _suggest_feedback(trial, budget: int, knots: int) -> dict[str, float]:
    return {
        "eta0": trial.suggest_float("feedback.eta0", 2.0, 16.0),
        "eta1": trial.suggest_float("feedback.eta1", 2.0, 16.0),
        "beta": trial.suggest_float("feedback.beta", -8.0, 8.0),
        "ratchet": float(trial.suggest_int("feedback.ratchet", 0, 1)),
    }


def _suggest_creep(trial, budget: int, knots: int) -> dict[str, float]:
    return {
        "h0": _h(trial, "creep.h0", 150.0, HEIGHT_MAX),
        "v0": trial.suggest_float("creep.v0", 0.0, 1.5),
        "v1": trial.suggest_float("creep.v1", 0.0, 1.5),
        "back": trial.suggest_float("creep.back", 0.0, 4.0),
        "eta": trial.suggest_float("creep.eta", 3.0, 16.0),
        "wait": trial.suggest_float("creep.wait", 0.0, 150.0),
    }


def _suggest_deadline(trial, budget: int, knots: int) -> dict[str, float]:
    return {
        "eta_hi": trial.suggest_float("deadline.eta_hi", 3.0, 20.0),
        "eta_lo": trial.suggest_float("deadline.eta_lo", 1.0, 12.0),
        "gain": trial.suggest_float("deadline.gain", 0.0, 40.0),
        "finish": trial.suggest_float("deadline.finish", 0.3, 1.0),
        "ratchet": float(trial.suggest_int("deadline.ratchet", 0, 1)),
    }


def _suggest_guarded(trial, budget: int, knots: int) -> dict[str, float]:
    return {
        "h0": _h(trial, "guarded.h0", 250.0, HEIGHT_MAX),
        "h1": _h(trial, "guarded.h1", HEIGHT_MIN, 300.0),
        "duration": trial.suggest_float("guarded.duration", 0.5 * budget, float(budget)),
        "eta_cap": trial.suggest_float("guarded.eta_cap", 3.0, 20.0),
        "gain": trial.suggest_float("guarded.gain", 0.0, 40.0),
        "eta_lo": trial.suggest_float("guarded.eta_lo", 1.0, 8.0),
        "eta_floor": trial.suggest_float("guarded.eta_floor", 0.0, 5.0),
    }


def _policy(family: str) -> Callable[[Mapping[str, float], int, int], Strategy]:
    def build(p: Mapping[str, float], budget: int, knots: int) -> Strategy:
        # Parameters to 4 decimals: short strategy texts, and the text is what was scored.
        return Policy(family, {**{k: round(v, 4) for k, v in p.items()}, "budget": float(budget)})

    return build


FAMILIES: dict[str, Family] = {
    f.name: f
    for f in (
        Family("linear", False, "H from h0 to h1 over a duration, then held",
               _suggest_linear, _build_linear),
        Family("knots", False, "monotone piecewise-linear with K knots",
               _suggest_knots, _build_knots),
        Family("exponential", False, "H = h_end + (h0 - h_end) exp(-t/tau)",
               _suggest_exponential, _build_exponential),
        Family("power", False, "H = h0 (1 + t/tau)^-alpha",
               _suggest_power, _build_power),
        Family("feedback", True, "H = eta kT/(m g), eta(t) + beta ln(T/Tc), optional ratchet",
               _suggest_feedback, _policy("feedback")),
        Family("creep", True, "lower while no atom leaves; step back up after an escape",
               _suggest_creep, _policy("creep")),
        Family("deadline", True, "eta falls with ln(T/Tc) per time left to a finish time",
               _suggest_deadline, _policy("deadline")),
        Family("guarded", True, "a linear ramp, cut lower when the win is far for the time left",
               _suggest_guarded, _policy("guarded")),
    )
}  # fmt: skip
FAMILY_HELP = ", ".join(FAMILIES)


def parse_families(text: str) -> tuple[str, ...]:
    """'all' or a comma-separated list of family names; ValueError naming the allowed ones."""
    names = tuple(n.strip() for n in str(text).split(",") if n.strip())
    if names == ("all",):
        return tuple(FAMILIES)
    bad = [n for n in names if n not in FAMILIES]
    if not names or bad or len(set(names)) != len(names):
        raise ValueError(
            f"family must be all or names from {FAMILY_HELP}, each once (got {text!r})"
        )
    return names


def suggest(trial, families: tuple[str, ...], budget: int, knots: int) -> tuple[str, dict]:
    """Ask the trial for a family (if several) and its parameters."""
    family = families[0] if len(families) == 1 else trial.suggest_categorical("family", families)
    return family, FAMILIES[family].suggest(trial, budget, knots)


def params_of(trial_params: Mapping[str, object]) -> tuple[str | None, dict[str, float]]:
    """Family and unprefixed parameters from a stored trial's params."""
    family = trial_params.get("family")
    params: dict[str, float] = {}
    for key, value in trial_params.items():
        fam, dot, name = key.partition(".")
        if dot:
            family = family or fam
            params[name] = float(value)
    return (str(family) if family else None), params


def build(family: str, params: Mapping[str, float], budget: int, knots: int) -> Strategy:
    return FAMILIES[family].build(params, budget, knots)
