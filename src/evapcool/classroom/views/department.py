"""A department's server: the administrator's and lecturers' calls and pages, joining by code.

The administrator (a token of their own, kept as a digest) makes lecturers and classes; a
lecturer (a token each, kept as a digest) makes and sees their own classes only, each with
its join code, its pages and its past challenges. These pages have no script: plain forms
posted to this server, each answered by the page again.
"""

from __future__ import annotations

import html
import secrets
from typing import Any
from urllib.parse import quote

from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, RedirectResponse, Response
from starlette.routing import Route

from evapcool.classroom import pages
from evapcool.classroom.boards import challenge_info
from evapcool.classroom.bodies import read_form
from evapcool.classroom.errors import RefusedError, read_json
from evapcool.classroom.guessing import room_for
from evapcool.classroom.hub import Hub
from evapcool.classroom.numbers import whole_number
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.tokens import ADMIN_SECRET, digest, matches_digest, room_projector_key
from evapcool.classroom.views.common import bearer_token, guard, join_url_of
from evapcool.i18n import Catalog

#: The longest class or lecturer name kept.
TITLE_MAX = 80
#: The longest form body read (a name and a token).
FORM_BYTES = 4096
STYLE = """
body{font:16px/1.4 system-ui,sans-serif;margin:1.5em;max-width:60em}
table{border-collapse:collapse;margin-bottom:1em}td,th{border-bottom:1px solid #ccc;
padding:.3em .8em;text-align:start}form{margin:1em 0}input,select,button{font:inherit}
.code{font:700 1.4em ui-monospace,monospace;letter-spacing:.15em}.note{background:#fff4c2;
padding:.5em}#error{color:#a00}
"""
POLICY = (
    f"default-src 'none'; style-src {pages.source_hash(STYLE)}; base-uri 'none'; "
    "form-action 'self'; frame-ancestors 'none'"
)


def new_token() -> str:
    """A new secret token (a lecturer's or the administrator's)."""
    return secrets.token_urlsafe(24)


def new_admin_token(store: Any) -> str:
    """A new administrator's token (the last one stops working); the store keeps its digest."""
    token = new_token()
    store.set_secret(ADMIN_SECRET, digest(token))
    return token


def clean_title(value: object, field: str) -> str:
    """A class's or lecturer's name: 1..TITLE_MAX visible characters (400 naming field)."""
    text = " ".join(value.split()) if isinstance(value, str) else ""
    if not text or len(text) > TITLE_MAX or not text.isprintable():
        raise RefusedError(400, field, "class.error.title", n=TITLE_MAX)
    return text


async def _admin(request: Request, token: str) -> Hub:
    """The Hub if `token` is the administrator's, else 403."""
    hub = guard(request)
    if not matches_digest(token, await hub.db(hub.store.secret, ADMIN_SECRET)):
        raise RefusedError(403, "token", "class.error.admin")
    return hub


async def _lecturer_of(request: Request, token: str) -> tuple[Hub, dict[str, Any]]:
    """The Hub and the lecturer `token` is of, else 403."""
    hub = guard(request)
    found = await hub.db(hub.store.lecturer_by_digest, digest(token)) if token else None
    if found is None:
        raise RefusedError(403, "token", "class.error.lecturer")
    return hub, found


async def listed_rooms(hub: Hub) -> list[dict[str, Any]]:
    """Every class the administrator sees: the single class's room only if it holds a
    challenge (a file of one class brought into a department), not the empty one every
    store has."""
    rooms = await hub.db(hub.store.rooms)
    if await hub.db(hub.store.latest, DEFAULT_ROOM) is None:
        rooms = [r for r in rooms if r["id"] != DEFAULT_ROOM]
    return rooms


def class_doc(request: Request, room: dict[str, Any]) -> dict[str, Any]:
    """A class as the administrator and its lecturer see it: code, name, its links (the
    lecturer's needs the lecturer's token added: ?token=)."""
    base = f"/c/{room['code']}"
    key = room_projector_key(room["digest"], room["code"]) if room["digest"] else None
    return {
        "code": room["code"],
        "name": room["name"],
        "lecturer": room["lecturer"],
        "join": join_url_of(request, room),
        "lecturer_page": f"{base}/lecturer",
        "projector": f"{base}/projector" + (f"?key={key}" if key else ""),
    }


# -- the administrator's calls ------------------------------------------------------------------


async def admin_lecturers(request: Request) -> Response:
    """GET: the lecturers; POST {name}: a new lecturer and their token (shown once)."""
    hub = await _admin(request, bearer_token(request))
    if request.method == "GET":
        return JSONResponse({"lecturers": await hub.db(hub.store.lecturers)})
    doc = await read_json(request, hub.limits.body_bytes)
    name = clean_title(doc.get("name"), "name")
    token = new_token()
    made = await hub.db(hub.store.add_lecturer, name, digest(token))
    return JSONResponse({"id": made, "name": name, "token": token})


