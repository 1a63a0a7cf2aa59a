"""The autopilot: strategies that move the trap-height slider, and a headless game that plays them.

A strategy turns what the player sees (the clock, the thermometer's T and Tc, the atom
count) into a trap height for the current frame. Two kinds:

- a ramp (open loop): H(t) piecewise linear in frames, written as a lab schedule
  ``400@0,300@600,140@1800``;
- a policy (closed loop): H set every frame from the measured T, N and Tc, written as
  ``FAMILY:name=value,...`` (e.g. ``feedback:eta0=5,eta1=3,beta=0,ratchet=1,budget=1800``).

Heights are clamped to the slider's range, so whatever a strategy asks for is playable in
the applet. Strategy files are JSON (`save_strategy`, `load_strategy`); ``demo`` names the
strategy that ships with the package. No pygame, no optional dependencies here.
"""

from __future__ import annotations

import itertools
import json
import math
import os
import re
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from evapcool.fileio import atomic_write_text, read_user_text
from evapcool.game.rules import HEIGHT_MAX, Game, clamp_height
from evapcool.i18n import t
from evapcool.limits import USER_FILE_MAX_BYTES
from evapcool.physics.simulation import (
    ATOM_RADIUS,
    N_ATOMS,
    TC_EXPONENT_SEED,
    Simulation,
)

DEMO = "demo"
FILE_FORMAT = "evapcool-strategy"
FILE_VERSION = 1
DEMO_RESOURCE = "demo_strategy.json"
#: kT of the cup's equilibrium gas is 2/5 of the mean energy per atom (SPEC 4).
KT_PER_MEAN_ENERGY = 0.4
STRATEGY_HELP = (
    "demo, a strategy file (.json), or a strategy like 400@0,140@1800 or feedback:eta0=5,eta1=3"
)

_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
_POINT = re.compile(rf"^\s*({_NUMBER})\s*@\s*({_NUMBER})\s*$")
_POLICY = re.compile(r"^\s*([a-z]+)\s*:(.*)$")


@dataclass(frozen=True)
class Reading:
    """What the player sees at one frame: clock, thermometer, atom count (and the game's laws)."""

    frame: float
    temperature: float
    critical_temperature: float
    n_trapped: int
    tc_exponent: float = TC_EXPONENT_SEED
    gravity: float = 10.0 / 30.0
    mass: float = 1.0

    @property
    def kt(self) -> float:
        """kT of a cup gas at this mean energy (SPEC 4)."""
        return KT_PER_MEAN_ENERGY * self.temperature

    def win_energy(self) -> float:
        """Energy the next escaping atom must carry for T < Tc(N - 1) at once (seed Eqs. 1, 46).

        A rim escape carries at least m g H, so a cut at this energy makes the next escape win.
        """
        n = self.n_trapped
        if n < 2:
            return math.inf
        tc_next: float = self.critical_temperature * ((n - 1) / n) ** self.tc_exponent
        return n * self.temperature - (n - 1) * tc_next


def read(sim: Simulation, mass: float | None = None) -> Reading:
    """The reading of a simulation now (the thermometer and the counter the applet shows).

    mass: the atoms' mass if known to be uniform (saves a per-frame mean in long searches).
    """
    n = sim.n_trapped
    if mass is None:
        mass = float(sim.masses.mean()) if n else 1.0
    return Reading(
        frame=sim.time,
        temperature=sim.temperature,
        critical_temperature=sim.critical_temperature if n else 0.0,
        n_trapped=n,
        tc_exponent=sim.tc_exponent,
        gravity=sim.gravity,
        mass=mass,
    )


#: A controller: one game's stateful rule, reading -> trap height (px, clamped).
Controller = Callable[[Reading], float]


# -- ramps (open loop) ---------------------------------------------------------------------


@dataclass(frozen=True)
class Ramp:
    """H(t) through points (frame, H), linear between them, held outside; heights clamped."""

    points: tuple[tuple[float, float], ...]
    closed_loop = False

    def __post_init__(self) -> None:
        if not self.points:
            raise ValueError("ramp must have at least one point")
        frames = [f for f, _ in self.points]
        for f, h in self.points:
            if not (math.isfinite(f) and f >= 0.0 and math.isfinite(h) and h > 0.0):
                raise ValueError(f"ramp points must be heights > 0 at frames >= 0 (got {h}@{f})")
        if any(b <= a for a, b in itertools.pairwise(frames)):
            raise ValueError("ramp frames must increase")

    def height_at(self, frame: float) -> float:
        pts = self.points
        if frame <= pts[0][0]:
            return clamp_height(pts[0][1])
        for (f0, h0), (f1, h1) in itertools.pairwise(pts):
            if frame <= f1:
                w = (frame - f0) / (f1 - f0)
                return clamp_height((1.0 - w) * h0 + w * h1)
        return clamp_height(pts[-1][1])

    def controller(self) -> Controller:
        return lambda reading: self.height_at(reading.frame)

    @property
    def text(self) -> str:
        return ",".join(f"{_num(h)}@{_num(f)}" for f, h in self.points)


