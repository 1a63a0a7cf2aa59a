"""The allowed range of every parameter, in one place.

`Simulation`, `run_experiment`, the settings, the command-line types (argtypes.py)
and the help texts all read their ranges here, so that what the help promises,
what validation accepts and what the settings offer agree. Each bound is chosen
so that every accepted value gives finite arithmetic and bounded work and memory
(under 1 GB for any accepted input below 100 000 atoms); the reason stands beside it.
Units: px, frames (1/30 s), atom masses; energies in mass px^2 / frame^2.

This module imports nothing from evapcool: every layer may read it.
"""

from __future__ import annotations

import math
import numbers
import reprlib
from collections.abc import Mapping
from dataclasses import dataclass

#: A value shown in an error message is cut to about this many characters.
_SHOWN = reprlib.Repr()
_SHOWN.maxstring = 40
_SHOWN.maxother = 40
_SHOWN.maxlist = _SHOWN.maxtuple = 4


def plain(value: object) -> object:
    """A NumPy scalar as the Python number it holds (its repr is np.float64(...)); a list
    or tuple with its first few items so; anything else as it is (issue 25.2)."""
    if getattr(value, "ndim", None) == 0 and hasattr(value, "item"):
        return value.item()
    if isinstance(value, (list, tuple)) and len(value) <= _SHOWN.maxlist:
        return type(value)(plain(v) for v in value) if type(value) in (list, tuple) else value
    return value


def shown(value: object) -> str:
    """repr of value as plain numbers, shortened: a 10**6-element list or a megabyte string
    stays one line, and np.float64(1.5) shows as 1.5."""
    value = plain(value)
    if isinstance(value, float):
        return repr(value)
    return _SHOWN.repr(value)


class ParameterError(ValueError):
    """A bad value of one parameter, its name as data (issue 26.2): str() is the Python
    API's line ("n_atoms must be ..."); a command line renders it with its own option names
    from a table (`render`), never by rewriting the text.

    joint: further parameters of a limit they share (atoms that do not fit at a radius).
    """

    def __init__(
        self, parameter: str, detail: str, joint: tuple[str, ...] = (), sep: str = " "
    ) -> None:
        super().__init__(parameter, detail, joint, sep)  # args: pickles through Dask
        self.parameter = parameter
        self.detail = detail
        self.joint = tuple(joint)
        self.sep = sep

    @property
    def parameters(self) -> tuple[str, ...]:
        """Every parameter the line is about, the first one first."""
        return (self.parameter, *self.joint)

    def render(self, names: Mapping[str, str] | None = None) -> str:
        """The line with each parameter under its name in names (e.g. n_atoms -> --atoms);
        a joint parameter missing from names is left out (that command cannot set it)."""
        if names is None:
            return str(self)
        joint = [names[p] for p in self.joint if p in names]
        shown_names = [names.get(self.parameter, self.parameter), *joint]
        label = shown_names[0] if len(shown_names) == 1 else _joined(shown_names)
        return f"{label}{self.sep}{self.detail}"

    def __str__(self) -> str:
        return f"{self.parameter}{self.sep}{self.detail}"


def _joined(names: list[str]) -> str:
    """'a and b', 'a, b and c'."""
    return ", ".join(names[:-1]) + " and " + names[-1]


def bad_value(name: str, allowed: str, value: object) -> ParameterError:
    """'name must be allowed (got value)' as a ParameterError."""
    return ParameterError(name, f"must be {allowed} (got {shown(value)})")


