"""A department's server: the administrator's and lecturers' calls and pages, joining by code.

The administrator (a token of their own, kept as a digest) makes lecturers and classes; a
lecturer (a token each, kept as a digest) makes and sees their own classes only, each with
its join code, its pages and its past challenges. These pages are forms posted to this server, each
answered by a redirect to the page (post/redirect/get); the lecturer's link's token is kept
in a cookie (session.py). The administrator's page is views/admin.py.
"""

from __future__ import annotations

import html
import secrets
from typing import Any

from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response
from starlette.routing import Route

from evapcool.classroom import pages
from evapcool.classroom.boards import challenge_info
from evapcool.classroom.bodies import read_form
from evapcool.classroom.console_pages import console_page
from evapcool.classroom.errors import RefusedError, read_json
from evapcool.classroom.hub import Hub
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.session import (
    CSRF_FIELD,
    LECTURER_COOKIE,
    adopt,
    back,
    check_csrf,
    csrf_token,
)
from evapcool.classroom.tokens import ADMIN_SECRET, digest, matches_digest, room_projector_key
from evapcool.classroom.views.common import bearer_token, guard, join_url_of
from evapcool.classroom.views.join import join_page
from evapcool.classroom.words import raw
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


async def form_of(request: Request) -> dict[str, str]:
    """A posted form's fields (urlencoded, at most FORM_BYTES; the last of a repeated one)."""
    return await read_form(request, FORM_BYTES)  # bounded as it arrives (issue 46)


def table(heads: list[str], rows: list[list[str]], ident: str) -> str:
    """A table with its column headers (headers and cells already escaped HTML)."""
    head = "".join(f'<th scope="col">{h}</th>' for h in heads)
    # Each cell names its column (data-label): a phone shows a row as a card of labelled
    # lines (console.css).
    body = "".join(
        "<tr>"
        + "".join(f'<td data-label="{h}">{c}</td>' for h, c in zip(heads, row, strict=True))
        + "</tr>"
        for row in rows
    )
    return (
        f'<div class="table-wrap"><table id="{ident}" class="cards"><thead><tr>{head}</tr></thead>'
        f"<tbody>{body}</tbody></table></div>"
    )


async def classes_page(request: Request) -> Response:
    """A department's lecturer's page: their classes with links and past rounds, and a
    form for a new class (a link's ?token= is taken into the cookie first)."""
    given = request.query_params.get("token")
    if given:
        await _lecturer_of(request, given)
        return adopt(request, LECTURER_COOKIE, given)
    token = request.cookies.get(LECTURER_COOKIE, "")
    hub, who = await _lecturer_of(request, token)
    return await _classes(request, hub, who, token)


async def classes_post(request: Request) -> Response:
    """A new class from the lecturer's page's form (name, csrf); then the list by GET (a
    reload makes no second class)."""
    form = await form_of(request)
    token = request.cookies.get(LECTURER_COOKIE, "")
    hub, who = await _lecturer_of(request, token)
    check_csrf(token, form.get(CSRF_FIELD, ""))
    await hub.db(hub.store.add_room, clean_title(form.get("name"), "name"), who["id"])
    return back(request, "/lecturer")


async def _classes(request: Request, hub: Hub, who: dict[str, Any], token: str) -> Response:
    words = hub.words.of(request)
    archived = await hub.db(hub.store.archived_rooms)
    title = _e(words, "class.classes.title", name=who["name"])
    parts = [f'<header id="top"><h1>{title}</h1></header><main>']
    for room in await hub.db(hub.store.rooms, who["id"]):
        parts.append(await _class_section(request, hub, words, room, room["id"] in archived))
    csrf = csrf_token(token)
    parts.append(
        f'<section id="new-class"><form method="post" action="/lecturer" class="inline">'
        f'<input type="hidden" name="{CSRF_FIELD}" value="{csrf}">'
        f'<label for="name">{_e(words, "class.admin.new_class")}</label> '
        f'<input id="name" name="name" maxlength="{TITLE_MAX}" required> '
        f'<button class="primary">{_e(words, "class.admin.create")}</button></form>'
        "</section></main>"
    )
    title = words.t("class.classes.title", name=who["name"])
    return console_page(
        lambda k: raw(words, k), words.locale, words.meta["direction"], title, "".join(parts)
    )