def _num(x: float) -> str:
    """Shortest text that reads back as the same float."""
    r = repr(float(x))
    return r[:-2] if r.endswith(".0") else r


# -- policies (closed loop) ----------------------------------------------------------------


@dataclass(frozen=True)
class Policy:
    """A closed-loop rule from a family in POLICIES, with its parameters."""

    family: str
    params: Mapping[str, float] = field(default_factory=dict)
    closed_loop = True

    def __post_init__(self) -> None:
        spec = POLICIES.get(self.family)
        if spec is None:
            raise ValueError(
                f"policy family must be one of {', '.join(POLICIES)} (got {self.family!r})"
            )
        full = dict(spec.defaults)
        for name, value in self.params.items():
            if name not in spec.defaults:
                raise ValueError(
                    f"{self.family} policy has no parameter {name!r}; "
                    f"allowed: {', '.join(spec.defaults)}"
                )
            v = float(value)
            if not math.isfinite(v):
                raise ValueError(f"{self.family} policy parameter {name} must be finite")
            full[name] = v
        if full.get("budget", 1.0) <= 0.0:
            raise ValueError(f"{self.family} policy parameter budget must be > 0")
        object.__setattr__(self, "params", full)

    def controller(self) -> Controller:
        return POLICIES[self.family].build(self.params)

    @property
    def text(self) -> str:
        body = ",".join(f"{k}={_num(v)}" for k, v in self.params.items())
        return f"{self.family}:{body}"


@dataclass(frozen=True)
class PolicySpec:
    """A closed-loop family: its parameters with defaults, and the controller they build
    (the builder's docstring says what the rule does)."""

    defaults: Mapping[str, float]
    build: Callable[[Mapping[str, float]], Controller]


def _progress(frame: float, budget: float) -> float:
    return min(max(frame / budget, 0.0), 1.0)


def _eta_rule(eta_of: Callable[[Reading], float | None], ratchet: bool) -> Controller:
    """The mechanism of the eta families: H = eta kT/(m g), eta from the reading (the cut
    in units of kT); with ratchet, H never rises. Without a gas to read (no atoms, no T, or
    eta_of says None), the trap stays where it was."""
    last = [math.inf]

    def rule(r: Reading) -> float:
        eta = eta_of(r) if r.n_trapped > 0 and r.temperature > 0.0 else None
        if eta is None:
            return last[0] if math.isfinite(last[0]) else HEIGHT_MAX
        h = clamp_height(eta * r.kt / (r.mass * r.gravity))
        if ratchet:
            h = min(h, last[0])
        last[0] = h
        return h

    return rule


def _feedback(p: Mapping[str, float]) -> Controller:
    """H = eta kT / (m g), eta from the clock and the thermometer; optional ratchet."""

    def eta(r: Reading) -> float:
        tau = _progress(r.frame, p["budget"])
        return p["eta0"] + (p["eta1"] - p["eta0"]) * tau + p["beta"] * _gap(r)

    return _eta_rule(eta, p["ratchet"] >= 0.5)


def _creep(p: Mapping[str, float]) -> Controller:
    """Lower the trap steadily while no atom leaves; after an escape step back up and wait.

    The creep speed goes from v0 to v1 px/frame over the budget; an escape raises H by
    `back` kT/(m g) but never above `eta` kT/(m g), then H holds for `wait` frames (a
    player's "lower until one goes"). Rates are per frame of play, however often it is asked.
    """
    state = {"h": math.nan, "n": -1, "hold": 0.0, "frame": 0.0}

    def rule(r: Reading) -> float:
        if state["n"] < 0:
            state.update(h=clamp_height(p["h0"]), n=r.n_trapped, frame=r.frame)
            return state["h"]
        dt = max(r.frame - state["frame"], 0.0)
        tau = _progress(r.frame, p["budget"])
        unit = r.kt / (r.mass * r.gravity) if r.temperature > 0.0 else 0.0
        if r.n_trapped < state["n"]:
            state["h"] = min(state["h"] + p["back"] * unit, max(state["h"], p["eta"] * unit))
            state["hold"] = p["wait"]
        else:
            creep = dt - min(state["hold"], dt)  # frames of this step past the wait
            state["hold"] = max(state["hold"] - dt, 0.0)
            state["h"] -= (p["v0"] + (p["v1"] - p["v0"]) * tau) * creep
        state.update(n=r.n_trapped, frame=r.frame, h=clamp_height(state["h"]))
        return state["h"]

    return rule


