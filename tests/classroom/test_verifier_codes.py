"""The server's reading of a code (issue 47's whole check): read once, it gives what
`decode` gives for every code, good or damaged; a code holding exactly its recording is kept
as it was sent (whichever edition packed it), any other is packed again."""

from __future__ import annotations

import base64
import json
import zlib

import pytest
from classhelp import SEED, variant
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.classroom.verifier import SETTING_NAMES, check_submission, checked_decode
from evapcool.game.replay import CODE_PREFIX, Recording, ReplayError, checksum, decode, encode


def packed(text: bytes, level: int = 9, tail: bytes = b"") -> str:
    """A code of any bytes with a right checksum (what a forger or another packer makes)."""
    payload = base64.urlsafe_b64encode(zlib.compress(text, level) + tail).decode().rstrip("=")
    return f"{CODE_PREFIX}.{payload}.{checksum(payload)}"


def page_like(rec: Recording) -> str:
    """As the page writes it: JSON.stringify's numbers (450, not 450.0), fields unsorted,
    deflated at zlib's default level."""

    def js(x: object) -> object:
        return int(x) if isinstance(x, float) and x.is_integer() else x

    doc = rec.to_json()
    doc["moves"] = [[js(h), n] for h, n in doc["moves"]]
    doc["settings"] = {k: js(v) for k, v in doc["settings"].items()}
    return packed(json.dumps(doc, separators=(",", ":")).encode(), level=6)


def outcome(read: object, code: str) -> object:
    try:
        got = read(code)  # type: ignore[operator]
    except ReplayError as exc:
        return ("refused", exc.reason)
    return got[0] if isinstance(got, tuple) else got


def damaged(rec: Recording, kind: int, cut: int) -> str:
    """One of the ways a code is damaged or forged, around a real recording."""
    text = json.dumps(rec.to_json()).encode()
    good = encode(rec)
    prefix, payload, crc = good.split(".")
    raw = zlib.compress(text, 9)
    return [
        good,
        f"{prefix}.{payload}.{'0' * 8}",  # wrong checksum
        packed(text[: max(1, cut % len(text))]),  # text cut short
        f"{prefix}.{payload[: max(4, cut % len(payload))]}.{crc}",  # payload cut short
        packed(b"\xff\xfe" + text),  # not UTF-8
        packed(text, tail=b"trailing"),  # bytes after the stream
        _code_of_raw(raw[: max(2, cut % len(raw))]),  # the stream itself cut short
        packed(text.replace(b'"won"', b'"extra": 1, "won"')),  # a field more
        packed(text + b" " * 160_000, level=0),  # longer than a code may be
        "  " + good + "\n",  # blanks around it
        _code_of_raw(raw[:-4]),  # the whole text, the stream's own checksum cut off
    ][kind]


def _code_of_raw(raw: bytes) -> str:
    payload = base64.urlsafe_b64encode(raw).decode().rstrip("=")
    return f"{CODE_PREFIX}.{payload}.{checksum(payload)}"


@settings(max_examples=60, deadline=None)
@given(kind=st.integers(0, 10), cut=st.integers(0, 10**6), k=st.integers(0, 3))
def test_the_server_reads_every_code_as_decode_does(kind: int, cut: int, k: int) -> None:
    code = damaged(variant(SEED, k), kind, cut)
    assert outcome(checked_decode, code) == outcome(decode, code)


@pytest.mark.parametrize(
    ("make", "kept"),
    [
        (encode, True),
        (page_like, True),
        (lambda rec: packed(json.dumps({**rec.to_json(), "note": "hi"}).encode()), False),
    ],
    ids=["desktop", "page", "a field more"],
)
def test_a_code_is_kept_as_sent_only_when_it_holds_its_recording_alone(
    make: object, kept: bool
) -> None:
    rec = variant(SEED, 2)
    code = make(rec)  # type: ignore[operator]
    challenge = {
        "settings": {name: getattr(rec.settings, name) for name in SETTING_NAMES},
        "seed": rec.seed,
        "max_frames": rec.n_frames,
    }
    got = check_submission(" " + code + " ", "code", challenge)
    assert got["score"] == rec.score and got["frames"] == rec.frames
    assert got["code"] == (code if kept else encode(rec))
    assert decode(got["code"]) == rec