@dataclass(frozen=True)
class Range:
    """A closed interval [low, high] (open at low if low_open), whole numbers if integer.

    inf_ok: +inf is accepted too, meaning "none" (no rim, no checkpoint).
    """

    low: float
    high: float
    unit: str = ""
    integer: bool = False
    low_open: bool = False
    inf_ok: bool = False

    def span(self) -> str:
        """'0.01 to 1000 px', '> 0 px', '1 to 1000000' (for help texts)."""
        unit = f" {self.unit}" if self.unit else ""
        if self.low_open and math.isinf(self.high):
            text = f"> {self.low:g}{unit}"
        elif self.low_open:
            text = f"> {self.low:g} and <= {self.high:g}{unit}"
        elif self.integer:
            text = f"{int(self.low)} to {int(self.high)}{unit}"
        else:
            text = f"{self.low:g} to {self.high:g}{unit}"
        return text + (" or inf" if self.inf_ok and not math.isinf(self.high) else "")

    def allowed(self) -> str:
        """'a whole number from 1 to 1000000', 'a number > 0 px or inf', ..."""
        kind = "a whole number" if self.integer else "a number"
        if self.low_open:
            return f"{kind} {self.span()}"
        return f"{kind} from {self.span()}"

    def contains(self, value: float) -> bool:
        if math.isnan(value):
            return False
        if math.isinf(value) and value > 0 and self.inf_ok:
            return True
        above = value > self.low if self.low_open else value >= self.low
        return above and value <= self.high and math.isfinite(value)

    def check(self, name: str, value: object) -> float:
        """value as int (integer ranges) or float; ValueError naming name and the range."""
        if isinstance(value, bool):  # True is no number here
            raise bad_value(name, self.allowed(), value)
        if self.integer:
            if isinstance(value, numbers.Integral) and self.low <= int(value) <= self.high:
                return int(value)
        elif isinstance(value, numbers.Real) and self.contains(float(value)):
            return float(value)
        raise bad_value(name, self.allowed(), value)  # built only for a refusal (hot path)

    def check_int(self, name: str, value: object) -> int:
        """check() of a whole-number range, typed as the int it returns."""
        if not self.integer:
            raise TypeError(f"{name}: check_int needs an integer range")
        return int(self.check(name, value))


# -- the physics (Simulation) ------------------------------------------------------------
#: Atoms: every table is O(N): 645 MB measured at 10^6 atoms with the fast engine
#: (196 MB at 10^5); the loader's work is O(N) too, and it says when they do not fit.
N_ATOMS = Range(1, 1_000_000, integer=True)
#: The reference engine keeps an N x N table of pair times: 8 N^2 bytes, 200 MB here.
REFERENCE_MAX_ATOMS = 5000
#: Atom radius. At 0.01 px the round-off of a position (1e-16 of it, 1.5e-8 px even at
#: POSITION_MAX) stays below 2e-6 of a radius, so contacts stay exact enough; at 1000 px
#: one atom is wider than the largest window (the loader then says none fit).
RADIUS = Range(0.01, 1000.0, "px")
#: Mass in atom masses: a mass ratio of at most 10^6, so after equipartition the
#: lightest atom is at most 1000 times faster than the heaviest (and its events as frequent).
MASS = Range(1e-3, 1e3, "atom masses")
#: g. A resting atom hops off the wall g / (2 v_min) times a frame (v_min =
#: world.WALL_MIN_NORMAL_SPEED = 1e-3 px/frame; 167 at the applet's 1/3): 5000 at the top.
#: At the bottom an atom of speed VELOCITY_MAX rises V^2 / 2g = 5e6 px, inside POSITION_MAX.
GRAVITY = Range(1e-3, 10.0, "px/frame^2")
#: a of the cup y = a x^2. At 1e-5 the cup is 6300 px wide at the default rim, ten
#: windows; at 10 the vertex is 0.05 px round (only the smallest atoms fit at the bottom).
#: Wall bounces in a gas come sqrt(2 a g) times a frame, at most 14.
CURVATURE = Range(1e-5, 10.0, "1/px")
#: Rim height H; inf: no rim (and no knife). Any positive H gives finite arithmetic:
#: sqrt(H / a) and m g H may become inf, which only means "never reached".
TRAP_HEIGHT = Range(0.0, math.inf, "px", low_open=True, inf_ok=True)
#: p in Tc(N) = Tc0 (N / N0)^p; N <= N0, so no p overflows.
TC_EXPONENT = Range(0.0, 10.0, low_open=True)
#: Speed of a given atom, px/frame (the applet's start: 3 to 8; its window in 7 frames at
#: 100). An atom that grazes the wall hops along it, each hop leaving at v_min, about
#: (1 + pi/2) v / v_min times a slide up and back (kernels.bounce_wall): 2.6e5 events at
#: 100 px/frame, a second of the fast engine, about half a minute of the reference one.
VELOCITY_MAX = 100.0
#: |x| and y of a given centre, px: twenty times the 5e6 px the fastest atom rises at the
#: weakest g; a position's round-off there is 1.5e-8 px.
POSITION_MAX = 1e8
#: The longest time a stored high-score row may claim, s: a billion seconds (31 years) is no
#: game, and the table's m:ss.s of more would not fit (both editions refuse such a row).
SCORE_SECONDS_MAX = 1e9
#: A recorded game (a replay code, a class challenge): the atoms and their radius a verifier
#: replays in milliseconds (400 atoms of radius 40 do not all fit: loading refuses those),
#: and the longest game, 20 minutes of play at 30 frames/s. Written once: both editions'
#: replay checks, the class server's challenge and the lecturer's form read these.
REPLAY_ATOMS = Range(2, 400, integer=True)
REPLAY_RADIUS = Range(1.0, 40.0, "px")
REPLAY_FRAMES_MAX = 36_000
#: A student's name in a class, characters: what a projector's row shows whole. The server,
#: the page's name box and the desktop's --name read this one number.
CLASS_NAME_MAX = 24
#: Window sides, px: at 8192 the loader's top rows start at 72 px/frame, under VELOCITY_MAX.
WINDOW_SIDE = Range(160, 8192, "px", integer=True)
#: Random seed of the shared start generator (physics/start.py): every edition holds it
#: exactly (a double's whole numbers), so any game can be replayed in the page too.
SEED = Range(0, 2**53 - 1, integer=True)
#: Frames in one run or one advance(dt): work is bounded by events per atom-frame
#: times atoms times frames. 10^8 frames are 39 days of the applet's time; the
#: clock's round-off is then 1.5e-8 frames.
FRAMES_MAX = 10**8
DT = Range(0.0, float(FRAMES_MAX), "frames")
#: Starting-state tolerance: a pair may be closer than r_i + r_j, and a centre below
#: the wall, by this relative round-off (a state saved mid-run touches at contacts).
CONTACT_TOLERANCE = 1e-9