def _deadline(p: Mapping[str, float]) -> Controller:
    """Cut as high as the clock allows: eta falls as the distance to the win grows per time left.

    d = ln(T/Tc) is how far the gas is from condensing; u = d / (finish - t/budget) is the
    rate it must still fall at to win by `finish` of the budget. eta = eta_hi - gain u,
    kept within [eta_lo, eta_hi].
    """

    def eta(r: Reading) -> float | None:
        if r.critical_temperature <= 0.0:
            return None
        left = max(p["finish"] - r.frame / p["budget"], 0.01)
        u = max(_gap(r), 0.0) / left
        return min(p["eta_hi"], max(p["eta_lo"], p["eta_hi"] - p["gain"] * u))

    return _eta_rule(eta, p["ratchet"] >= 0.5)


def _gap(r: Reading) -> float:
    """ln(T/Tc): how far the gas is from condensing (0 or less: it wins)."""
    if r.n_trapped == 0 or r.temperature <= 0.0 or r.critical_temperature <= 0.0:
        return 0.0
    return math.log(r.temperature / r.critical_temperature)


def _guarded(p: Mapping[str, float]) -> Controller:
    """A linear ramp with a rescue: when the win is far for the time left, cut lower.

    H = min(ramp(t), eta kT/(m g)) with eta = eta_cap - gain u, at least eta_lo, where
    u = ln(T/Tc) / (1 - t/budget). Early on (or close to Tc) u is small and the ramp rules;
    a gas still far from Tc late in the game is evaporated faster so that it still wins.
    Never below eta_floor kT/(m g): a cut that low takes atoms of less than the mean energy
    plus Tc's share, and brings the gas no closer to Tc.

    The guard: from frame rescue_from on, the rim never rises again, and while the gas is
    behind schedule (ln(T/Tc) > rescue_gap (1 - t/budget)) it falls at least rescue_rate
    px per frame, floor or not, until the win (a demo must not lose; issue 25).
    """
    ramp = Ramp(((0.0, p["h0"]), (max(p["duration"], 1.0), p["h1"])))
    last = {"h": math.inf, "frame": 0.0}

    def rule(r: Reading) -> float:
        h = ramp.height_at(r.frame)
        if r.n_trapped > 0 and r.temperature > 0.0 and r.critical_temperature > 0.0:
            left = max(1.0 - r.frame / p["budget"], 0.01)
            u = max(math.log(r.temperature / r.critical_temperature), 0.0) / left
            eta = max(p["eta_lo"], p["eta_cap"] - p["gain"] * u)
            unit = r.kt / (r.mass * r.gravity)
            h = clamp_height(max(min(h, eta * unit), p["eta_floor"] * unit))
        if r.frame > p["rescue_from"] and p["rescue_rate"] > 0.0:
            dt = max(r.frame - max(last["frame"], p["rescue_from"]), 0.0)
            behind = _gap(r) > p["rescue_gap"] * max(1.0 - r.frame / p["budget"], 0.0)
            h = clamp_height(min(h, last["h"] - (p["rescue_rate"] * dt if behind else 0.0)))
        last.update(h=h, frame=r.frame)
        return h

    return rule


POLICIES: dict[str, PolicySpec] = {
    "feedback": PolicySpec(
        defaults={"eta0": 6.0, "eta1": 6.0, "beta": 0.0, "ratchet": 0.0, "budget": 1800.0},
        build=_feedback,
    ),
    "creep": PolicySpec(
        defaults={
            "h0": 400.0,
            "v0": 0.2,
            "v1": 0.2,
            "back": 0.0,
            "eta": 8.0,
            "wait": 0.0,
            "budget": 1800.0,
        },
        build=_creep,
    ),
    "deadline": PolicySpec(
        defaults={
            "eta_hi": 10.0,
            "eta_lo": 3.0,
            "gain": 10.0,
            "finish": 0.9,
            "ratchet": 0.0,
            "budget": 1800.0,
        },
        build=_deadline,
    ),
    "guarded": PolicySpec(
        defaults={
            "h0": 425.0,
            "h1": 162.0,
            "duration": 1788.0,
            "eta_cap": 12.0,
            "gain": 10.0,
            "eta_lo": 2.0,
            "eta_floor": 0.0,
            "rescue_from": 1800.0,
            "rescue_rate": 0.0,
            "rescue_gap": 0.0,
            "budget": 1800.0,
        },
        build=_guarded,
    ),
}