async def admin_classes(request: Request) -> Response:
    """GET: every class; POST {name, lecturer}: a new class for a lecturer."""
    hub = await _admin(request, bearer_token(request))
    if request.method == "GET":
        rooms = await listed_rooms(hub)
        return JSONResponse({"classes": [class_doc(request, r) for r in rooms]})
    doc = await read_json(request, hub.limits.body_bytes)
    name = clean_title(doc.get("name"), "name")
    lecturer = doc.get("lecturer")
    known = {row["id"] for row in await hub.db(hub.store.lecturers)}
    if not isinstance(lecturer, int) or isinstance(lecturer, bool) or lecturer not in known:
        raise RefusedError(400, "lecturer", "class.error.no_lecturer")
    room = await hub.db(hub.store.add_room, name, lecturer)
    return JSONResponse(class_doc(request, room))


# -- a lecturer's calls ---------------------------------------------------------------------


async def my_classes(request: Request) -> Response:
    """GET: the lecturer's classes; POST {name}: a new class of theirs."""
    hub, who = await _lecturer_of(request, bearer_token(request))
    if request.method == "POST":
        doc = await read_json(request, hub.limits.body_bytes)
        room = await hub.db(hub.store.add_room, clean_title(doc.get("name"), "name"), who["id"])
        return JSONResponse(class_doc(request, room))
    rooms = await hub.db(hub.store.rooms, who["id"])
    return JSONResponse({"classes": [class_doc(request, r) for r in rooms]})


# -- pages ---------------------------------------------------------------------------------------


def _page(words: Catalog, title: str, body: str) -> HTMLResponse:
    text = (
        f'<!doctype html><html lang="{html.escape(words.locale)}" '
        f'dir="{html.escape(words.meta["direction"])}"><head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f"<title>{html.escape(title)}</title><style>{STYLE}</style></head>"
        f"<body><h1>{html.escape(title)}</h1>{body}</body></html>"
    )
    headers = {"Content-Security-Policy": POLICY, "Cache-Control": "no-store"}
    return HTMLResponse(text, headers=headers)


def _e(words: Catalog, key: str, **args: Any) -> str:
    """A catalog message, escaped for HTML."""
    return html.escape(words.t(key, **args))


async def _form(request: Request) -> dict[str, str]:
    """A posted form's fields (urlencoded, at most FORM_BYTES; the last of a repeated one)."""
    return await read_form(request, FORM_BYTES)


async def join_page(request: Request) -> Response:
    """The department's root: a box for the join code; a known code goes to its class."""
    hub = guard(request)
    words = hub.words.of(request)
    given = request.query_params.get("code")
    error = ""
    if given is not None:
        room = await room_for(request, hub, given)  # wrong codes limited (issue 46)
        if room is not None:
            return RedirectResponse(f"/c/{room['code']}/", status_code=303)
        error = f'<p id="error" role="alert">{_e(words, "class.join.unknown")}</p>'
    body = (
        f'{error}<form method="get" action="/"><label for="code">{_e(words, "class.join.code")}'
        '</label> <input id="code" name="code" class="code" size="8" maxlength="12" '
        'autocomplete="off" autocapitalize="characters" spellcheck="false" required autofocus> '
        f"<button>{_e(words, 'class.join.go')}</button></form>"
    )
    return _page(words, words.t("class.join.title"), body)


def _rows(cells: list[list[str]]) -> str:
    return "".join("<tr>" + "".join(f"<td>{c}</td>" for c in row) + "</tr>" for row in cells)


async def classes_page(request: Request) -> Response:
    """A department's lecturer's page (?token=): their classes with links and past
    challenges, and a form for a new class."""
    token = request.query_params.get("token", "")
    hub, who = await _lecturer_of(request, token)
    return await _classes(request, hub, who, token, "")


async def classes_post(request: Request) -> Response:
    """A new class from the lecturer's page's form (name, token)."""
    form = await _form(request)
    token = form.get("token", "")
    hub, who = await _lecturer_of(request, token)
    room = await hub.db(hub.store.add_room, clean_title(form.get("name"), "name"), who["id"])
    words = hub.words.of(request)
    made = _e(words, "class.classes.made", name=room["name"], code=room["code"])
    note = f'<p class="note">{made}</p>'
    return await _classes(request, hub, who, token, note)


