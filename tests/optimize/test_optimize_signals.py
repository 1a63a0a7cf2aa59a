"""SIGTERM during the optimizer's validation: one line, exit 130, the study kept (issue 25.5)."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys

import pytest

pytest.importorskip("optuna")
pytest.importorskip("distributed")

STUDY = ["--budget", "300", "--seeds", "2", "--chunk", "100", "--sampler-seed", "1",
         "--family", "linear", "--workers", "1"]  # fmt: skip


def _optimize(tmp_path, *args: str) -> subprocess.Popen[str]:
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    return subprocess.Popen(
        [sys.executable, "-m", "evapcool", "optimize", *args],
        cwd=tmp_path,
        stderr=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
        env=env,
    )


def _complete_trials(db) -> int:
    with sqlite3.connect(db) as con:
        return con.execute("SELECT count(*) FROM trials WHERE state = 'COMPLETE'").fetchone()[0]


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_stop_in_the_validation_says_one_line_and_keeps_the_study(tmp_path, sig) -> None:
    first = _optimize(tmp_path, "--study", "s.db", "--trials", "4", "--validate", "0", *STUDY)
    _, err = first.communicate(timeout=600)
    assert first.returncode == 0, err
    assert _complete_trials(tmp_path / "s.db") == 4
    proc = _optimize(tmp_path, "--resume", "s.db", "--trials", "0", "--validate", "2000",
                     "--finalists", "2", "--workers", "1")  # fmt: skip
    assert proc.stderr is not None
    for line in proc.stderr:
        if "re-ranking" in line or "validating" in line:
            break
    proc.send_signal(sig)
    rest = proc.stderr.read()
    assert proc.wait(timeout=300) == 130, rest
    lines = [ln for ln in rest.splitlines() if "interrupted" in ln]
    assert len(lines) == 1 and "--resume s.db" in lines[0], rest
    assert "Traceback" not in rest
    assert _complete_trials(tmp_path / "s.db") == 4
