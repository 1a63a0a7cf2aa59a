"""The administrator's page of a department's server: lecturers and classes as tables, a
lecturer's new link with a copy button and a QR code, relink, rename, retire, archive,
a new administrator's link: everything `evapcool class admin` does.

Its link's token goes into a cookie at the first visit (session.adopt); each form carries
the CSRF token and is answered by a redirect to the page (post/redirect/get). A new link
is shown once: it travels to the next page in a short-lived HttpOnly cookie, then is gone.
"""

from __future__ import annotations

import html
from typing import Any

from starlette.requests import Request
from starlette.responses import Response
from starlette.routing import Route

from evapcool.classroom.console_pages import console_page
from evapcool.classroom.errors import RefusedError
from evapcool.classroom.hub import Hub
from evapcool.classroom.numbers import ID_MAX, digits_value, whole_number
from evapcool.classroom.session import (
    ADMIN_COOKIE,
    CSRF_FIELD,
    NOTE_COOKIE,
    adopt,
    back,
    check_csrf,
    csrf_token,
    drop_cookie,
    set_cookie,
)
from evapcool.classroom.tokens import ADMIN_SECRET, digest, matches_digest
from evapcool.classroom.views.board import _qr_svg
from evapcool.classroom.views.common import guard
from evapcool.classroom.views.department import (
    TITLE_MAX,
    class_doc,
    clean_title,
    form_of,
    listed_rooms,
    new_token,
    table,
)
from evapcool.classroom.words import raw
from evapcool.i18n import Catalog


async def _admin(request: Request, token: str) -> Hub:
    """The Hub if `token` is the administrator's, else 403."""
    hub = guard(request)
    if not matches_digest(token, await hub.db(hub.store.secret, ADMIN_SECRET)):
        raise RefusedError(403, "token", "class.error.admin")
    return hub


def _root(request: Request) -> str:
    """The server's address as people reach it (for the links shown)."""
    return str(request.app.state.join_url or request.base_url).rstrip("/")


async def admin_page(request: Request) -> Response:
    """The administrator's page: a link's ?token= is taken into the cookie first."""
    given = request.query_params.get("token")
    if given:
        await _admin(request, given)
        return adopt(request, ADMIN_COOKIE, given)
    token = request.cookies.get(ADMIN_COOKIE, "")
    hub = await _admin(request, token)
    note = request.cookies.get(NOTE_COOKIE, "")
    answer = await _view(request, hub, token, note)
    if note:
        drop_cookie(answer, request, NOTE_COOKIE)
    return answer


async def admin_post(request: Request) -> Response:
    """One of the page's forms (what=lecturer|relink|rename_lecturer|retire|class|
    rename_class|archive|unarchive|admin_link), then back to the page by GET."""
    form = await form_of(request)
    token = request.cookies.get(ADMIN_COOKIE, "")
    hub = await _admin(request, token)
    check_csrf(token, form.get(CSRF_FIELD, ""))
    what = form.get("what", "")
    answer = back(request, "/admin")
    note = await _act(hub, what, form)
    if what == "admin_link":
        token = note.split(".", 1)[1]
        set_cookie(answer, request, ADMIN_COOKIE, token)
    if note:
        set_cookie(answer, request, NOTE_COOKIE, note)
    return answer


def _id(form: dict[str, str], field: str, known: set[int]) -> int:
    """A lecturer's or class's id from a form (400 naming the field if unknown)."""
    value = whole_number(form.get(field), field)  # ASCII digits only (issue 46)
    if value not in known:
        key = "class.error.no_lecturer" if field == "lecturer" else "class.error.no_class"
        raise RefusedError(400, field, key)
    return value