async def _classes(
    request: Request, hub: Hub, who: dict[str, Any], token: str, note: str
) -> Response:
    words = hub.words.of(request)
    parts = [note]
    q = "?token=" + quote(token)
    for room in await hub.db(hub.store.rooms, who["id"]):
        doc = class_doc(request, room)
        parts.append(
            f'<h2>{html.escape(room["name"])} · <span class="code">{room["code"]}</span></h2>'
            f'<p><a href="{html.escape(doc["lecturer_page"] + q)}">'
            f"{_e(words, 'class.classes.page')}</a> · "
            f'<a href="{html.escape(doc["projector"])}">{_e(words, "class.lecturer.projector")}'
            f"</a> · {html.escape(doc['join'])}</p>"
        )
        past = await hub.db(hub.store.challenges, room["id"])
        if not past:
            parts.append(f"<p>{_e(words, 'class.classes.none')}</p>")
            continue
        rows = []
        for c in past:
            csv_link = f"/c/{room['code']}/api/export.csv{q}&challenge={c['id']}"
            info = challenge_info(c)
            rows.append(
                [
                    str(c["id"]),
                    html.escape(str(info["closes_at"] or "")),
                    _e(words, "class.classes.games", n=c["games"], students=c["students"]),
                    f'<a href="{html.escape(csv_link)}">CSV</a>',
                ]
            )
        parts.append(f"<table>{_rows(rows)}</table>")
    parts.append(
        f'<form method="post" action="/lecturer"><input type="hidden" name="token" '
        f'value="{html.escape(token)}"><label for="name">{_e(words, "class.admin.new_class")}'
        f'</label> <input id="name" name="name" maxlength="{TITLE_MAX}" required> '
        f"<button>{_e(words, 'class.admin.create')}</button></form>"
    )
    return _page(words, words.t("class.classes.title", name=who["name"]), "".join(parts))


async def admin_page(request: Request) -> Response:
    """The administrator's page (?token=): lecturers, classes, and forms for new ones."""
    token = request.query_params.get("token", "")
    hub = await _admin(request, token)
    return await _admin_view(request, hub, token, "")


async def admin_post(request: Request) -> Response:
    """A new lecturer (what=lecturer, name) or class (what=class, name, lecturer) from the
    administrator's page; the new lecturer's link is shown once."""
    form = await _form(request)
    token = form.get("token", "")
    hub = await _admin(request, token)
    words = hub.words.of(request)
    name = clean_title(form.get("name"), "name")
    root = (request.app.state.join_url or str(request.base_url)).rstrip("/")
    if form.get("what") == "lecturer":
        secret = new_token()
        await hub.db(hub.store.add_lecturer, name, digest(secret))
        url = f"{root}/lecturer?token={secret}"
        note = _e(words, "class.admin.made_lecturer", name=name, url=url)
    else:
        lecturer = whole_number(form.get("lecturer"), "lecturer")
        known = {row["id"] for row in await hub.db(hub.store.lecturers)}
        if lecturer not in known:
            raise RefusedError(400, "lecturer", "class.error.no_lecturer")
        room = await hub.db(hub.store.add_room, name, lecturer)
        note = _e(words, "class.classes.made", name=room["name"], code=room["code"])
    return await _admin_view(request, hub, token, f'<p class="note">{note}</p>')


async def _admin_view(request: Request, hub: Hub, token: str, note: str) -> Response:
    words = hub.words.of(request)
    lecturers = await hub.db(hub.store.lecturers)
    rooms = await listed_rooms(hub)
    names = {row["id"]: row["name"] for row in lecturers}
    hidden = f'<input type="hidden" name="token" value="{html.escape(token)}">'
    lecturer_rows = [[str(r["id"]), html.escape(r["name"]), str(r["classes"])] for r in lecturers]
    class_rows = [
        [
            f'<span class="code">{r["code"]}</span>',
            html.escape(r["name"]),
            html.escape(names.get(r["lecturer"], "—")),
        ]
        for r in rooms
    ]
    options = "".join(
        f'<option value="{r["id"]}">{html.escape(r["name"])}</option>' for r in lecturers
    )
    body = (
        f"{note}<h2>{_e(words, 'class.admin.lecturers')}</h2><table>{_rows(lecturer_rows)}</table>"
        f'<form method="post" action="/admin">{hidden}<input type="hidden" name="what" '
        f'value="lecturer"><label for="lname">{_e(words, "class.admin.new_lecturer")}</label> '
        f'<input id="lname" name="name" maxlength="{TITLE_MAX}" required> '
        f"<button>{_e(words, 'class.admin.create')}</button></form>"
        f"<h2>{_e(words, 'class.admin.classes')}</h2><table>{_rows(class_rows)}</table>"
        f'<form method="post" action="/admin">{hidden}<input type="hidden" name="what" '
        f'value="class"><label for="cname">{_e(words, "class.admin.new_class")}</label> '
        f'<input id="cname" name="name" maxlength="{TITLE_MAX}" required> '
        f'<select name="lecturer" aria-label="{_e(words, "class.admin.lecturer")}">{options}'
        f"</select> <button>{_e(words, 'class.admin.create')}</button></form>"
    )
    return _page(words, words.t("class.admin.title"), body)


#: A department's root and lecturer's page (before the single class's at the same paths).
ROOT_ROUTES = [
    Route("/", join_page, methods=["GET"]),
    Route("/lecturer", classes_page, methods=["GET"]),
]
ROUTES = [
    Route("/admin", admin_page, methods=["GET"]),
    Route("/admin", admin_post, methods=["POST"]),
    Route("/lecturer", classes_post, methods=["POST"]),
    Route("/api/admin/lecturers", admin_lecturers, methods=["GET", "POST"]),
    Route("/api/admin/classes", admin_classes, methods=["GET", "POST"]),
    Route("/api/classes", my_classes, methods=["GET", "POST"]),
]
