"""A department's class server (issue 35): classes with join codes, lecturers and the
administrator, each class apart from the others, the term's history, on both stores."""

from __future__ import annotations

import asyncio
import csv
import io
import json
import re
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from classhelp import SEED, SETTINGS, Server, browse, code, start_server

from evapcool.classroom import rooms
from evapcool.classroom.server import digest, new_lecturer_token, open_store


@pytest.fixture
def department(store_at: Path | str) -> Iterator[Server]:
    """A department's server on a new store (SQLite and PostgreSQL); token: the admin's."""
    running = start_server(store_at, extra=("--department",))
    yield running
    running.stop()


def admin(server: Server) -> dict[str, str]:
    return {"Authorization": f"Bearer {server.token}"}


def admin_form(server: Server, fields: dict[str, str]) -> httpx.Response:
    """One form of the administrator's page posted as a browser does (its link opened,
    the CSRF token read from the page), the page it is sent back to."""
    with httpx.Client(base_url=server.base, follow_redirects=True) as browser:
        page = browser.get("/admin", params={"token": server.token})
        csrf = re.search(r'name="csrf" value="([0-9a-f]+)"', page.text)
        assert csrf, page.text
        return browser.post("/admin", data={"csrf": csrf.group(1), **fields})


def new_lecturer(server: Server, name: str) -> str:
    made = httpx.post(
        server.base + "/api/admin/lecturers", json={"name": name}, headers=admin(server)
    )
    assert made.status_code == 200, made.text
    return str(made.json()["token"])


def new_class(server: Server, token: str, name: str) -> dict[str, str]:
    made = httpx.post(server.base + "/api/classes", json={"name": name}, headers=bearer(token))
    assert made.status_code == 200, made.text
    doc: dict[str, str] = made.json()
    return doc


def bearer(token: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {token}"}


def open_in(server: Server, base: str, token: str) -> int:
    body = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "escape": SETTINGS.escape}
    answer = httpx.post(
        server.base + base + "api/challenge", json={**body, "seed": SEED}, headers=bearer(token)
    )
    assert answer.status_code == 200, answer.text
    return int(answer.json()["id"])


def join_in(server: Server, base: str, name: str) -> dict[str, str]:
    answer = httpx.post(server.base + base + "api/join", json={"name": name})
    assert answer.status_code == 200, answer.text
    return bearer(answer.json()["token"])


def submit_in(
    server: Server, base: str, who: dict[str, str], challenge: int, k: int
) -> httpx.Response:
    body = {"challenge": challenge, "code": code(SEED, k)}
    return httpx.post(server.base + base + "api/submit", json=body, headers=who, timeout=60)


def test_join_codes_are_easy_to_read_and_unique(
    store_at: Path | str, monkeypatch: pytest.MonkeyPatch
) -> None:
    for confusable in "0O1lI2Z5S8BUVQ":
        assert confusable not in rooms.CODE_ALPHABET
    made = rooms.new_code()
    assert len(made) == rooms.CODE_LENGTH and set(made) <= set(rooms.CODE_ALPHABET)
    spoken = f" {made[:3].lower()}-{made[3:]} "
    assert rooms.normal_code(spoken) == made and rooms.normal_code("O0O0O0") is None
    store = open_store(store_at, 2)
    try:
        codes = iter(["ACEFGH", "ACEFGH", "ACEFGH", "KMNPRT"])
        monkeypatch.setattr("evapcool.classroom.storage.classes.new_code", lambda: next(codes))
        first = store.add_room("Physics 1", None)
        second = store.add_room("Physics 2", None)  # the same code twice refused by the store
        assert (first["code"], second["code"]) == ("ACEFGH", "KMNPRT")
        assert store.room_by_code("KMNPRT")["name"] == "Physics 2"  # type: ignore[index]
    finally:
        store.close()


