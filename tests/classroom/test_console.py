"""The console's links that last (issue 45), against a really started department server:
the link's token taken into an HttpOnly SameSite=Strict cookie (Secure over HTTPS) and out
of the address, CSRF refused on forms and on the page's calls, post/redirect/get, refusals
as pages for browsers and JSON for API clients, and the administrator's page doing what
`evapcool class admin` does (relink, rename, retire, archive with records kept)."""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from classhelp import SETTINGS, Server, start_server

from evapcool.classroom.session import csrf_token

#: A round's settings as the lecturer's page sends them.
ROUND = {
    "n_atoms": SETTINGS.n_atoms,
    "radius": SETTINGS.radius,
    "escape": SETTINGS.escape,
    "seed": 5,
}
HTML = {"Accept": "text/html,application/xhtml+xml", "Accept-Language": "de"}


@pytest.fixture
def department(store_at: Path | str) -> Iterator[Server]:
    running = start_server(store_at, extra=("--department",))
    yield running
    running.stop()


def _lecturer(server: Server, name: str) -> str:
    made = httpx.post(
        server.base + "/api/admin/lecturers",
        json={"name": name},
        headers={"Authorization": f"Bearer {server.token}"},
    )
    assert made.status_code == 200, made.text
    return str(made.json()["token"])


def _class(server: Server, token: str, name: str) -> dict[str, str]:
    made = httpx.post(
        server.base + "/api/classes",
        json={"name": name},
        headers={"Authorization": f"Bearer {token}"},
    )
    assert made.status_code == 200, made.text
    doc: dict[str, str] = made.json()
    return doc


def _cookie_line(answer: httpx.Response, name: str) -> str:
    lines = [v for k, v in answer.headers.multi_items() if k == "set-cookie" and v.startswith(name)]
    assert len(lines) == 1, answer.headers
    return lines[0]


def test_a_link_leaves_its_token_in_a_strict_http_only_cookie(department: Server) -> None:
    went = httpx.get(department.base + "/admin", params={"token": department.token, "lang": "de"})
    assert went.status_code == 303 and went.headers["location"] == "/admin?lang=de"
    line = _cookie_line(went, "evapcool_admin=")
    flags = {part.strip().lower() for part in line.split(";")[1:]}
    assert {"httponly", "samesite=strict", "path=/admin"} <= flags, line
    assert "secure" not in flags  # read over http://
    ada = _lecturer(department, "Ada")
    over_https = httpx.get(
        department.base + "/lecturer",
        params={"token": ada},
        headers={"X-Forwarded-Proto": "https"},
    )
    assert over_https.status_code == 303 and over_https.headers["location"] == "/lecturer"
    flags = {p.strip().lower() for p in _cookie_line(over_https, "evapcool_lecturer=").split(";")}
    assert {"httponly", "samesite=strict", "path=/", "secure"} <= flags, flags


def test_forms_without_their_csrf_token_are_refused(department: Server) -> None:
    ada = _lecturer(department, "Ada")
    made = _class(department, ada, "Optics")
    base = f"/c/{made['code']}"
    with httpx.Client(base_url=department.base) as browser:
        browser.get("/lecturer", params={"token": ada})  # the cookie
        forged = browser.post("/lecturer", data={"name": "Forged"})
        assert forged.status_code == 403 and forged.json()["error"]["field"] == "csrf"
        as_page = browser.post("/lecturer", data={"name": "Forged", "csrf": "0" * 32}, headers=HTML)
        assert as_page.status_code == 403 and "text/html" in as_page.headers["content-type"]
        assert "Lade die Seite neu" in as_page.text or "lade die Seite neu" in as_page.text
        # the page's own calls: the cookie alone is not enough, the header makes them good
        body = ROUND
        bare = browser.post(base + "/api/challenge", json=body)
        assert bare.status_code == 403 and bare.json()["error"]["field"] == "csrf"
        signed = browser.post(
            base + "/api/challenge", json=body, headers={"X-Evapcool-CSRF": csrf_token(ada)}
        )
        assert signed.status_code == 200, signed.text
        # post/redirect/get: a good form answers 303 to the list; reading it again adds nothing
        good = browser.post("/lecturer", data={"name": "Waves", "csrf": csrf_token(ada)})
        assert good.status_code == 303 and good.headers["location"] == "/lecturer"
        browser.get("/lecturer")
        browser.get("/lecturer")
    listed = httpx.get(department.base + "/api/classes", headers={"Authorization": f"Bearer {ada}"})
    assert [c["name"] for c in listed.json()["classes"]] == ["Optics", "Waves"]


