"""Issue 46: wrong join codes limited per address (a guesser held back for years per hit),
while the codes an address already reached keep working for its hall."""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from classhelp import Server, start_server

from evapcool.classroom.guessing import WRONG_CODES
from evapcool.classroom.rooms import CODE_ALPHABET, CODE_LENGTH


@pytest.fixture
def department(tmp_path: Path) -> Iterator[Server]:
    running = start_server(tmp_path / "dept.sqlite", extra=("--department",))
    yield running
    running.stop()


def _class(server: Server, lecturer: str, name: str) -> str:
    made = httpx.post(
        server.base + "/api/classes",
        json={"name": name},
        headers={"Authorization": f"Bearer {lecturer}"},
    )
    assert made.status_code == 200, made.text
    return str(made.json()["code"])


def test_wrong_codes_are_limited_per_address(department: Server) -> None:
    made = httpx.post(
        department.base + "/api/admin/lecturers", json={"name": "Ada"}, headers=department.lecturer
    )
    lecturer = made.json()["token"]
    ours, other = _class(department, lecturer, "Ours"), _class(department, lecturer, "Other")
    board = department.base + "/c/{}/api/leaderboard"
    assert httpx.get(board.format(ours)).status_code == 200  # the hall reached its class
    wrong = (
        "".join(t)
        for t in itertools.product(CODE_ALPHABET[:3], repeat=CODE_LENGTH)
        if "".join(t) not in (ours, other)
    )
    statuses = [
        httpx.get(board.format(next(wrong))).status_code for _ in range(int(WRONG_CODES.burst))
    ]
    assert statuses == [404] * int(WRONG_CODES.burst)
    held = httpx.get(board.format(next(wrong)))
    assert held.status_code == 429 and held.json()["error"]["field"] == "code"
    assert int(held.headers["retry-after"]) >= 1
    # a code never reached from here is held back too (a guess cannot tell a hit) ...
    assert httpx.get(board.format(other)).status_code == 429
    assert httpx.get(department.base + "/", params={"code": other}).status_code == 429
    # ... while the hall's own class goes on
    assert httpx.get(board.format(ours)).status_code == 200
    page = httpx.get(department.base + "/", params={"code": ours})
    assert page.status_code == 303 or page.status_code == 200


def test_the_guide_states_the_wrong_code_limit() -> None:
    guide = " ".join(
        (Path(__file__).resolve().parents[2] / "docs" / "class.md").read_text().split()
    )
    burst, every = int(WRONG_CODES.burst), round(1 / WRONG_CODES.per_second)
    assert f"{burst} at once, then one every {every} s" in guide
    per_hit = len(CODE_ALPHABET) ** CODE_LENGTH / 500  # guesses per hit among 500 classes
    years = (per_hit - burst) / (86400 / every) / 365
    assert f"about {years:.1f} years per hit" in guide, years
