"""Recordings of games, replay codes, and verification by replay (issue 22).

A `Recording` holds what decides a game: its settings and seed, the edition that played it,
the trap height held in each physics frame (run-length coded as [height, frames] pairs) and
the claimed result. A replay code is that recording as short text a student can paste:
``EC1.<payload>.<crc>`` with payload = URL-safe base64 (no padding) of zlib(compact JSON)
and crc = 8 hex digits of CRC-32 of the payload text, so a damaged or edited code is told
apart from one of another version. `verify` replays a recording headless with the game's
own rules (`Game`: the height applies at the next whole frame) and checks the claim.
"""

from __future__ import annotations

import base64
import binascii
import json
import math
import zlib
from dataclasses import asdict, dataclass, fields
from functools import cached_property
from typing import Any

from evapcool.about import __version__
from evapcool.game.rules import HEIGHT_MAX, HEIGHT_MIN, Game, GameConfig, clamp_height
from evapcool.limits import REPLAY_ATOMS, REPLAY_FRAMES_MAX, REPLAY_RADIUS
from evapcool.physics.constants import ATOM_RADIUS, N_ATOMS, TC_EXPONENT_SEED
from evapcool.physics.model import ESCAPE_RULES
from evapcool.physics.start import SEED_PORTABLE_MAX, START_GENERATOR

CODE_PREFIX = "EC1"
FORMAT_VERSION = 1
EDITIONS = ("desktop", "web")
#: Longest game a recording may hold (frames), and its most atoms (limits.py's).
MAX_FRAMES = REPLAY_FRAMES_MAX
MAX_ATOMS = int(REPLAY_ATOMS.high)
ATOMS_SPAN = f"{int(REPLAY_ATOMS.low)}..{MAX_ATOMS}"
RADIUS_SPAN = f"{REPLAY_RADIUS.low:g}..{REPLAY_RADIUS.high:g}"
MAX_CODE_CHARS = 200_000

#: Why a code or recording is rejected (the reasons `evapcool verify` prints).
DAMAGED = "damaged"
EDITED = "edited"
OTHER_VERSION = "other version"
WRONG_SCORE = "does not replay to the claimed score"


class ReplayError(ValueError):
    """A code or recording rejected, with one of the reasons above and a detail."""

    def __init__(self, reason: str, detail: str) -> None:
        super().__init__(f"{reason}: {detail}")
        self.reason = reason
        self.detail = detail


@dataclass(frozen=True)
class Settings:
    """The game's settings a recording was played with (GameConfig's deciding fields)."""

    n_atoms: int = N_ATOMS
    radius: float = ATOM_RADIUS
    escape: str = ESCAPE_RULES[0]
    tc_exponent: float = TC_EXPONENT_SEED

    def game_config(self, seed: int, engine: str = "auto") -> GameConfig:
        """The game these settings, seed and engine play (each field is GameConfig's)."""
        return GameConfig(seed=seed, engine=engine, **asdict(self))


