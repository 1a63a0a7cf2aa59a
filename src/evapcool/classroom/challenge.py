"""A challenge's parameters from the lecturer's JSON, checked field by field, and its API form."""

from __future__ import annotations

import math
import secrets
import time
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import Any

from evapcool.classroom.errors import RefusedError
from evapcool.game.replay import MAX_FRAMES, Settings
from evapcool.limits import REPLAY_ATOMS, REPLAY_RADIUS, SEED

#: Seeds drawn for "random": small enough to read out in class.
RANDOM_SEED_MAX = 1_000_000
MAX_MINUTES = 24 * 60
MAX_ATTEMPTS = 1000


@dataclass(frozen=True)
class Field:
    """One parameter: its range, whether a whole number, whether it may be left out."""

    low: float
    high: float
    integer: bool
    optional: bool

    def read(self, name: str, value: object) -> float | int | None:
        """The value, or RefusedError(400) naming the field."""
        if value is None or value == "":
            if self.optional:
                return None
            raise RefusedError(400, name, "class.error.value", allowed=self.allowed())
        number = value if isinstance(value, (int, float)) and not isinstance(value, bool) else None
        if number is None or not math.isfinite(number) or not self.low <= number <= self.high:
            raise RefusedError(400, name, "class.error.value", allowed=self.allowed())
        if self.integer and not float(number).is_integer():
            raise RefusedError(400, name, "class.error.value", allowed=self.allowed())
        return int(number) if self.integer else float(number)

    def allowed(self) -> str:
        return (
            f"{self.low:g}..{self.high:g}"
            if not self.integer
            else f"{self.low:.0f}..{self.high:.0f}"
        )


FIELDS = {
    "n_atoms": Field(REPLAY_ATOMS.low, REPLAY_ATOMS.high, True, False),
    "radius": Field(REPLAY_RADIUS.low, REPLAY_RADIUS.high, False, False),
    "tc_exponent": Field(1e-9, 2.0, False, True),
    "seed": Field(SEED.low, SEED.high, True, True),
    "minutes": Field(0.1, MAX_MINUTES, False, True),
    "attempts": Field(1, MAX_ATTEMPTS, True, True),
    "max_frames": Field(1, MAX_FRAMES, True, True),
}


@dataclass(frozen=True)
class NewChallenge:
    """What opening a challenge stores."""

    settings: dict[str, Any]
    seed: int
    #: None: the server sets it from a real game on the challenge (verifier.reference_frames).
    max_frames: int | None
    attempts: int | None
    closes_at: float | None
    #: Whether games that do not win are taken (ranked with 0 atoms).
    lost: bool = False


def parse_challenge(doc: dict[str, Any], now: float | None = None) -> NewChallenge:
    """The challenge asked for; RefusedError(400) naming the first bad field."""
    got = {name: f.read(name, doc.get(name)) for name, f in FIELDS.items()}
    escape = doc.get("escape", "rim")
    if escape not in ("rim", "knife"):
        raise RefusedError(400, "escape", "class.error.value", allowed="rim, knife")
    lost = doc.get("lost", False)
    if not isinstance(lost, bool):
        raise RefusedError(400, "lost", "class.error.value", allowed="true, false")
    tc = got["tc_exponent"] if got["tc_exponent"] is not None else Settings().tc_exponent
    settings = {
        "n_atoms": got["n_atoms"],
        "radius": got["radius"],
        "escape": escape,
        "tc_exponent": tc,
    }
    seed = got["seed"] if got["seed"] is not None else secrets.randbelow(RANDOM_SEED_MAX)
    minutes = got["minutes"]
    start = time.time() if now is None else now
    return NewChallenge(
        settings=settings,
        seed=int(seed),
        max_frames=None if got["max_frames"] is None else int(got["max_frames"]),
        attempts=None if got["attempts"] is None else int(got["attempts"]),
        closes_at=None if minutes is None else start + 60.0 * minutes,
        lost=lost,
    )


def iso(ts: float | None) -> str | None:
    """Seconds since the epoch as ISO 8601 in UTC (None stays None)."""
    if ts is None:
        return None
    return datetime.fromtimestamp(ts, timezone.utc).isoformat().replace("+00:00", "Z")


def challenge_doc(row: dict[str, Any]) -> dict[str, Any]:
    """The API form of a stored challenge."""
    return {
        "id": row["id"],
        "settings": row["settings"],
        "seed": row["seed"],
        "max_frames": row["max_frames"],
        "attempts": row["attempts"],
        "closes_at": iso(row["closes_at"]),
        "lost": bool(row.get("lost")),
    }