async def _act(hub: Hub, what: str, form: dict[str, str]) -> str:
    """Do what a form asks; the note for the next page ("" for none)."""
    store = hub.store
    lecturers = {row["id"] for row in await hub.db(store.lecturers)}
    if what == "lecturer":
        secret = new_token()
        made = await hub.db(
            store.add_lecturer, clean_title(form.get("name"), "name"), digest(secret)
        )
        return f"L{made}.{secret}"
    if what == "relink":
        who, secret = _id(form, "lecturer", lecturers), new_token()
        await hub.db(store.set_lecturer_digest, who, digest(secret))
        return f"L{who}.{secret}"
    if what == "admin_link":
        secret = new_token()
        await hub.db(store.set_secret, ADMIN_SECRET, digest(secret))
        return f"A.{secret}"
    if what == "rename_lecturer":
        name = clean_title(form.get("name"), "name")
        await hub.db(store.rename_lecturer, _id(form, "lecturer", lecturers), name)
    elif what == "retire":
        await hub.db(store.retire_lecturer, _id(form, "lecturer", lecturers))
    elif what == "class":
        name = clean_title(form.get("name"), "name")
        new_room = await hub.db(store.add_room, name, _id(form, "lecturer", lecturers))
        return f"C{new_room['id']}"
    elif what in ("rename_class", "archive", "unarchive"):
        rooms = {r["id"] for r in await hub.db(store.rooms)}
        room = _id(form, "class", rooms)
        if what == "rename_class":
            await hub.db(store.rename_room, room, clean_title(form.get("name"), "name"))
        else:
            await hub.db(store.set_archived, room, what == "archive")
    else:
        raise RefusedError(400, "what", "class.error.value", allowed="lecturer, class, ...")
    return ""


def _e(words: Catalog, key: str, **args: Any) -> str:
    return html.escape(words.t(key, **args))


def _form(csrf: str, what: str, inner: str, button: str, extra: str = "") -> str:
    """A small form posting `what` to /admin with the CSRF token."""
    return (
        f'<form method="post" action="/admin" class="inline"{extra}>'
        f'<input type="hidden" name="{CSRF_FIELD}" value="{csrf}">'
        f'<input type="hidden" name="what" value="{what}">{inner}'
        f"<button>{button}</button></form>"
    )


def link_box(words: Catalog, label: str, url: str) -> str:
    """A link to hand on: its words, the link in a box to select, a copy button, a QR code."""
    u = html.escape(url)
    return (
        f'<div class="link-box" role="status"><div><p>{label}</p>'
        f'<p><input class="link" readonly value="{u}" aria-label="{label}" size="48"> '
        f'<button type="button" class="copy" data-copy="{u}">{_e(words, "console.copy")}'
        f'</button></p><p class="hint">{_e(words, "console.admin.once")}</p></div>'
        f'<div class="qr" aria-hidden="true">{_qr_svg(url)}</div></div>'
    )


async def _note(request: Request, hub: Hub, words: Catalog, note: str) -> str:
    """The one-time note: a new lecturer's or administrator's link, or a new class."""
    kind, _, secret = note.partition(".")
    if kind == "A" and secret:
        return link_box(
            words, _e(words, "console.admin.admin_link"), f"{_root(request)}/admin?token={secret}"
        )
    if kind.startswith("L") and digits_value(kind[1:], 1, ID_MAX) and secret:
        names = {r["id"]: r["name"] for r in await hub.db(hub.store.lecturers)}
        label = _e(words, "console.admin.lecturer_link", name=names.get(int(kind[1:]), "?"))
        return link_box(words, label, f"{_root(request)}/lecturer?token={secret}")
    if kind.startswith("C") and digits_value(kind[1:], 1, ID_MAX):
        room = await hub.db(hub.store.room, int(kind[1:]))
        if room:
            made = _e(words, "class.classes.made", name=room["name"], code=room["code"])
            return f'<p class="note" role="status">{made}</p>'
    return ""


async def _view(request: Request, hub: Hub, token: str, note: str) -> Response:
    words = hub.words.of(request)
    csrf = csrf_token(token)
    lecturers = await hub.db(hub.store.lecturers)
    parts = [
        f'<header id="top"><h1>{_e(words, "class.admin.title")}</h1>'
        + _form(
            csrf,
            "admin_link",
            "",
            _e(words, "console.admin.new_admin_link"),
            f' data-confirm="{_e(words, "console.admin.confirm_admin_link")}"',
        )
        + "</header><main>",
        await _note(request, hub, words, note),
        _lecturers(words, csrf, lecturers),
        await _classes(request, hub, words, csrf, lecturers),
        "</main>",
    ]
    return console_page(
        lambda k: raw(words, k),
        words.locale,
        words.meta["direction"],
        words.t("class.admin.title"),
        "".join(parts),
    )


def _name_input(words: Catalog, value: str, label: str) -> str:
    return (
        f'<input name="name" value="{html.escape(value)}" maxlength="{TITLE_MAX}" required '
        f'aria-label="{label}" size="16"> '
    )


