"""The game around a `Simulation`: pause, speed, restart, win, score, play time.

Pure state, no pygame: the view and the app read and drive it, tests drive it
directly. Time is physics frames (1/30 s) unless a name says seconds.

When the player's trap height takes effect (both editions' rule, written once in the
compiled core: core/play.c, `Simulation.play_to`): at the next whole physics frame, t = k.
The game advances in pieces that stop at each whole frame, see the win there (the score
fixed then) and apply the height asked for since the last one, so a run depends on what
the player did in which frame, never on the display's rate. Paused, or standing on a
whole frame, the height applies at once. (`Simulation.trap_height = H` itself applies at
once: docs/model.md.)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, fields
from typing import Any

from evapcool.i18n import t
from evapcool.limits import APPLET_HEIGHT, APPLET_SPEED
from evapcool.physics.config import CHECKED_KEYWORDS, SimulationConfig
from evapcool.physics.model import REACH_NAMES, REACH_STUCK_HERE, REACH_WITHIN
from evapcool.physics.room import CLASSIC_ROOM, Room
from evapcool.physics.simulation import (
    ATOM_RADIUS,
    CURVATURE,
    FPS,
    GRAVITY,
    N_ATOMS,
    TC_EXPONENT_SEED,
    TRAP_HEIGHT,
    Simulation,
)

#: Trap-height range of the original slider, px (limits.APPLET_HEIGHT), and its start.
HEIGHT_MIN = APPLET_HEIGHT.low
HEIGHT_MAX = APPLET_HEIGHT.high
HEIGHT_START = TRAP_HEIGHT
#: Simulation speed multipliers: +/- double or halve within these (limits.APPLET_SPEED).
SPEED_MIN = APPLET_SPEED.low
SPEED_MAX = APPLET_SPEED.high
#: One wall-clock step never advances more than this many seconds of play: when frames
#: fall behind (a loaded machine, thousands of atoms) the game slows down instead of
#: taking ever larger steps, each costlier than the last; a stall (window dragged,
#: laptop asleep) does not jump the game ahead: at most MAX_WALL_STEP x 30 x speed
#: physics frames a frame (2 at 1x, 8 at 4x).
MAX_WALL_STEP = 1.0 / 15.0


@dataclass(frozen=True)
class GameConfig:
    """What a (re)start builds: the original's 49 atoms of radius 12 by default."""

    n_atoms: int = N_ATOMS
    radius: float = ATOM_RADIUS
    seed: int | None = None
    speed: float = 1.0
    engine: str = "auto"
    #: p in Tc(N) = Tc0 (N / N0)^p: the seed's 2/3 or the cup's 2/5.
    tc_exponent: float = TC_EXPONENT_SEED
    #: "rim" (atoms fly over the rim) or "knife" (energy above m g H is cut at once).
    escape: str = "rim"
    #: Where escaped atoms are gone: the view gives the room its window shows (view/screen.py).
    room: Room = CLASSIC_ROOM
    #: The rim's height at each (re)start (a setup's link: `trap`), inside the slider's range.
    start_height: float = TRAP_HEIGHT


def clamp_height(h: float) -> float:
    """The slider's range, 25 to 450 px; NaN (a broken rule) leaves the trap where it starts."""
    if h != h:
        return HEIGHT_MAX
    return min(HEIGHT_MAX, max(HEIGHT_MIN, float(h)))


def check_speed(speed: object) -> float:
    """The speed as a float, or ValueError naming the allowed range."""
    return APPLET_SPEED.check("speed", speed)


#: Every game's physics (the applet's), beside what its GameConfig chooses.
GAME_PHYSICS: dict[str, Any] = {
    "mass": 1.0,
    "curvature": CURVATURE,
    "gravity": GRAVITY,
    "trap_height": HEIGHT_START,
    "record_events": False,
    "win": True,
}


def lose_message(code: int) -> str | None:
    """The reach rule's answer (Simulation.out_of_reach) as the player reads it (lose.*)."""
    return None if code == REACH_WITHIN else t(f"lose.{REACH_NAMES[code]}")


def make_simulation(config: GameConfig) -> Simulation:
    """A fresh simulation for config; the reference engine if the compiled core is missing."""

    # Checked once, here at the game's boundary. The config's own fields that are the
    # simulation's (all but speed), by their names. engine="auto" plays on the reference
    # engine where the core is missing (Simulation says so once).
    chosen = {f.name: getattr(config, f.name) for f in fields(config) if f.name in CHECKED_KEYWORDS}
    return Simulation.from_config(SimulationConfig.checked(**chosen, **GAME_PHYSICS))