def test_refusals_are_pages_for_browsers_and_json_for_api_clients(department: Server) -> None:
    ada, bo = _lecturer(department, "Ada"), _lecturer(department, "Bo")
    made = _class(department, ada, "Optics")
    stale = httpx.get(department.base + "/lecturer", params={"token": "stale"}, headers=HTML)
    assert stale.status_code == 403 and "text/html" in stale.headers["content-type"]
    assert 'lang="de"' in stale.text and 'id="todo"' in stale.text
    assert "stale" not in stale.text
    with httpx.Client(base_url=department.base) as browser:
        browser.get("/lecturer", params={"token": bo})
        theirs = browser.get(f"/c/{made['code']}/lecturer", headers=HTML)
        assert theirs.status_code == 403 and 'id="refusal"' in theirs.text
        api = browser.get(f"/c/{made['code']}/api/entries", headers=HTML)
        assert api.status_code == 403 and api.json()["error"]["field"] == "token"
    plain = httpx.get(department.base + "/lecturer", params={"token": "stale"})
    assert plain.status_code == 403 and plain.json()["error"]["field"] == "token"
    lost = httpx.get(department.base + "/no/such/page", headers=HTML)
    assert lost.status_code == 404 and 'id="todo"' in lost.text


def test_the_admin_page_relinks_renames_retires_and_archives(department: Server) -> None:
    ada = _lecturer(department, "Ada")
    made = _class(department, ada, "Optics")
    with httpx.Client(base_url=department.base, follow_redirects=True) as browser:
        page = browser.get("/admin", params={"token": department.token})
        csrf = csrf_token(department.token)
        assert f'value="{csrf}"' in page.text and "<th" in page.text
        assert department.token not in page.text

        def form(**fields: str) -> httpx.Response:
            return browser.post("/admin", data={"csrf": csrf, **fields})

        relinked = form(what="relink", lecturer="1")
        link = re.search(r"/lecturer\?token=([\w-]+)", relinked.text)
        assert link and "<svg" in relinked.text and 'class="copy"' in relinked.text
        assert re.search(r"/lecturer\?token=", browser.get("/admin").text) is None  # once
        new = link.group(1)
        assert httpx.get(department.base + "/lecturer", params={"token": ada}).status_code == 403
        form(what="rename_lecturer", lecturer="1", name="Ada L.")
        form(
            what="rename_class", **{"class": str(_room_id(department, made["code"]))}, name="Optik"
        )
        form(what="archive", **{"class": str(_room_id(department, made["code"]))})
        text = browser.get("/admin").text
        assert "Ada L." in text and "Optik" in text and "Archived" in text
        form(what="retire", lecturer="1")
    assert httpx.get(department.base + "/lecturer", params={"token": new}).status_code == 403
    classes = httpx.get(
        department.base + "/api/admin/classes",
        headers={"Authorization": f"Bearer {department.token}"},
    ).json()["classes"]
    assert [c["name"] for c in classes] == ["Optik"]  # the class and its records stay


def test_an_archived_class_opens_no_new_round(department: Server) -> None:
    ada = _lecturer(department, "Ada")
    made = _class(department, ada, "Optics")
    with httpx.Client(base_url=department.base, follow_redirects=True) as browser:
        browser.get("/admin", params={"token": department.token})
        room = str(_room_id(department, made["code"]))
        browser.post(
            "/admin", data={"csrf": csrf_token(department.token), "what": "archive", "class": room}
        )
    body = ROUND
    refused = httpx.post(
        department.base + f"/c/{made['code']}/api/challenge",
        json=body,
        headers={"Authorization": f"Bearer {ada}"},
    )
    assert refused.status_code == 409 and refused.json()["error"]["field"] == "class"


def _room_id(server: Server, code: str) -> int:
    """A class's id, as the administrator's page's forms name it (from its hidden fields)."""
    with httpx.Client(base_url=server.base, follow_redirects=True) as browser:
        page = browser.get("/admin", params={"token": server.token}).text
    row = page[page.index(code) :]
    found = re.search(r'name="class" value="(\d+)"', row)
    assert found, row[:400]
    return int(found.group(1))
