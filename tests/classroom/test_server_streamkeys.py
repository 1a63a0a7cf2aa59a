"""Issue 46: keys checked for the life of an event stream: after `class admin relink`
(another process), a projector stream opened with the old key is closed and never gets
the next shown replay's code; one opened with the new key gets it."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from classhelp import SEED, SETTINGS, SRC, Server, code, start_server


@pytest.fixture
def department(store_at: Path | str) -> Iterator[Server]:
    running = start_server(store_at, extra=("--department",))
    yield running
    running.stop()


def _bearer(token: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {token}"}


def _relink(server: Server, lecturer: int) -> str:
    """`evapcool class admin relink` in a process of its own; the new token."""
    env = {**os.environ, "PYTHONPATH": str(SRC), "LANGUAGE": "en"}
    where = ["--db", str(server.data)]
    cmd = [sys.executable, "-m", "evapcool", "class", "admin", *where, "relink", str(lecturer)]
    out = subprocess.run(cmd, capture_output=True, text=True, env=env, check=True).stdout
    found = re.search(r"token=(\S+)", out)
    assert found, out
    return found.group(1)


def _class_of(server: Server, token: str) -> dict[str, str]:
    answer = httpx.get(server.base + "/api/classes", headers=_bearer(token))
    assert answer.status_code == 200, answer.text
    doc: dict[str, str] = answer.json()["classes"][0]
    return doc


def test_a_relinked_key_stream_closes_and_leaks_nothing(department: Server) -> None:
    made = httpx.post(
        department.base + "/api/admin/lecturers", json={"name": "Ada"}, headers=department.lecturer
    ).json()
    old = made["token"]
    httpx.post(department.base + "/api/classes", json={"name": "Optics"}, headers=_bearer(old))
    room = _class_of(department, old)
    base = f"{department.base}/c/{room['code']}/"
    rules = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "escape": SETTINGS.escape}
    opened = httpx.post(base + "api/challenge", json={**rules, "seed": SEED}, headers=_bearer(old))
    challenge = opened.json()["id"]
    student = httpx.post(base + "api/join", json={"name": "Bo"}).json()["token"]
    game = code(SEED, 1)
    sent = httpx.post(
        base + "api/submit",
        json={"challenge": challenge, "code": game},
        headers=_bearer(student),
        timeout=60,
    )
    assert sent.status_code == 200, sent.text
    entry = sent.json()["entry"]
    with httpx.Client(timeout=httpx.Timeout(10, read=60)) as client:
        stale = room["projector"].replace("/projector", "/api/stream")
        with client.stream("GET", department.base + stale) as s:
            lines = s.iter_lines()
            assert next(line for line in lines if line.startswith("data: "))
            new = _relink(department, made["id"])
            shown = httpx.post(base + "api/show", json={"entry": entry}, headers=_bearer(new))
            assert shown.status_code == 200, shown.text
            after = []
            for line in lines:  # ends once the stream is closed
                if line.startswith("data: "):
                    after.append(line)
                    if game in line:
                        break
    assert not any(game in line for line in after), "a stale key's stream got the code"
    # the new key's stream is open and has the replay's code
    fresh = _class_of(department, new)["projector"]
    assert fresh != room["projector"]
    with (
        httpx.Client(timeout=httpx.Timeout(10, read=60)) as client,
        client.stream("GET", department.base + fresh.replace("/projector", "/api/stream")) as s,
    ):
        first = next(line for line in s.iter_lines() if line.startswith("data: "))
    assert game in first