class Game:
    """One game: a simulation plus the player's controls and the rules of winning."""

    def __init__(self, config: GameConfig | None = None, sim: Simulation | None = None) -> None:
        """sim: a simulation already made for config (built elsewhere, e.g. in a thread)."""
        self.config = config or GameConfig()
        self.speed = check_speed(self.config.speed)
        #: Called once with the game when the gas condenses (highscores, sounds...).
        self.on_win: list[Callable[[Game], None]] = []
        #: Called at the end of each whole physics frame up to the win with the height held
        #: during it (the run log; the moves themselves are the core's: Simulation.moves).
        self.on_frame: list[Callable[[float], None]] = []
        #: Bumped by every restart so views can drop per-game caches.
        self.generation = 0
        self.restart(sim=sim)

    # -- lifecycle ---------------------------------------------------------------
    def restart(self, config: GameConfig | None = None, sim: Simulation | None = None) -> None:
        """New atoms, trap at its start height, paused (the original's restart).

        config, if given, replaces the current one first (settings applied on restart);
        a config the simulation rejects raises ValueError and leaves the game as it was.
        sim: the new simulation, already made for that config.
        """
        if sim is None:
            sim = make_simulation(config or self.config)
        if config is not None:
            self.config = config
        self.sim = sim
        self.sim.set_checked_trap_height(clamp_height(self.config.start_height))
        self.paused = True
        #: Play time (s) at which the win was first seen, None before.
        self.won_at: float | None = None
        self.generation += 1

    # -- pause and speed -----------------------------------------------------------
    @property
    def paused(self) -> bool:
        return self._paused

    @paused.setter
    def paused(self, value: bool) -> None:
        """Pausing finishes the frame in flight: a paused game stands on a whole frame, so a
        height set while paused takes effect at one (the rule replays rely on)."""
        if value and not getattr(self, "_paused", True):
            self._finish_frame()
        self._paused = bool(value)

    def _finish_frame(self) -> None:
        t = float(self.sim.time)
        if not t.is_integer():
            self._play_to(math.floor(t) + 1.0)

    def toggle_pause(self) -> None:
        self.paused = not self.paused

    def set_speed(self, speed: float) -> None:
        self.speed = check_speed(speed)

    def faster(self) -> None:
        self.speed = min(SPEED_MAX, self.speed * 2.0)

    def slower(self) -> None:
        self.speed = max(SPEED_MIN, self.speed / 2.0)

    # -- the trap ----------------------------------------------------------------------
    @property
    def trap_height(self) -> float:
        """The rim's height now, or the one it takes at the next whole frame."""
        return self.sim.asked_height

    def set_trap_height(self, height: float) -> bool:
        """Ask for a rim height (clamped to the slider range), applied at the next whole
        frame (at once if paused or on one); frozen once the gas has condensed and while a
        recording plays (Simulation.ask_height, the core's rule).

        Returns True if the height asked for changed.
        """
        # The slider's range, inside limits.TRAP_HEIGHT: the one check and conversion.
        return self.sim.ask_height(clamp_height(height), self.paused)

    def nudge_height(self, delta: float) -> bool:
        return self.set_trap_height(self.trap_height + delta)

    def playback(self, moves: Sequence[tuple[float, int]] | None) -> None:
        """Hold a recording's (height, frames) moves, frame by frame from the start (a
        recording watched); the player's heights are ignored until they end or
        playback(None)."""
        self.sim.hold([(clamp_height(h), n) for h, n in moves or ()])

    # -- time ----------------------------------------------------------------------------
    def update(self, wall_seconds: float) -> float:
        """Advance by elapsed wall time x 30 x speed (capped); returns the frames advanced."""
        if self.paused or wall_seconds <= 0.0:
            return 0.0
        return self._advance(min(wall_seconds, MAX_WALL_STEP) * FPS * self.speed)

    def run_frames(self, n: int = 1) -> float:
        """Advance exactly n display frames of 1 physics frame x speed (headless runs)."""
        if self.paused:
            return 0.0
        return self._advance(n * self.speed)

    def step(self) -> float:
        """One physics frame forward, only while paused (frame-by-frame study)."""
        return self._advance(1.0) if self.paused else 0.0

    def _advance(self, frames: float) -> float:
        self._play_to(self.sim.time + frames)
        return frames

    def _play_to(self, end: float) -> None:
        """Play to `end` (Simulation.play_to: the core's clock, whole frame by whole frame; a
        game, its win and its score depend on the heights of whole frames, not on the
        display's step); the frame listeners hear each frame up to the win."""
        self.sim.play_to(end, self._frame_played if self.on_frame else None)
        self._check_win()

    def _frame_played(self, height: float) -> None:
        for listener in self.on_frame:
            listener(height)
        self._check_win()

    def _check_win(self) -> None:
        """The win seen at a frame's end (the score fixed there), once."""
        if self.sim.score is not None and self.won_at is None:
            self.won_at = (self.sim.win_frame or 0.0) / FPS
            for callback in list(self.on_win):
                callback(self)

    # -- what the player sees ------------------------------------------------------------
    @property
    def play_time(self) -> float:
        """Simulated seconds since the (re)start; independent of the speed setting."""
        return self.sim.time / FPS

    @property
    def won(self) -> bool:
        return self.sim.won

    @property
    def score(self) -> int | None:
        """Atoms in the cup when the gas condensed; None before.

        Fixed at that moment: an atom already on its way over the rim may still leave
        while the rest settle, but the score shown and the one stored stay the same.
        """
        if not self.sim.won:
            return None
        return self.sim.score if self.sim.score is not None else self.sim.n_trapped

    @property
    def all_escaped(self) -> bool:
        """Every atom has left the cup: nothing more can happen but a restart."""
        return self.sim.n_trapped == 0 and not self.sim.won

    @property
    def lost(self) -> bool:
        """The gas can no longer condense whatever the trap does: a lost game (a class
        that counts lost games takes it)."""
        return self._reach() not in (REACH_WITHIN, REACH_STUCK_HERE)

    @property
    def too_few_atoms(self) -> str | None:
        """Why the gas can no longer condense (say so, offer a restart), or None."""
        return lose_message(self._reach())

    def _reach(self) -> int:
        """The reach rule (Simulation.out_of_reach) for the slider's floor and the trap asked."""
        return self.sim.out_of_reach(HEIGHT_MIN, self.trap_height)