# -- the lab (run_experiment, evapcool lab) -------------------------------------------------
FRAMES = Range(1, FRAMES_MAX, integer=True)
EVERY = Range(1, FRAMES_MAX, integer=True)
#: Records kept in memory as Python lists (about 0.4 KB each) and written as text
#: (about 0.2 KB each): 10^5 records stay far below 1 GB with every copy made.
RECORDS_MAX = 100_000
#: Seconds between checkpoint writes of --out; 0: at every record, inf: never. Each
#: rewrites the whole file, so 0 costs O(records^2) bytes: for tests and short runs.
CHECKPOINT_SECONDS = Range(0.0, math.inf, "s", inf_ok=True)
#: kT of a thermal start (the applet's gas: about 20): the fastest of 10^6 atoms goes
#: about 5.3 sqrt(kT / m), 84 px/frame at the top, under VELOCITY_MAX, so the state a run
#: saves stays a valid start; at 1e-3 the cloud is 3e-3 px tall.
START_KT = Range(1e-3, 250.0, "mass px^2/frame^2")
#: eta of an 'eta=' schedule (cut at eta kT). Below about 1e-50 the truncated law's mean
#: energy underflows to 0 (then 0/0: a NaN height, found by the fuzz); at 1000 the cut
#: leaves e^-1000 of the gas above it, no cut at all. Evaporation runs use 4 to 10.
ETA = Range(1e-3, 1e3)
#: Points of a ramp schedule: each frame looks its height up among them.
SCHEDULE_POINTS_MAX = 1000

# -- the applet (evapcool, its settings screen and file) ----------------------------------
#: Atom radius in the applet: 1 px is a dot on a projector; from 21 px fewer than 49 fit.
APPLET_RADIUS = Range(1.0, 20.0, "px")
#: Atoms in the applet; the settings also cap them by what fits the cup (settings.max_atoms).
APPLET_ATOMS = Range(1, 20_000, integer=True)
#: Simulation speed multiplier (the +/- keys halve and double within it).
APPLET_SPEED = Range(0.25, 4.0)
#: The trap-height slider's range, the original applet's (SPEC section 1).
APPLET_HEIGHT = Range(25.0, 450.0, "px")
#: --frames N of a headless run.
APPLET_FRAMES = Range(0, FRAMES_MAX, integer=True)

# -- files the program reads ------------------------------------------------------------------
#: Settings and high-score files are a few hundred bytes; a bigger one is damaged.
USER_FILE_MAX_BYTES = 1 << 20
#: A lab result: RECORDS_MAX rows and N_ATOMS final energies are about 50 MB of text;
#: parsing 128 MB takes under 1 GB.
LAB_FILE_MAX_BYTES = 128 << 20
