"""Issue 46: the copy check across the whole server: a game already verified from the same
start (seed and settings) is refused in any other class and any other challenge, whoever
sends it; the same student resending in the same challenge is not a copy."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from classhelp import SEED, SETTINGS, Server, code, start_server

from evapcool.classroom.storage.sqlite import Store


@pytest.fixture
def department(store_at: Path | str) -> Iterator[Server]:
    running = start_server(store_at, extra=("--department",))
    yield running
    running.stop()


def _bearer(token: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {token}"}


def _class(server: Server, lecturer: str, name: str) -> str:
    made = httpx.post(server.base + "/api/classes", json={"name": name}, headers=_bearer(lecturer))
    assert made.status_code == 200, made.text
    return f"{server.base}/c/{made.json()['code']}/"


def _open(base: str, lecturer: str, seed: int = SEED) -> int:
    rules = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "escape": SETTINGS.escape}
    answer = httpx.post(
        base + "api/challenge", json={**rules, "seed": seed}, headers=_bearer(lecturer)
    )
    assert answer.status_code == 200, answer.text
    return int(answer.json()["id"])


def _send(base: str, student: str, challenge: int, game: str) -> httpx.Response:
    body = {"challenge": challenge, "code": game}
    return httpx.post(base + "api/submit", json=body, headers=_bearer(student), timeout=60)


def _student(base: str, name: str) -> str:
    return str(httpx.post(base + "api/join", json={"name": name}).json()["token"])


def test_a_game_from_another_class_or_challenge_is_a_copy(department: Server) -> None:
    lecturers = []
    for name in ("Ada", "Max"):
        made = httpx.post(
            department.base + "/api/admin/lecturers",
            json={"name": name},
            headers=department.lecturer,
        )
        lecturers.append(made.json()["token"])
    x, y = _class(department, lecturers[0], "X"), _class(department, lecturers[1], "Y")
    in_x, in_y = _open(x, lecturers[0]), _open(y, lecturers[1])
    ann, bob = _student(x, "Ann"), _student(y, "Bob")
    game = code(SEED, 1)
    assert _send(x, ann, in_x, game).status_code == 200
    assert _send(x, ann, in_x, game).status_code == 200  # her own resend: not a copy
    closed = httpx.post(x + "api/challenge/close", headers=_bearer(lecturers[0]))
    assert closed.status_code == 200, closed.text
    copied = _send(y, bob, in_y, game)
    assert copied.status_code == 422, copied.text
    assert copied.json()["error"]["field"] == "code"
    # a new round of X on the same start: Ann's own old game is not played in it
    again = _open(x, lecturers[0])
    refused = _send(x, ann, again, game)
    assert refused.status_code == 422 and refused.json()["error"]["field"] == "code"
    # an honest game of Bob's still counts
    assert _send(y, bob, in_y, code(SEED, 2)).status_code == 200


def test_the_copy_lookup_uses_an_index(tmp_path: Path) -> None:
    store = Store(tmp_path / "c.sqlite")
    try:
        from evapcool.classroom.storage.copies import COPY_QUERY

        plan = store._rows("EXPLAIN QUERY PLAN " + COPY_QUERY, (1, "m" * 64, "t"))
        text = " ".join(str(row[-1]) for row in plan)
        assert "entry_moves_any" in text and "SCAN e" not in text, text
    finally:
        store.close()