Strategy = Ramp | Policy


# -- text and files ------------------------------------------------------------------------


def parse_strategy(text: object) -> Strategy:
    """A ramp '400@0,140@1800' (or a constant '400'), or a policy 'family:k=v,...'."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"strategy must be {STRATEGY_HELP} (got {text!r})")
    s = text.strip()
    m = _POLICY.match(s)
    if m:
        params: dict[str, float] = {}
        body = m.group(2).strip()
        for part in body.split(",") if body else []:
            name, eq, value = part.partition("=")
            try:
                params[name.strip()] = float(value) if eq else math.nan
            except ValueError:
                params[name.strip()] = math.nan
            if not math.isfinite(params[name.strip()]):
                raise ValueError(f"strategy parameter {part.strip()!r} must be name=number")
        return Policy(m.group(1), params)
    if re.fullmatch(_NUMBER, s):
        return Ramp(((0.0, float(s)),))
    points = []
    for part in s.split(","):
        pm = _POINT.match(part)
        if not pm:
            raise ValueError(f"strategy must be {STRATEGY_HELP} (got {text!r})")
        points.append((float(pm.group(2)), float(pm.group(1))))
    return Ramp(tuple(points))


def is_strategy_name(text: str) -> bool:
    """True for 'demo', a policy text or a .json strategy file name (what lab schedules defer)."""
    s = text.strip()
    return s.lower() == DEMO or bool(_POLICY.match(s)) or s.lower().endswith(".json")


def strategy_document(strategy: Strategy, **info: object) -> dict[str, object]:
    """The JSON object of a strategy file: the strategy text plus where it came from."""
    doc: dict[str, object] = {
        "format": FILE_FORMAT,
        "version": FILE_VERSION,
        "strategy": strategy.text,
        "kind": "policy" if strategy.closed_loop else "ramp",
    }
    doc.update(info)
    return doc


def save_strategy(path: str | os.PathLike[str], strategy: Strategy, **info: object) -> None:
    """Write a strategy file (JSON) atomically; info (search, scores...) is kept beside it."""
    text = json.dumps(strategy_document(strategy, **info), indent=2, default=_jsonable) + "\n"
    atomic_write_text(path, text)


def _jsonable(obj: object) -> object:
    if hasattr(obj, "item"):
        return obj.item()  # NumPy scalars
    raise TypeError(f"cannot store {type(obj).__name__} in a strategy file")


def _from_document(doc: object, where: str) -> Strategy:
    if not isinstance(doc, dict) or doc.get("format") != FILE_FORMAT:
        raise ValueError(f"{where} is not an evapcool strategy file")
    if doc.get("version") != FILE_VERSION:
        raise ValueError(f"{where}: strategy file version {doc.get('version')!r} is not supported")
    return parse_strategy(doc.get("strategy"))


def read_strategy_file(path: str | os.PathLike[str]) -> Strategy:
    """A strategy file's strategy; ValueError if it is not one."""
    p = Path(path)
    try:  # never blocks (a FIFO is refused), and capped: issue 18
        text = read_user_text(p, USER_FILE_MAX_BYTES)
    except (OSError, ValueError) as exc:
        raise ValueError(f"cannot read strategy file {str(p)!r}: {exc}") from None
    if p.suffix.lower() != ".json":
        return parse_strategy(text)
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ValueError(f"{str(p)!r} is not valid JSON: {exc}") from None
    except RecursionError:
        raise ValueError(f"{str(p)!r} is nested too deeply") from None
    return _from_document(doc, repr(str(p)))


def demo_document() -> dict[str, Any]:
    """The shipped demo strategy's file (package data)."""
    text = resources.files("evapcool.data").joinpath(DEMO_RESOURCE).read_text(encoding="utf-8")
    doc: dict[str, Any] = json.loads(text)
    return doc


def _is_file(text: str) -> bool:
    """Whether text names a file (False for names the system refuses, e.g. too long)."""
    try:
        return Path(text).is_file()
    except (OSError, ValueError):
        return False


def load_strategy(spec: str | os.PathLike[str]) -> Strategy:
    """'demo', a strategy file (.json, or a text file holding one strategy) or strategy text."""
    if isinstance(spec, os.PathLike):
        return read_strategy_file(spec)
    if not isinstance(spec, str):
        raise ValueError(f"strategy must be {STRATEGY_HELP} (got {spec!r})")
    s = spec.strip()
    if s.lower() == DEMO:
        return _from_document(demo_document(), "the demo strategy")
    if s.lower().endswith(".json") or (_is_file(s) and not _POLICY.match(s)):
        return read_strategy_file(s)
    return parse_strategy(s)