def _lecturers(words: Catalog, csrf: str, lecturers: list[dict[str, Any]]) -> str:
    """The lecturers' table and the form for a new one."""
    rows = []
    for r in lecturers:
        ident = f'<input type="hidden" name="lecturer" value="{r["id"]}">'
        rename = _form(
            csrf,
            "rename_lecturer",
            ident
            + _name_input(words, r["name"], _e(words, "console.admin.name_of", name=r["name"])),
            _e(words, "console.rename"),
        )
        relink = _form(
            csrf,
            "relink",
            ident,
            _e(words, "console.admin.relink"),
            f' data-confirm="{_e(words, "console.admin.confirm_relink", name=r["name"])}"',
        )
        retire = (
            ""
            if r["retired"]
            else _form(
                csrf,
                "retire",
                ident,
                _e(words, "console.admin.retire"),
                f' data-confirm="{_e(words, "console.admin.confirm_retire", name=r["name"])}"',
            )
        )
        state = _e(words, "console.admin.retired" if r["retired"] else "console.admin.active")
        rows.append([str(r["id"]), rename, str(r["classes"]), state, relink + retire])
    heads = [
        _e(words, k)
        for k in (
            "console.admin.id",
            "class.label.name",
            "class.admin.classes",
            "console.admin.state",
            "console.admin.actions",
        )
    ]
    new = _form(
        csrf,
        "lecturer",
        f'<label for="lname">{_e(words, "class.admin.new_lecturer")}</label> '
        f'<input id="lname" name="name" maxlength="{TITLE_MAX}" required> ',
        _e(words, "class.admin.create"),
    )
    return (
        f'<section id="lecturers"><h2>{_e(words, "class.admin.lecturers")}</h2>'
        f"{table(heads, rows, 'lecturer-table')}{new}</section>"
    )


async def _classes(
    request: Request, hub: Hub, words: Catalog, csrf: str, lecturers: list[dict[str, Any]]
) -> str:
    """The classes' table (archived ones marked) and the form for a new one."""
    names = {row["id"]: row["name"] for row in lecturers}
    archived = await hub.db(hub.store.archived_rooms)
    rows = []
    for r in await listed_rooms(hub):
        doc = class_doc(request, r)
        ident = f'<input type="hidden" name="class" value="{r["id"]}">'
        rename = _form(
            csrf,
            "rename_class",
            ident
            + _name_input(words, r["name"], _e(words, "console.admin.name_of", name=r["name"])),
            _e(words, "console.rename"),
        )
        gone = r["id"] in archived
        what = "unarchive" if gone else "archive"
        arch = _form(csrf, what, ident, _e(words, f"console.admin.{what}"))
        links = (  # buttons: a finger's 44 px
            f'<a class="button" href="{html.escape(doc["join"])}">'
            f"{_e(words, 'console.admin.join')}</a> "
            f'<a class="button" href="{html.escape(doc["projector"])}">'
            f"{_e(words, 'class.lecturer.projector')}</a>"
        )
        state = _e(words, "console.admin.archived" if gone else "console.admin.active")
        rows.append(
            [
                f'<span class="code">{html.escape(r["code"])}</span>',
                rename,
                html.escape(names.get(r["lecturer"], "—")),
                state,
                links,
                arch,
            ]
        )
    heads = [
        _e(words, k)
        for k in (
            "console.lecturer.join_code",
            "class.label.name",
            "class.admin.lecturer",
            "console.admin.state",
            "console.admin.links",
            "console.admin.actions",
        )
    ]
    options = "".join(
        f'<option value="{r["id"]}">{html.escape(r["name"])}</option>'
        for r in lecturers
        if not r["retired"]
    )
    new = _form(
        csrf,
        "class",
        f'<label for="cname">{_e(words, "class.admin.new_class")}</label> '
        f'<input id="cname" name="name" maxlength="{TITLE_MAX}" required> '
        f'<select name="lecturer" aria-label="{_e(words, "class.admin.lecturer")}">{options}'
        "</select> ",
        _e(words, "class.admin.create"),
    )
    return (
        f'<section id="classes"><h2>{_e(words, "class.admin.classes")}</h2>'
        f"{table(heads, rows, 'class-table')}{new}</section>"
    )


ROUTES = [
    Route("/admin", admin_page, methods=["GET"]),
    Route("/admin", admin_post, methods=["POST"]),
]
