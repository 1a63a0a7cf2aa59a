"""The lecturer's list of classes keeps each round (issue 45) with its closing time as a
<time datetime> (the page writes it in the reader's language and time zone: times.ts,
walked in Chromium by web/test/e2e/console-phone.test.mjs) and its links: the projector
reopening that round, its CSV and JSON exports, each answered for the browser's cookie."""

from __future__ import annotations

import re
from collections.abc import Iterator
from datetime import datetime, timedelta, timezone
from pathlib import Path

import httpx
import pytest
from classhelp import SEED, SETTINGS, Server, start_server

ROUND = {
    "n_atoms": SETTINGS.n_atoms,
    "radius": SETTINGS.radius,
    "escape": SETTINGS.escape,
    "seed": SEED,
}


@pytest.fixture
def department(tmp_path: Path) -> Iterator[Server]:
    running = start_server(tmp_path / "department.sqlite", extra=("--department",))
    yield running
    running.stop()


def test_each_round_has_its_time_projector_and_exports(department: Server) -> None:
    admin = {"Authorization": f"Bearer {department.token}"}
    made = httpx.post(department.base + "/api/admin/lecturers", json={"name": "Ada"}, headers=admin)
    token = made.json()["token"]
    bearer = {"Authorization": f"Bearer {token}"}
    room = httpx.post(department.base + "/api/classes", json={"name": "Optics"}, headers=bearer)
    code = room.json()["code"]
    api = f"{department.base}/c/{code}/api"
    timed = httpx.post(api + "/challenge", json={**ROUND, "minutes": 20}, headers=bearer).json()
    httpx.post(api + "/challenge/close", json={}, headers=bearer)
    untimed = httpx.post(api + "/challenge", json=ROUND, headers=bearer).json()

    with httpx.Client(base_url=department.base, follow_redirects=True) as browser:
        page = browser.get("/lecturer", params={"token": token, "lang": "de"}).text
        rows = page[page.index(f'id="rounds-{code}"') :]
        rows = rows[: rows.index("</table>")].split("<tr>")[2:]  # after the header's row
        assert len(rows) == 2  # newest first
        now_row, past_row = rows
        stamp = re.search(r'<time datetime="([^"]+)">([^<]+)</time>', past_row)
        assert stamp and stamp.group(1) == stamp.group(2)
        # Closed by hand 20 minutes early: the time it closed, not its window's end.
        ended, planned = (
            datetime.fromisoformat(t.replace("Z", "+00:00"))
            for t in (stamp.group(1), timed["closes_at"])
        )
        assert abs(ended - datetime.now(timezone.utc)) < timedelta(minutes=2)
        assert planned - ended > timedelta(minutes=18)
        assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(\.\d+)?Z", stamp.group(1))
        assert "<time" not in now_row  # no window: no closing time
        links = dict(
            (text, href.replace("&amp;", "&"))
            for href, text in re.findall(
                r'<a class="button" href="([^"]+)"[^>]*>([^<]+)</a>', past_row
            )
        )
        assert set(links) == {"Auf dem Projektor öffnen", "CSV", "JSON"}
        assert re.fullmatch(
            rf"/c/{code}/projector\?key=[0-9a-f]+&round={timed['id']}",
            links["Auf dem Projektor öffnen"],
        )
        live = re.search(r'<a class="button" href="([^"]+)"[^>]*>Auf dem Projektor', now_row)
        assert live and "round=" not in live.group(1)  # the open round: the live board
        projector = browser.get(links["Auf dem Projektor öffnen"])
        assert projector.status_code == 200 and 'id="board"' in projector.text
        key = re.search(r"key=([0-9a-f]+)", links["Auf dem Projektor öffnen"])
        assert key
        # What that page asks for: the past round's board, kept after the new round opened.
        board = browser.get(
            f"/c/{code}/api/leaderboard", params={"key": key.group(1), "challenge": timed["id"]}
        )
        assert board.status_code == 200 and board.json()["challenge"] == timed["id"]
        # The exports with the browser's cookie alone (the link as clicked), of that round.
        got_csv = browser.get(links["CSV"])
        assert got_csv.status_code == 200, got_csv.text
        assert got_csv.headers["content-type"].startswith("text/csv")
        assert f"-{timed['id']}.csv" in got_csv.headers["content-disposition"]
        got_json = browser.get(links["JSON"])
        assert got_json.status_code == 200 and got_json.json()["challenge"]["id"] == timed["id"]
    # Without the cookie the exports are refused.
    assert httpx.get(department.base + links["CSV"]).status_code == 403
    assert untimed["id"] != timed["id"]