def test_classes_are_apart_and_lecturers_act_on_their_own(department: Server) -> None:
    ada, bo = new_lecturer(department, "Ada"), new_lecturer(department, "Bo")
    one, two = new_class(department, ada, "Optics"), new_class(department, bo, "Atoms")
    assert one["code"] != two["code"]
    a, b = f"/c/{one['code']}/", f"/c/{two['code']}/"
    # one lecturer's token against another's class: refused
    assert httpx.get(department.base + b + "api/entries", headers=bearer(ada)).status_code == 403
    assert httpx.get(department.base + a + "api/entries", headers=bearer(bo)).status_code == 403
    assert httpx.get(department.base + b + "lecturer", params={"token": ada}).status_code == 403
    assert (
        httpx.get(department.base + b + "api/export.csv", params={"token": ada}).status_code == 403
    )
    mine = httpx.get(department.base + "/api/classes", headers=bearer(ada)).json()["classes"]
    assert [c["code"] for c in mine] == [one["code"]]
    first_a, first_b = open_in(department, a, ada), open_in(department, b, bo)
    # the same name in two classes; a student's token works in their own class only
    in_a, in_b = join_in(department, a, "Sam"), join_in(department, b, "Sam")
    assert httpx.get(department.base + b + "api/me", headers=in_a).status_code == 401
    assert submit_in(department, b, in_a, first_b, 1).status_code == 401
    assert submit_in(department, a, in_a, first_a, 1).status_code == 200
    assert submit_in(department, b, in_b, first_b, 2).status_code == 200
    board_a = httpx.get(department.base + a + "api/leaderboard").json()
    board_b = httpx.get(department.base + b + "api/leaderboard").json()
    assert board_a["challenge"] == first_a and board_b["challenge"] == first_b
    assert len(board_a["entries"]) == len(board_b["entries"]) == 1
    entry_b = httpx.get(department.base + b + "api/entries", headers=bearer(bo)).json()["entries"][
        0
    ]
    # an entry of class B cannot be hidden, renamed or shown through class A
    for action, body in (("hide", {}), ("rename", {"name": "X"}), ("show", {})):
        sent = httpx.post(
            department.base + a + "api/" + action,
            json={"entry": entry_b["entry"], **body},
            headers=bearer(ada),
        )
        assert sent.status_code == 404, (action, sent.text)
    csv_a = httpx.get(department.base + a + "api/export.csv", params={"token": ada}).text
    assert len(list(csv.reader(io.StringIO(csv_a)))) == 2
    assert (
        httpx.get(department.base + "/c/ACEACE/api/leaderboard").json()["error"]["field"] == "class"
    )


def test_the_terms_history_and_streams_per_class(department: Server) -> None:
    ada = new_lecturer(department, "Ada")
    one, two = new_class(department, ada, "Monday"), new_class(department, ada, "Tuesday")
    a, b = f"/c/{one['code']}/", f"/c/{two['code']}/"
    first = open_in(department, a, ada)
    who = join_in(department, a, "Kim")
    assert submit_in(department, a, who, first, 3).status_code == 200
    second = open_in(department, a, ada)  # the first closes, kept in the history
    past = httpx.get(department.base + a + "api/challenges", headers=bearer(ada)).json()
    assert [c["id"] for c in past["challenges"]] == [second, first]
    assert past["challenges"][1]["games"] == 1 and past["challenges"][1]["students"] == 1
    old = httpx.get(
        department.base + a + "api/export.csv", params={"token": ada, "challenge": first}
    )
    assert [row[1] for row in csv.reader(io.StringIO(old.text))][1:] == ["Kim"]
    assert (
        httpx.get(
            department.base + b + "api/export.csv", params={"token": ada, "challenge": first}
        ).status_code
        == 404
    )  # a challenge of another class
    page = browse(department.base, "/lecturer", ada).text
    assert one["code"] in page and two["code"] in page and f"challenge={first}" in page
    third = open_in(department, b, ada)

    async def watch() -> list[dict[str, object]]:
        async with (
            httpx.AsyncClient(timeout=60) as client,
            client.stream("GET", department.base + b + "api/stream") as events,
        ):
            lines = events.aiter_lines()
            seen = [await _next(lines)]
            sent = await client.post(
                department.base + a + "api/submit",
                json={"challenge": second, "code": code(SEED, 4)},
                headers=who,
            )
            assert sent.status_code == 200
            other = join_in(department, b, "Lee")
            await client.post(
                department.base + b + "api/submit",
                json={"challenge": third, "code": code(SEED, 5)},
                headers=other,
            )
            seen.append(await asyncio.wait_for(_next(lines), 60))
            return seen

    seen = asyncio.run(asyncio.wait_for(watch(), 120))
    # class B's stream saw class B's game only: Kim's game in class A never reached it
    assert [[e["name"] for e in s["entries"]] for s in seen] == [[], ["Lee"]]  # type: ignore[union-attr]


async def _next(lines: object) -> dict[str, object]:
    async for line in lines:  # type: ignore[attr-defined]
        if line.startswith("data: "):
            doc: dict[str, object] = json.loads(line[6:])
            return doc
    raise AssertionError("the stream ended")