@dataclass(frozen=True)
class Recording:
    """One game's moves and claimed result; moves are [height, frames] runs."""

    settings: Settings
    seed: int
    moves: tuple[tuple[float, int], ...]
    won: bool
    score: int
    frames: int
    edition: str = "desktop"
    version: str = __version__
    start_generator: int = START_GENERATOR
    format: int = FORMAT_VERSION

    @cached_property
    def n_frames(self) -> int:
        return sum(n for _, n in self.moves)

    def heights(self) -> list[float]:
        """The held height of every frame, in order."""
        return [h for h, n in self.moves for _ in range(n)]

    def to_json(self) -> dict[str, Any]:
        """The JSON document, fields in order; shallow (asdict deep-copied every move)."""
        doc = {f.name: getattr(self, f.name) for f in fields(self)}
        doc["settings"] = asdict(self.settings)
        doc["moves"] = [[h, n] for h, n in self.moves]
        return doc

    @classmethod
    def from_json(cls, doc: object) -> Recording:
        """The recording of a JSON document; ReplayError (edited / other version) if not one."""
        if not isinstance(doc, dict):
            raise ReplayError(EDITED, "not a recording object")
        if doc.get("format") != FORMAT_VERSION:
            raise ReplayError(OTHER_VERSION, f"format {doc.get('format')!r}")
        if doc.get("start_generator") != START_GENERATOR:
            raise ReplayError(OTHER_VERSION, f"start generator {doc.get('start_generator')!r}")
        if doc.get("version") != __version__:
            raise ReplayError(OTHER_VERSION, f"edition version {doc.get('version')!r}")
        try:
            s = doc["settings"]
            settings = Settings(
                n_atoms=_int(s["n_atoms"]),
                radius=_num(s["radius"]),
                escape=str(s["escape"]),
                tc_exponent=_num(s["tc_exponent"]),
            )
            moves = tuple((_num(h), _int(n)) for h, n in doc["moves"])
            rec = cls(
                settings=settings,
                seed=_int(doc["seed"]),
                moves=moves,
                won=_bool(doc["won"]),
                score=_int(doc["score"]),
                frames=_int(doc["frames"]),
                edition=str(doc["edition"]),
                version=str(doc["version"]),
            )
        except (KeyError, TypeError, ValueError) as exc:
            raise ReplayError(EDITED, f"bad field ({exc})") from None
        rec.check()
        return rec

    def check(self, max_frames: int = MAX_FRAMES) -> None:
        """ReplayError(EDITED) naming the first field out of its limits or inconsistent."""
        s = self.settings
        problems = [
            (not REPLAY_ATOMS.contains(s.n_atoms), f"settings.n_atoms must be {ATOMS_SPAN}"),
            (not REPLAY_RADIUS.contains(s.radius), f"settings.radius must be {RADIUS_SPAN}"),
            (s.escape not in ("rim", "knife"), "settings.escape must be rim or knife"),
            (not 0.0 < s.tc_exponent <= 2.0, "settings.tc_exponent must be in (0, 2]"),
            (not 0 <= self.seed <= SEED_PORTABLE_MAX, "seed must be 0..2^53-1"),
            (self.edition not in EDITIONS, "edition must be desktop or web"),
            (any(n < 1 for _, n in self.moves), "moves: each run needs frames >= 1"),
            (
                any(not HEIGHT_MIN <= h <= HEIGHT_MAX for h, _ in self.moves),
                f"moves: heights must be {HEIGHT_MIN:g}..{HEIGHT_MAX:g}",
            ),
            (self.n_frames > max_frames, f"moves: at most {max_frames} frames"),
            (self.frames != self.n_frames, "frames must equal the moves' frames"),
            (not 0 <= self.score <= s.n_atoms, "score must be 0..n_atoms"),
            (not self.won and self.score != 0, "score must be 0 without a win"),
        ]
        for bad, message in problems:
            if bad:
                raise ReplayError(EDITED, message)


def _num(x: object) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
        raise ValueError(f"{x!r} is not a finite number")
    return float(x)


def _int(x: object) -> int:
    if isinstance(x, bool) or not isinstance(x, int):
        raise ValueError(f"{x!r} is not an integer")
    return x


def _bool(x: object) -> bool:
    if not isinstance(x, bool):
        raise ValueError(f"{x!r} is not true/false")
    return x


# -- codes -----------------------------------------------------------------------------------


def checksum(payload: str) -> str:
    """The code's last part: the payload's CRC-32, 8 hex digits."""
    return f"{zlib.crc32(payload.encode('ascii')) & 0xFFFFFFFF:08x}"


def encode(rec: Recording) -> str:
    """The replay code of a recording: EC1.<base64url(zlib(json))>.<crc32 hex>."""
    text = json.dumps(rec.to_json(), separators=(",", ":"), sort_keys=True)
    packed = base64.urlsafe_b64encode(zlib.compress(text.encode("utf-8"), 9))
    payload = packed.decode("ascii").rstrip("=")
    return f"{CODE_PREFIX}.{payload}.{checksum(payload)}"