async def _class_section(
    request: Request, hub: Hub, words: Catalog, room: dict[str, Any], archived: bool
) -> str:
    """One class of the lecturer's list: name, join code, links, its past rounds."""
    doc = class_doc(request, room)
    mark = f' <span class="tag">{_e(words, "console.admin.archived")}</span>' if archived else ""
    head = (
        f'<section class="class-card" data-code="{room["code"]}"><h2>{html.escape(room["name"])}'
        f'{mark}</h2><p><span class="label">{_e(words, "console.lecturer.join_code")}</span> '
        f'<span class="code">{room["code"]}</span></p>'
        f'<p class="links"><a class="button primary" href="{html.escape(doc["lecturer_page"])}">'
        f"{_e(words, 'class.classes.page')}</a> "
        f'<a class="button" href="{html.escape(doc["projector"])}">'
        f"{_e(words, 'class.lecturer.projector')}</a> "
        f'<input class="link" readonly value="{html.escape(doc["join"])}" size="36" '
        f'aria-label="{_e(words, "console.admin.join")}"> <button type="button" class="copy" '
        f'data-copy="{html.escape(doc["join"])}">{_e(words, "console.copy")}</button></p>'
    )
    past = await hub.db(hub.store.challenges, room["id"])
    if not past:
        return head + f"<p>{_e(words, 'class.classes.none')}</p></section>"
    rows = []
    for c in past:
        info = challenge_info(c)
        when = info["closes_at"]
        # The ISO time stays in datetime=; console.ts writes it in the reader's language
        # and time zone.
        shown = f'<time datetime="{html.escape(when)}">{html.escape(when)}</time>' if when else "—"
        rows.append(
            [
                str(c["id"]),
                shown,
                _e(words, "class.classes.games", n=c["games"], students=c["students"]),
                _round_links(words, room, doc, int(info["id"]), bool(info["open"])),
            ]
        )
    heads = [
        _e(words, k)
        for k in (
            "console.lecturer.round",
            "console.lecturer.closes",
            "console.lecturer.played",
            "console.admin.links",
        )
    ]
    return head + table(heads, rows, f"rounds-{room['code']}") + "</section>"


def _round_links(
    words: Catalog, room: dict[str, Any], doc: dict[str, Any], challenge: int, live: bool
) -> str:
    """A round's links: reopened on the projector (the live board while it is open), its
    CSV and JSON exports."""
    projector = doc["projector"]
    if not live:
        projector += ("&" if "?" in projector else "?") + f"round={challenge}"
    api = f"/c/{room['code']}/api/export"
    parts = [
        f'<a class="button" href="{html.escape(projector)}" target="_blank" '
        f'data-round="{challenge}">{_e(words, "console.lecturer.round_projector")}</a>',
        f'<a class="button" href="{api}.csv?challenge={challenge}" download>CSV</a>',
        f'<a class="button" href="{api}.json?challenge={challenge}" download>JSON</a>',
    ]
    return f'<span class="round-links">{" ".join(parts)}</span>'


#: A department's root and lecturer's page (before the single class's at the same paths).
ROOT_ROUTES = [
    Route("/", join_page, methods=["GET"]),
    Route("/lecturer", classes_page, methods=["GET"]),
]
ROUTES = [
    Route("/lecturer", classes_post, methods=["POST"]),
    Route("/api/admin/lecturers", admin_lecturers, methods=["GET", "POST"]),
    Route("/api/admin/classes", admin_classes, methods=["GET", "POST"]),
    Route("/api/classes", my_classes, methods=["GET", "POST"]),
]
