"""The game around a `Simulation`: pause, speed, restart, win, score, play time.

Pure state, no pygame: the view and the app read and drive it, tests drive it
directly. Time is physics frames (1/30 s) unless a name says seconds.

When the player's trap height takes effect (both editions' rule, written once in the
compiled core: core/game.c, `Simulation.frame`): at the next whole physics frame, t = k.
The game advances in pieces that stop at each whole frame, see the win there (the score
fixed then) and apply the height asked for since the last one, so a run depends on what
the player did in which frame, never on the display's rate. Paused, or standing on a
whole frame, the height applies at once. (`Simulation.trap_height = H` itself applies at
once: docs/model.md.)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import Any

from evapcool.i18n import t
from evapcool.limits import APPLET_SPEED
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

#: Trap-height range of the original slider, px, and its start.
HEIGHT_MIN = 25.0
HEIGHT_MAX = 450.0
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
        #: during it (a replay's Recorder.frame: a game is its heights per frame, issue 22).
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
        #: A height asked for since the last whole frame, applied at the next one.
        self._pending_height: float | None = None
        #: Heights to hold frame by frame (a recording played back), or None: the player's.
        self._script: list[float] | None = None
        #: Whole frames played since the (re)start (the script's index).
        self._frames_done = 0
        self.paused = True
        #: Play time (s) at which the win was first seen, None before.
        self.won_at: float | None = None
        self._won_with: int | None = None
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
        for _ in range(3):  # one piece, a second if rounding stopped short of the boundary
            t = float(self.sim.time)
            if t.is_integer():
                return
            self._advance(math.floor(t) + 1.0 - t)

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
        pending = self._pending_height
        return self.sim.trap_height if pending is None else pending

    def set_trap_height(self, height: float) -> bool:
        """Ask for a rim height (clamped to the slider range), applied at the next whole
        frame (at once if paused or on one); frozen once the gas has condensed.

        Returns True if the height asked for changed.
        """
        if self.won or self._script is not None:
            return False  # the score is the atoms left: no evaporating after the win
        # The slider's range, inside limits.TRAP_HEIGHT: the one check and conversion.
        h = clamp_height(height)
        if h == self.trap_height:
            return False
        self._pending_height = h
        if self.paused or float(self.sim.time).is_integer():
            self._apply_pending()  # nothing in flight
        return True

    def nudge_height(self, delta: float) -> bool:
        return self.set_trap_height(self.trap_height + delta)

    def playback(self, heights: list[float] | None) -> None:
        """Hold these heights, one per whole frame from now (a recording watched); the
        player's heights are ignored until the script ends or playback(None)."""
        self._script = list(heights) if heights else None
        self._scripted()
        if float(self.sim.time).is_integer():
            self._apply_pending()

    def _scripted(self) -> None:
        """The script's height for the frame starting now."""
        if self._script is None:
            return
        if self._frames_done >= len(self._script):
            self._script = None
            return
        self._pending_height = clamp_height(self._script[self._frames_done])

    def _apply_pending(self) -> None:
        if self._pending_height is not None:
            self.sim.set_checked_trap_height(self._pending_height)
            self._pending_height = None

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
        """Advance frames in pieces that stop at each whole frame: the win is seen and the
        score fixed at the frame's end, then the held height applies (Simulation.frame's
        rule, the core's), so a game (its win, its score) depends on the heights of whole
        frames, not on the display's step (replays rely on it)."""
        sim = self.sim
        end = sim.time + frames
        while sim.time < end:
            boundary = math.floor(sim.time) + 1.0
            if float(sim.time).is_integer() and end >= boundary:
                sim.frame(sim.trap_height)  # a whole frame in one step
            else:
                sim.advance(min(boundary, end) - sim.time)
                if sim.time >= boundary:
                    sim.frame_end()
            if sim.time >= boundary:
                if self.won_at is None:  # the moves end with the frame of the win
                    for listener in self.on_frame:
                        listener(sim.trap_height)
                self._frames_done += 1
                self._check_win()
                self._scripted()
                self._apply_pending()
        return frames

    def _check_win(self) -> None:
        """The win seen at a frame's end (the score fixed there), once."""
        if self.sim.score is not None and self.won_at is None:
            self.won_at = self.play_time
            self._won_with = self.sim.score
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
        return self._won_with if self._won_with is not None else self.sim.n_trapped

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