def decode(code: str) -> Recording:
    """The recording of a replay code; ReplayError with the reason it is not a valid one."""
    code = code.strip()
    if len(code) > MAX_CODE_CHARS:
        raise ReplayError(DAMAGED, f"longer than {MAX_CODE_CHARS} characters")
    parts = code.split(".")
    if len(parts) != 3:
        raise ReplayError(DAMAGED, "not of the form EC1.<payload>.<checksum>")
    prefix, payload, crc = parts
    if prefix != CODE_PREFIX:
        if prefix.startswith("EC") and prefix[2:].isdigit():
            raise ReplayError(OTHER_VERSION, f"code version {prefix}")
        raise ReplayError(DAMAGED, "does not start with EC1.")
    if crc != checksum(payload):
        raise ReplayError(DAMAGED, "checksum does not match")
    try:
        raw = base64.urlsafe_b64decode(payload + "=" * (-len(payload) % 4))
        text = zlib.decompress(raw).decode("utf-8")
        doc = json.loads(text)
    except (binascii.Error, zlib.error, UnicodeDecodeError, ValueError) as exc:
        raise ReplayError(DAMAGED, f"cannot unpack ({exc})") from None
    return Recording.from_json(doc)


# -- recording and verifying -----------------------------------------------------------------


@dataclass
class Recorder:
    """Who played: the settings, seed and edition of a game whose moves the core records
    (the held height of each whole frame up to the win: Simulation.moves, core/play.c)."""

    settings: Settings
    seed: int
    edition: str = "desktop"

    def finish(self, game: Game) -> Recording:
        """The game's recording so far: its moves, and its win and score if won."""
        moves = tuple((float(h), int(n)) for h, n in game.sim.moves())
        return Recording(
            settings=self.settings,
            seed=self.seed,
            moves=moves,
            won=game.won,
            score=int(game.score or 0) if game.won else 0,
            frames=sum(n for _, n in moves),
            edition=self.edition,
        )


@dataclass(frozen=True)
class Verdict:
    """What a replay gave: won, score (atoms at the win, else 0), frames played."""

    won: bool
    score: int
    frames: int


def replay(rec: Recording, engine: str = "auto") -> Verdict:
    """Play the recording headless with the game's rules: each frame hold its height and
    advance one whole frame; stop at the win or at the end of the moves (`Simulation.replay`:
    in one call to the compiled core where it is installed)."""
    game = Game(rec.settings.game_config(rec.seed, engine))
    game.toggle_pause()
    moves = [(clamp_height(h), n) for h, n in rec.moves]  # as Game.set_trap_height clamps
    frames = game.sim.replay(moves, min(rec.n_frames, 2**31 - 1))
    score = game.sim.score
    return Verdict(score is not None, score or 0, frames)


def verify(rec: Recording, engine: str = "auto") -> Verdict:
    """The replayed result if it is the one claimed, else ReplayError(WRONG_SCORE)."""
    rec.check()
    return check_claim(rec, replay(rec, engine))


def check_claim(rec: Recording, got: Verdict) -> Verdict:
    """The replayed result `got` if it is the one the recording claims, else
    ReplayError(WRONG_SCORE)."""
    if (got.won, got.score, got.frames) != (rec.won, rec.score, rec.frames):
        raise ReplayError(
            WRONG_SCORE,
            f"claimed won={rec.won} score={rec.score} frames={rec.frames}, "
            f"replayed won={got.won} score={got.score} frames={got.frames}",
        )
    return got


def record_autopilot(
    strategy_spec: str, settings: Settings, seed: int, budget: int = 1800, engine: str = "auto"
) -> Recording:
    """A recording of an autopilot strategy playing one game headless (tests, benchmarks)."""
    from evapcool.game.autopilot import load_strategy, read

    control = load_strategy(strategy_spec).controller()
    game = Game(settings.game_config(seed, engine))
    game.toggle_pause()
    for _ in range(budget):
        game.set_trap_height(clamp_height(control(read(game.sim, mass=1.0))))
        game.run_frames(1)
        if game.won or game.sim.n_trapped == 0:
            break
    return Recorder(settings, seed).finish(game)