def test_join_by_code_admin_page_and_class_pages(department: Server) -> None:
    assert 'name="code"' in httpx.get(department.base + "/").text
    ada = new_lecturer(department, "Ada")
    made = new_class(department, ada, "Lab")
    went = httpx.get(department.base + "/", params={"code": made["code"].lower()})
    assert went.status_code == 303 and went.headers["location"] == f"/c/{made['code']}/"
    wrong = httpx.get(department.base + "/", params={"code": "XXXXXX"})
    assert wrong.status_code == 200 and 'role="alert"' in wrong.text
    game = httpx.get(department.base + f"/c/{made['code']}/").text
    assert f'{{"api":"/c/{made["code"]}/api","name_max":' in game
    assert httpx.get(department.base + "/admin", params={"token": ada}).status_code == 403
    assert httpx.get(department.base + "/api/admin/classes", headers=bearer(ada)).status_code == 403
    page = browse(department.base, "/admin", department.token)
    assert page.status_code == 200 and made["code"] in page.text and "Ada" in page.text
    listed = httpx.get(department.base + "/api/admin/classes", headers=admin(department)).json()
    assert [c["code"] for c in listed["classes"]] == [made["code"]]  # not the empty single class
    posted = admin_form(department, {"what": "lecturer", "name": "Cy"})
    link = re.search(r"/lecturer\?token=([\w-]+)", posted.text)
    assert posted.status_code == 200 and link, posted.text
    cy = link.group(1)
    with httpx.Client(base_url=department.base, follow_redirects=True) as browser:
        listed = browser.get("/lecturer", params={"token": cy})
        csrf = re.search(r'name="csrf" value="([0-9a-f]+)"', listed.text)
        assert csrf, listed.text
        mine = browser.post("/lecturer", data={"csrf": csrf.group(1), "name": "Cy's class"})
    assert mine.status_code == 200 and "Cy&#x27;s class" in mine.text
    classes = httpx.get(department.base + "/api/classes", headers=bearer(cy)).json()["classes"]
    assert [c["name"] for c in classes] == ["Cy's class"]
    projector = httpx.get(department.base + classes[0]["projector"])
    # the class's join code in the projector's largest type (its address is in the QR code)
    code_shown = f'<p id="join-code">{classes[0]["code"]}</p>'
    assert projector.status_code == 200 and code_shown in projector.text
    bad_key = httpx.get(department.base + f"/c/{made['code']}/api/stream", params={"key": "0" * 32})
    assert bad_key.status_code == 403
    refused = httpx.post(department.base + "/api/classes", json={"name": ""}, headers=bearer(cy))
    assert refused.status_code == 400 and refused.json()["error"]["field"] == "name"


def _back_link(page: str) -> str | None:
    """The href of a class's lecturer page's link back to the list of classes, or None."""
    found = re.search(r'<a id="classes" href="([^"]*)">([^<]*)</a>', page)
    if found is None:
        assert 'id="classes"' not in page, page
        return None
    assert found.group(2) == "Back to my classes"
    return found.group(1)


def test_a_class_page_links_back_to_its_lecturers_classes(store_at: Path | str) -> None:
    store = open_store(store_at, 2)
    try:  # the single class's lecturer, as `evapcool class` without --department made one
        single = new_lecturer_token(store)
        single_code = store.room(rooms.DEFAULT_ROOM)["code"]  # type: ignore[index]
    finally:
        store.close()
    running = start_server(store_at, extra=("--department",))
    try:
        ada = new_lecturer(running, "Ada")
        made = new_class(running, ada, "Optics")
        with httpx.Client(base_url=running.base, follow_redirects=True) as browser:
            page = browser.get(made["lecturer_page"], params={"token": ada})
            assert page.status_code == 200 and str(page.url).endswith(made["lecturer_page"])
            href = _back_link(page.text)
            assert href == "/lecturer"  # the cookie the link left carries the token there
            listed = browser.get(href)
        assert listed.status_code == 200 and made["code"] in listed.text
        # a token given as Bearer only is never written into the page
        bearer_only = httpx.get(running.base + made["lecturer_page"], headers=bearer(ada))
        assert bearer_only.status_code == 200 and ada not in bearer_only.text
        # the single class's token is no department lecturer's: no list to go back to
        old = browse(running.base, f"/c/{single_code}/lecturer", single)
        assert old.status_code == 200 and _back_link(old.text) is None
        assert httpx.get(running.base + "/lecturer", params={"token": single}).status_code == 403
    finally:
        running.stop()


def test_a_single_class_server_has_no_list_to_link_to(store_at: Path | str) -> None:
    store = open_store(store_at, 2)
    try:  # a department's class in the store, served without --department
        ada = "a" * 32
        made = store.add_room("Optics", store.add_lecturer("Ada", digest(ada)))
    finally:
        store.close()
    running = start_server(store_at)
    try:
        page = browse(running.base, "/lecturer", running.token)
        assert page.status_code == 200 and 'id="projector"' in page.text
        assert _back_link(page.text) is None
        theirs = browse(running.base, f"/c/{made['code']}/lecturer", ada)
        assert theirs.status_code == 200 and _back_link(theirs.text) is None
    finally:
        running.stop()
