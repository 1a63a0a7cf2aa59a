"""`evapcool class` starting (issue 33): the lecturer's link survives a restart, the links
come once the server answers, $EVAPCOOL_DATA_DIR is honoured, `evapcool[all]` has it."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import httpx
import pytest
from classhelp import SRC, free_port, lecturer_line, start_server

ROOT = Path(__file__).resolve().parents[2]


def entries(base: str, token: str) -> int:
    headers = {"Authorization": f"Bearer {token}"}
    return httpx.get(base + "/api/entries", headers=headers).status_code


def test_the_lecturers_link_survives_a_restart_and_is_never_stored(tmp_path: Path) -> None:
    data = tmp_path / "class.sqlite"
    first = start_server(data)
    token = first.token
    first.stop()
    stored = b"".join(p.read_bytes() for p in tmp_path.iterdir() if p.is_file())
    assert token.encode() not in stored
    again = start_server(data, token=token)
    try:
        assert entries(again.base, token) == 200
    finally:
        again.stop()
    fresh = start_server(data, extra=("--new-link",))
    try:
        assert fresh.token != token
        assert entries(fresh.base, token) == 403 and entries(fresh.base, fresh.token) == 200
    finally:
        fresh.stop()


def test_links_printed_once_it_answers_in_the_data_dir(tmp_path: Path) -> None:
    port = free_port()
    env = {
        **os.environ,
        "PYTHONPATH": str(SRC),
        "LANG": "C.UTF-8",
        "LANGUAGE": "en",
        "EVAPCOOL_DATA_DIR": str(tmp_path),
    }
    cmd = [sys.executable, "-m", "evapcool", "class", "--port", str(port), "--workers", "1"]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, text=True, env=env)
    try:
        assert proc.stdout is not None
        first = lecturer_line(proc.stdout)
        # Printed only after start-up: its verifying worker is already running.
        workers = subprocess.run(
            ["ps", "--ppid", str(proc.pid), "-o", "pid="], capture_output=True, text=True
        ).stdout.split()
        assert "token=" in first and workers, (first, workers)
        assert httpx.get(f"http://127.0.0.1:{port}/api/leaderboard", timeout=30).status_code == 200
        lines = [proc.stdout.readline() for _ in range(3)]
        assert str(tmp_path / "class.sqlite") in lines[1]
        assert (tmp_path / "class.sqlite").is_file()
    finally:
        proc.terminate()
        proc.wait(30)
        if proc.stdout:
            proc.stdout.close()


def test_all_includes_the_class_server() -> None:
    tomllib = pytest.importorskip("tomllib")  # Python 3.11+
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert any("class" in spec for spec in project["optional-dependencies"]["all"])
