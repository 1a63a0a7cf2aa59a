"""`evapcool verify`: ranks codes by verified score, rejects each bad one with its reason."""

from __future__ import annotations

import dataclasses
import functools
import json
from pathlib import Path

import pytest

from evapcool.cli import main
from evapcool.game import replay as r


@functools.cache
def recordings() -> tuple[r.Recording, r.Recording]:
    settings = r.Settings()
    return (
        r.record_autopilot("demo", settings, seed=1),
        r.record_autopilot("demo", settings, seed=2),
    )


def test_ranks_codes_and_rejects_forged(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    a, b = recordings()
    forged = dataclasses.replace(a, score=a.score + 1)
    damaged = r.encode(a)[:-1] + ("0" if r.encode(a)[-1] != "0" else "1")
    listing = tmp_path / "codes.txt"
    listing.write_text(f"{r.encode(b)}\n\n{r.encode(forged)}\n")
    recording_file = tmp_path / "rec.json"
    recording_file.write_text(json.dumps(a.to_json()))
    status = main(["verify", r.encode(a), str(listing), str(recording_file), damaged])
    out = capsys.readouterr().out.splitlines()
    assert status == 1
    verified = [ln for ln in out if not ln.lstrip().startswith("-")]
    rejected = [ln for ln in out if ln.lstrip().startswith("-")]
    assert len(verified) == 3 and len(rejected) == 2
    scores = [int(ln.split(".", 1)[1].split()[0]) for ln in verified]
    assert scores == sorted(scores, reverse=True)
    assert sorted(scores) == sorted([a.score, a.score, b.score])
    assert any(r.WRONG_SCORE in ln and "codes.txt:3" in ln for ln in rejected)
    assert any(r.DAMAGED in ln for ln in rejected)


def test_all_verified_exits_zero(capsys: pytest.CaptureFixture[str]) -> None:
    a, _ = recordings()
    assert main(["verify", r.encode(a)]) == 0
    assert f"{a.score} atoms" in capsys.readouterr().out


def test_bad_usage_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["verify"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "evapcool verify: error:" in err
