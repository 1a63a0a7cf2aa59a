"""Issue 46: numbers in paths, queries and forms by one strict rule (400, never 500); form
bodies bounded as they arrive; an upload cut mid-body ended quietly."""

from __future__ import annotations

import signal
import socket
from collections.abc import Iterator
from pathlib import Path
from urllib.parse import urlsplit

import httpx
import pytest
from classhelp import Server, join, open_challenge, start_server

from evapcool.classroom.session import csrf_token

#: Not ASCII digits, or out of bounds: each 400 naming the parameter.
NOT_NUMBERS = ["%C2%B2", "%E2%91%A0", "%D9%A3", "-1", "+1", "%201", "1.0", "0", "", "9" * 30]


@pytest.fixture
def single(tmp_path: Path) -> Iterator[Server]:
    running = start_server(tmp_path / "class.sqlite")
    yield running
    running.stop()


@pytest.fixture
def department(tmp_path: Path) -> Iterator[Server]:
    running = start_server(tmp_path / "dept.sqlite", extra=("--department",))
    yield running
    running.stop()


def _refused(answer: httpx.Response, status: int, field: str) -> None:
    assert answer.status_code == status, (answer.status_code, answer.text)
    assert answer.json()["error"]["field"] == field, answer.text


def test_a_challenge_number_is_ascii_digits_or_400(single: Server) -> None:
    challenge = open_challenge(single)["id"]
    for path in ("/api/entries", "/api/export.csv"):
        url = f"{single.base}{path}?challenge="
        assert httpx.get(url + str(challenge), headers=single.lecturer).status_code == 200
        _refused(httpx.get(url + "424242", headers=single.lecturer), 404, "challenge")
        for bad in NOT_NUMBERS:
            _refused(httpx.get(url + bad, headers=single.lecturer), 400, "challenge")


def _admin_form(server: Server, **fields: str) -> httpx.Response:
    """The admin page's form as a browser sends it: the link's cookie, the CSRF token."""
    with httpx.Client(base_url=server.base, follow_redirects=True) as browser:
        browser.get("/admin", params={"token": server.token})
        return browser.post("/admin", data={"csrf": csrf_token(server.token), **fields})


def test_the_admin_form_lecturer_number_is_strict(department: Server) -> None:
    made = httpx.post(
        department.base + "/api/admin/lecturers",
        json={"name": "Ada"},
        headers=department.lecturer,
    )
    lecturer = str(made.json()["id"])
    for bad in ("²", "①", "٣", " 1", "1 ", "0x1", "9" * 30):
        answer = _admin_form(department, what="class", name="Sec", lecturer=bad)
        _refused(answer, 400, "lecturer")
    answer = _admin_form(department, what="class", name="Sec", lecturer=lecturer)
    assert answer.status_code == 200 and "Sec" in answer.text


def _raw(server: Server, head: str, body: bytes = b"") -> socket.socket:
    """A connection that sent `head` (CRLF lines) and `body`, left open."""
    where = urlsplit(server.base)
    sock = socket.create_connection((where.hostname, where.port), timeout=30)
    sock.sendall(head.replace("\n", "\r\n").encode() + b"\r\n" + body)
    return sock


def _status(sock: socket.socket) -> int:
    """The status of the answer read from `sock` (its first line)."""
    first = b""
    while b"\r\n" not in first:
        part = sock.recv(4096)
        if not part:
            break
        first += part
    sock.close()
    return int(first.split(b" ")[1])


def test_a_huge_form_is_refused_before_its_upload(department: Server) -> None:
    # Content-Length says 100 MB: 413 after the first 4 KB sent, not after 100 MB.
    head = (
        "POST /lecturer HTTP/1.1\nHost: x\nContent-Type: application/x-www-form-urlencoded\n"
        "Content-Length: 100000000\n"
    )
    assert _status(_raw(department, head, b"name=" + b"a" * 4000)) == 413
    # No length (chunked): 413 as soon as more than the limit arrived.
    head = (
        "POST /admin HTTP/1.1\nHost: x\nContent-Type: application/x-www-form-urlencoded\n"
        "Transfer-Encoding: chunked\n"
    )
    chunk = b"2000\r\n" + b"a" * 0x2000 + b"\r\n"
    assert _status(_raw(department, head, chunk)) == 413


def _cut(server: Server, path: str, kind: str, extra: str = "") -> None:
    """Three uploads to `path` that stop mid-body (the phone left the Wi-Fi)."""
    for _ in range(3):
        head = f"POST {path} HTTP/1.1\nHost: x\nContent-Type: {kind}\nContent-Length: 900\n"
        _raw(server, head + extra, b"name=" + b"a" * 100).close()


def _log_after_stop(server: Server) -> str:
    """What the server wrote, once it answered one more request and stopped."""
    assert httpx.get(server.base + "/api/leaderboard").status_code in (200, 404)
    server.proc.send_signal(signal.SIGTERM)
    server.proc.wait(30)
    assert server.proc.stdout is not None
    return server.proc.stdout.read()


def test_uploads_cut_mid_body_leave_no_traceback(single: Server, department: Server) -> None:
    open_challenge(single)
    student = join(single, "Leaver")["Authorization"]
    _cut(single, "/api/join", "application/json")
    _cut(single, "/api/submit", "application/json", f"Authorization: {student}\n")
    _cut(department, "/lecturer", "application/x-www-form-urlencoded")
    _cut(department, "/admin", "application/x-www-form-urlencoded")
    for server in (single, department):
        log = _log_after_stop(server)
        assert "Traceback" not in log and "Exception in ASGI" not in log, log
        assert "uploads cut mid-body: 6" in log, log


def test_the_guide_states_these_limits() -> None:
    from evapcool.classroom.streamkeys import KEY_CHECK
    from evapcool.classroom.views.department import FORM_BYTES

    guide = " ".join(
        (Path(__file__).resolve().parents[2] / "docs" / "class.md").read_text().split()
    )
    assert f"past {FORM_BYTES // 1024} KB" in guide
    assert f"within {KEY_CHECK:g} s when nothing changes" in guide
    assert "ASCII digits only, 1 to 2^63 - 1" in guide
