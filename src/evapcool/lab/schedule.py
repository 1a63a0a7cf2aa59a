"""Trap-height schedules H(t): constant, piecewise linear in frames, or constant truncation eta."""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass, field
from functools import cached_property

from evapcool import limits
from evapcool.game import autopilot
from evapcool.lab.theory import truncated_mean_energy, truncation_height

SCHEDULE_HELP = (
    "a height > 0 like 400 (or inf), a ramp like 400@0,60@1800 "
    f"(heights > 0 at frames >= 0, frames increasing), eta=6 (eta {limits.ETA.span()}), "
    "or an autopilot strategy: demo, FILE.json or a policy like feedback:eta0=5"
)

_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
_ETA = re.compile(rf"^eta\s*=\s*({_NUMBER})$", re.IGNORECASE)
_POINT = re.compile(rf"^({_NUMBER})\s*@\s*({_NUMBER})$")


def _bad(text: object) -> limits.ParameterError:
    return limits.bad_value("schedule", SCHEDULE_HELP, text)


@dataclass(frozen=True)
class Schedule:
    """A trap-height rule: kind 'ramp' (points (frame, H), constant if one), 'eta' or
    'autopilot' (a strategy of game.autopilot, restarted by the call at frame 0)."""

    kind: str
    points: tuple[tuple[float, float], ...] = ()
    eta: float = math.nan
    text: str = ""
    strategy: object = field(default=None, compare=False, repr=False)
    _controller: list = field(default_factory=list, compare=False, repr=False)

    @cached_property
    def mean_energy_per_kt(self) -> float:
        """<E> / kT of the law E^(3/2) exp(-E/kT) cut at eta kT (eta schedules)."""
        return float(truncated_mean_energy(self.eta))

    def fixed_height(self, frame: float) -> float:
        """H at this frame for a constant or ramp schedule; linear between points, held outside."""
        if self.kind != "ramp":
            raise ValueError("fixed_height is for constant and ramp schedules")
        pts = self.points
        if frame <= pts[0][0]:
            return pts[0][1]
        for (f0, h0), (f1, h1) in itertools.pairwise(pts):
            if frame <= f1:
                w = (frame - f0) / (f1 - f0)
                return (1.0 - w) * h0 + w * h1  # exact at both ends
        return pts[-1][1]

    def apply(self, sim, frame: float) -> None:
        """Set sim.trap_height for this frame; eta mode needs the gas's measured kT."""
        if self.kind == "ramp":
            sim.trap_height = self.fixed_height(frame)
            return
        if self.kind == "autopilot":
            if frame == 0.0 or not self._controller:
                self._controller[:] = [self.strategy.controller()]
            if not sim.won:  # the game's rule: the slider is frozen once the gas condenses
                sim.trap_height = self._controller[0](autopilot.read(sim))
            return
        # Constant truncation: H = eta kT / (m g), kT from the mean energy of the law
        # E^(3/2) exp(-E/kT) cut at eta kT (docs/lab.md). With the knife, lowering H removes
        # hot atoms and cools the rest, so repeat until self-consistent.
        mass = float(sim.masses.mean()) if sim.n_trapped else 1.0
        for _ in range(sim.n_atoms + 1):
            n_before = sim.n_trapped
            if n_before == 0:
                return
            kt = sim.temperature / self.mean_energy_per_kt
            sim.trap_height = max(truncation_height(self.eta, kt, mass, sim.gravity), 1e-300)
            if sim.n_trapped == n_before:
                return


def parse_schedule(text: str) -> Schedule:
    """Parse '400', 'inf', '400@0,60@1800' or 'eta=6'; ValueError naming the rule otherwise."""
    if not isinstance(text, str):
        raise _bad(text)
    s = text.strip()
    if autopilot.is_strategy_name(s):
        try:
            strategy = autopilot.load_strategy(s)
        except ValueError as exc:
            raise limits.ParameterError("schedule", str(exc), sep=": ") from None
        return Schedule("autopilot", text=s, strategy=strategy)
    m = _ETA.match(s)
    if m:
        eta = float(m.group(1))
        if not limits.ETA.contains(eta):
            raise _bad(text)
        return Schedule("eta", eta=eta, text=s)
    if s.lower() in ("inf", "+inf", "infinity"):
        return Schedule("ramp", points=((0.0, math.inf),), text=s)
    if re.fullmatch(_NUMBER, s):
        h = float(s)
        if not (math.isfinite(h) and h > 0.0):
            raise _bad(text)
        return Schedule("ramp", points=((0.0, h),), text=s)
    points = []
    for part in s.split(","):
        pm = _POINT.match(part.strip())
        if not pm:
            raise _bad(text)
        h, f = float(pm.group(1)), float(pm.group(2))
        if not (math.isfinite(h) and h > 0.0 and math.isfinite(f) and f >= 0.0):
            raise _bad(text)
        if points and f <= points[-1][0]:
            raise _bad(text)
        points.append((f, h))
    if not points:
        raise _bad(text)
    return Schedule("ramp", points=tuple(points), text=s)
