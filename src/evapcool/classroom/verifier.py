"""A submitted game checked in a worker process: decoded, matched to the challenge, replayed.

Runs in a ProcessPoolExecutor, off the server's event loop. Its answers are plain dicts
(picklable): the verified result, or the refused field with a catalog key and arguments.
"""

from __future__ import annotations

import base64
import binascii
import hashlib
import json
import math
import operator
import re
import zlib
from typing import Any

from evapcool.classroom.depth import MAX_DEPTH, too_deep
from evapcool.game.path import game_path
from evapcool.game.replay import (
    CODE_PREFIX,
    DAMAGED,
    EDITED,
    MAX_CODE_CHARS,
    MAX_FRAMES,
    WRONG_SCORE,
    Recording,
    ReplayError,
    Settings,
    Verdict,
    check_claim,
    checksum,
    decode,
    encode,
    record_autopilot,
    replay,
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
#: What a replay code is made of (URL-safe base64, dots): checked before anything else.
CODE_CHARS = re.compile(r"[A-Za-z0-9_.-]+")
#: Inflated bytes a recording may need: its fields, plus one [height, frames] run a frame
#: at most (a height's repr is at most 18 characters within HEIGHT_MIN..HEIGHT_MAX).
HEADER_BYTES = 1024
RUN_BYTES = 32
#: The default frame limit: this many times the demo autopilot's game on the challenge
#: (people play slower than it), at least FLOOR_FRAMES; MAX_FRAMES if it does not win.
MARGIN = 4
FLOOR_FRAMES = 3600


def warm() -> None:
    """Play a tiny game once in this worker (imports, first allocations) before real games."""
    rec = Recording(Settings(n_atoms=8), 1, ((450.0, 2),), won=False, score=0, frames=2)
    replay(rec, ENGINE)


def refusal(field: str, key: str, **args: Any) -> dict[str, Any]:
    """A refused submission: the field, and the catalog key and arguments saying why."""
    return {"error": {"field": field, "key": key, "args": args}}


def code_chars_ok(code: str) -> bool:
    """Whether a code is short enough and only of the characters a code has (ASCII)."""
    text = code.strip()
    return len(text) <= MAX_CODE_CHARS and CODE_CHARS.fullmatch(text) is not None


#: Bytes the longest game a recording may hold (MAX_FRAMES) can inflate to, about 1.2 MB:
#: a longer code is no game. (Longer than a challenge allows is told apart, as "moves".)
INFLATE_LIMIT = HEADER_BYTES + RUN_BYTES * MAX_FRAMES


def checked_decode(code: str) -> tuple[Recording, object]:
    """`decode`, once the code is known to inflate within INFLATE_LIMIT and to nest no
    deeper than a recording: ReplayError(DAMAGED) otherwise, before decode unpacks it.
    Also the code's JSON document when it was read here (None when `decode` read it)."""
    parts = code.strip().split(".")
    if len(parts) == 3 and parts[0] == CODE_PREFIX:
        try:
            raw = base64.urlsafe_b64decode(parts[1] + "=" * (-len(parts[1]) % 4))
            inflater = zlib.decompressobj()
            text = inflater.decompress(raw, INFLATE_LIMIT + 1)
        except (binascii.Error, zlib.error, ValueError):
            return decode(code), None  # its own reason (damaged)
        if len(text) > INFLATE_LIMIT or inflater.unconsumed_tail:
            raise ReplayError(DAMAGED, f"inflates past {INFLATE_LIMIT} bytes")
        doc = _parsed_within_depth(text)
        if doc is not None and _as_decode_reads(code, parts, inflater):
            return Recording.from_json(doc), doc
    return decode(code), None


def _parsed_within_depth(text: bytes) -> object | None:
    """The parsed JSON if it is UTF-8 JSON (else None: decode says why), ReplayError if
    it nests deeper than a recording may (or than the parser can)."""
    try:
        doc: object = json.loads(text.decode("utf-8"))
    except RecursionError:
        doc = None
        deep = True
    except ValueError:  # UnicodeDecodeError is one
        return None
    else:
        deep = too_deep(doc)
    if deep:
        raise ReplayError(DAMAGED, f"nested deeper than {MAX_DEPTH}")
    return doc


def _as_decode_reads(code: str, parts: list[str], inflater: Any) -> bool:
    """Whether `decode` would read the same text: not too long, its checksum right, one
    whole zlib stream and nothing after it (else decode reads it and says why not)."""
    whole = inflater.eof and not inflater.unused_data
    return whole and len(code.strip()) <= MAX_CODE_CHARS and parts[2] == checksum(parts[1])


def moves_key(rec: Recording, frames: int) -> str:
    """The moves up to frame `frames` (the win), whatever runs or fields carry them: a
    copy of a game, re-encoded, split into other runs or of another edition, has the same."""
    heights = [h for h, _ in rec.moves]
    if frames >= rec.n_frames and not any(map(operator.eq, heights, heights[1:])):
        return _digest(rec.moves)  # its own runs (as a recorder writes them), all played
    runs: list[list[float]] = []
    left = frames
    for height, n in rec.moves:
        take = min(n, left)
        if take <= 0:
            break
        if runs and runs[-1][0] == height:
            runs[-1][1] += take
        else:
            runs.append([height, take])
        left -= take
    return _digest(runs)


def _digest(runs: Any) -> str:
    text = json.dumps(runs, separators=(",", ":"))
    return hashlib.sha256(text.encode("ascii")).hexdigest()


def reference_frames(settings: dict[str, Any], seed: int) -> int:
    """The default frame limit of a challenge: MARGIN x the demo autopilot's winning game
    on it (FLOOR_FRAMES at least, MAX_FRAMES at most or if it does not win)."""
    budget = MAX_FRAMES // MARGIN
    rec = record_autopilot("demo", Settings(**settings), seed, budget=budget, engine=ENGINE)
    if not rec.won:
        return MAX_FRAMES
    return min(MAX_FRAMES, max(FLOOR_FRAMES, math.ceil(MARGIN * rec.frames)))


def _recording(item: object, how: str) -> tuple[Recording, str | None]:
    """The recording of a code or a JSON recording, and the code as kept: the code sent
    when it holds the recording's fields and nothing else (whichever edition packed it, it
    unpacks to the same game: no need to pack it again), else None. ReplayError if it is
    not one."""
    if how == "code" and isinstance(item, str):
        rec, doc = checked_decode(item)
        return rec, item.strip() if doc == rec.to_json() else None
    if how == "recording" and isinstance(item, dict):
        return Recording.from_json(item), None
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
    """The verified result {score, frames, edition, code, moves, path}, or a refusal
    (`refusal`). path: the game's path (game/path.py) as JSON text, computed here once so
    the debrief draws every game without replaying any.

    A game that does not claim a win is refused before it is replayed, unless the
    challenge takes lost games (`lost`).
    """
    try:
        rec, kept = _recording(item, how)
        wrong = _mismatch(rec, challenge)
        if wrong is not None:
            return wrong
        if not rec.won and not challenge.get("lost"):
            return refusal("won", "class.error.not_won")
        # from_json has checked the recording's fields and limits. One replay gives the
        # result and the path (game_path plays the frames verify would).
        path = game_path(rec, engine=ENGINE)
        got = check_claim(rec, Verdict(path.won, path.score, path.frames))
    except ReplayError as exc:
        return _replay_refusal(exc, how)
    return {
        "score": got.score,
        "frames": got.frames,
        "edition": rec.edition,
        "code": kept or encode(rec),
        "moves": moves_key(rec, got.frames),
        "path": json.dumps(path.to_json(), separators=(",", ":")),
    }
