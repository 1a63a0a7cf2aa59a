"""A submitted game checked in a worker process: decoded, matched to the challenge, replayed.

Runs in a ProcessPoolExecutor, off the server's event loop. Its answers are plain dicts
(picklable): the verified result, or the refused field with a catalog key and arguments.
"""

from __future__ import annotations

from typing import Any

from evapcool.game.replay import (
    DAMAGED,
    EDITED,
    WRONG_SCORE,
    Recording,
    ReplayError,
    Settings,
    decode,
    encode,
    replay,
    verify,
)

#: The compiled core where it is built, else the reference engine (the same results).
ENGINE = "auto"
#: Fields a ReplayError(EDITED) message may start with (Recording.check's wording).
EDITED_FIELDS = (
    "settings.n_atoms",
    "settings.radius",
    "settings.escape",
    "settings.tc_exponent",
    "seed",
    "edition",
    "moves",
    "frames",
    "score",
)
SETTING_NAMES = ("n_atoms", "radius", "escape", "tc_exponent")


def warm() -> None:
    """Play a tiny game once in this worker (imports, first allocations) before real games."""
    rec = Recording(Settings(n_atoms=8), 1, ((450.0, 2),), won=False, score=0, frames=2)
    replay(rec, ENGINE)


def refusal(field: str, key: str, **args: Any) -> dict[str, Any]:
    """A refused submission: the field, and the catalog key and arguments saying why."""
    return {"error": {"field": field, "key": key, "args": args}}


def _recording(item: object, how: str) -> Recording:
    """The recording of a code or a JSON recording; ReplayError if it is not one."""
    if how == "code" and isinstance(item, str):
        return decode(item)
    if how == "recording" and isinstance(item, dict):
        return Recording.from_json(item)
    raise ReplayError(DAMAGED, f"{how} of the wrong type")


def _replay_refusal(exc: ReplayError, how: str) -> dict[str, Any]:
    """The refusal of a code that does not decode, or of a forged result."""
    if exc.reason == WRONG_SCORE:
        return refusal("score", "class.error.forged", detail=exc.detail)
    field = how
    if exc.reason == EDITED:
        field = next((f for f in EDITED_FIELDS if exc.detail.startswith(f)), how)
    return refusal(field, "class.error.bad_code", reason=exc.reason, detail=exc.detail)


def _mismatch(rec: Recording, challenge: dict[str, Any]) -> dict[str, Any] | None:
    """The refusal of a game played with other settings, seed or too many frames."""
    for name in SETTING_NAMES:
        got, wanted = getattr(rec.settings, name), challenge["settings"][name]
        if got != wanted:
            return refusal(f"settings.{name}", "class.error.setting", got=got, wanted=wanted)
    if rec.seed != challenge["seed"]:
        return refusal("seed", "class.error.setting", got=rec.seed, wanted=challenge["seed"])
    if rec.n_frames > challenge["max_frames"]:
        return refusal("moves", "class.error.too_long", n=challenge["max_frames"])
    return None


def check_submission(item: object, how: str, challenge: dict[str, Any]) -> dict[str, Any]:
    """The verified result {score, frames, edition, code}, or a refusal (see `refusal`)."""
    try:
        rec = _recording(item, how)
        wrong = _mismatch(rec, challenge)
        if wrong is not None:
            return wrong
        got = verify(rec, ENGINE)
    except ReplayError as exc:
        return _replay_refusal(exc, how)
    return {"score": got.score, "frames": got.frames, "edition": rec.edition, "code": encode(rec)}