# -- the headless game ---------------------------------------------------------------------


@dataclass(frozen=True)
class Outcome:
    """One game: the score (atoms left at the win, 0 without a win in the budget) and when."""

    seed: int
    score: int
    won_frame: int | None
    n_final: int
    temperature_final: float

    @property
    def won(self) -> bool:
        return self.won_frame is not None


@dataclass(frozen=True)
class GameSetup:
    """The game a strategy plays (each field a keyword of `Simulation`): the classic applet's
    gas by default, the fast engine."""

    n_atoms: int = N_ATOMS
    radius: float = ATOM_RADIUS
    escape: str = "rim"
    tc_exponent: float = TC_EXPONENT_SEED
    engine: str = "fast"


def play(
    strategy: Strategy,
    seed: int,
    budget: int = 1800,
    setup: GameSetup = GameSetup(),
    trace: list[tuple[int, float, int, float]] | None = None,
) -> Outcome:
    """Play one game headless, the trap set at the start of every frame from the strategy.

    The same order as the lab (`evapcool lab --schedule`): H for frame k is decided from the
    state at frame k. trace, if given, gets (frame, H, N, T) for each frame played.
    """
    sim = Simulation(seed=seed, **asdict(setup))
    control = strategy.controller()
    closed = strategy.closed_loop or trace is not None
    frame = 0
    while True:
        if closed:
            reading = read(sim, mass=1.0)
            h = control(reading)
        else:
            h = control(Reading(float(frame), math.nan, math.nan, 0))
        sim.trap_height = h
        if trace is not None:
            trace.append((frame, h, reading.n_trapped, reading.temperature))
        if frame == budget:
            break
        sim.advance(1.0)
        frame += 1
        if sim.won:
            return Outcome(seed, sim.n_trapped, frame, sim.n_trapped, sim.temperature)
        if sim.n_trapped == 0:
            break
    return Outcome(seed, 0, None, sim.n_trapped, sim.temperature)


# -- the autopilot in a game ------------------------------------------------------------------


class Autopilot:
    """Plays a strategy in a `Game`: moves the trap each frame until the player takes over.

    The applet calls `steer(game)` after each advance; touching the slider (or its keys)
    calls `take_over()`. `engage()` hands control back (from the current time on: a ramp
    continues where its clock is, a policy reads the gas as it is). `flew` says whether
    the autopilot moved the trap in this game: its score is then an autopilot score.
    """

    def __init__(self, strategy: Strategy, name: str = DEMO) -> None:
        self.strategy = strategy
        self.name = name
        self.engaged = True
        self.flew = False
        self._control: Controller | None = None

    @classmethod
    def load(cls, spec: str | os.PathLike[str]) -> Autopilot:
        """From 'demo', a strategy file or strategy text (ValueError naming what is allowed)."""
        strategy = load_strategy(spec)
        text = str(spec).strip()
        if text.lower() == DEMO:
            name = DEMO
        elif _is_file(text):
            name = Path(text).stem
        else:
            name = "custom"
        return cls(strategy, name=name)

    def new_game(self) -> None:
        """A restart: the strategy starts over, and the autopilot flies again if engaged."""
        self._control = None
        self.flew = False

    def engage(self) -> None:
        self.engaged = True
        self._control = None

    def take_over(self) -> None:
        """The player touched the controls: hands off until engaged again."""
        self.engaged = False

    def toggle(self) -> bool:
        if self.engaged:
            self.take_over()
        else:
            self.engage()
        return self.engaged

    def steer(self, game: Game) -> float | None:
        """Set the game's trap for its current frame; the height set, or None if hands off.

        Nothing moves while paused (the player may still be choosing the start) or after
        the win (the game freezes the slider then).
        """
        running = game.sim.time > 0.0
        if not self.engaged or game.won or game.sim.n_trapped == 0 or (game.paused and running):
            return None
        if self._control is None:
            self._control = self.strategy.controller()
        game.set_trap_height(self._control(read(game.sim)))
        self.flew = self.flew or running  # setting the start alone makes no autopilot game
        return game.trap_height

    @property
    def label(self) -> str:
        """What the screen calls it: 'Autopilot (demo)'."""
        return t("autopilot.label", name=self.name)

    @property
    def table_name(self) -> str:
        """Its name in the (autopilot's own) score table: 'Autopilot demo', cut to fit."""
        from evapcool.game.highscores import NAME_MAX

        return f"Autopilot {self.name}"[:NAME_MAX]
