"""The lecturer: their page, opening and closing challenges, hiding and renaming students,
the replay on the projector, the entries and the class's past challenges."""

from __future__ import annotations

import asyncio
from typing import Any

from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response

from evapcool.classroom import pages
from evapcool.classroom.boards import challenge_info, keyed_replay
from evapcool.classroom.challenge import challenge_doc, parse_challenge
from evapcool.classroom.debrief import Showing
from evapcool.classroom.errors import RefusedError, read_json
from evapcool.classroom.session import LECTURER_COOKIE, adopt, csrf_token
from evapcool.classroom.store import NAME_MAX, NameTakenError
from evapcool.classroom.tokens import projector_key, room_projector_key
from evapcool.classroom.verifier import reference_frames
from evapcool.classroom.views.common import (
    _base,
    _challenge_asked,
    _entry_id,
    _lecturer_token,
    _room_doc,
    _show,
    debrief_state,
    lecturer,
)
from evapcool.classroom.words import raw


async def lecturer_page(request: Request) -> Response:
    """The lecturer's page (403 without the lecturer's token); a link's ?token= is taken
    into the cookie and the browser sent here without it (session.adopt). A department's
    lecturers get the list of their classes at /lecturer instead (department.py)."""
    hub, room = await lecturer(request, query=True)
    token = _lecturer_token(request, query=True)
    if request.query_params.get("token"):
        return adopt(request, LECTURER_COOKIE, token)
    words = hub.words.of(request)
    if room["lecturer"] is None:
        key = projector_key(token)
    else:
        key = room_projector_key(room["digest"], room["code"])
    department = bool(request.app.state.department) and room["lecturer"] is not None
    text = pages.lecturer_page(
        lambda k: raw(words, k),
        words.locale,
        words.meta["direction"],
        key,
        _base(room),
        "/lecturer" if department else "",
        name=str(room["name"] or ""),
        code=str(room["code"]) if department else "",
        csrf=csrf_token(token),
    )
    headers = {"Content-Security-Policy": pages.LECTURER_POLICY, "Cache-Control": "no-store"}
    return HTMLResponse(text, headers=headers)


async def _open_class(hub: Any, room: dict[str, Any]) -> None:
    """409 if the class is archived (its records stay; no new round)."""
    if await hub.db(hub.store.archived, room["id"]):
        raise RefusedError(409, "class", "console.error.archived")


async def open_challenge(request: Request) -> Response:
    """Open a challenge (closing the one open); the lecturer's."""
    hub, room = await lecturer(request)
    await _open_class(hub, room)
    new = parse_challenge(await read_json(request, hub.limits.body_bytes))
    max_frames = new.max_frames
    if max_frames is None:  # a real game's length on these settings, with a margin
        loop = asyncio.get_running_loop()
        max_frames = await loop.run_in_executor(hub.pool, reference_frames, new.settings, new.seed)
    cid = await hub.db(
        hub.store.open_challenge,
        new.settings,
        new.seed,
        max_frames,
        new.attempts,
        new.closes_at,
        new.lost,
        room["id"],
    )
    await hub.db(hub.store.set_showing, room["id"], None)
    state = await debrief_state(hub, room["id"])
    fresh = Showing(anonymous=state.anonymous).to_json()
    await hub.db(hub.store.set_debrief_state, room["id"], fresh)
    await hub.publish(room["id"])
    row = await hub.db(hub.store.challenge, cid, room["id"])
    assert row is not None
    return JSONResponse(challenge_doc(row))


async def close_challenge(request: Request) -> Response:
    """Close the open challenge; the lecturer's."""
    hub, room = await lecturer(request)
    row = await hub.db(hub.store.open_one, room["id"])
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    await hub.db(hub.store.close_challenge, row["id"])
    await hub.publish(room["id"])
    return JSONResponse({"id": row["id"], "open": False})


async def hide(request: Request) -> Response:
    """Hide the student of an entry: all their entries, later ones too, leave the board
    ({"entry", "hidden": false} puts them back: the lecturer's undo)."""
    hub, room = await lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    entry = _entry_id(doc)
    hidden = doc.get("hidden", True)
    if not isinstance(hidden, bool):
        raise RefusedError(400, "hidden", "class.error.value", allowed="true, false")
    if not await hub.db(hub.store.hide, entry, hidden, room["id"]):
        raise RefusedError(404, "entry", "class.error.no_entry")
    player = await hub.db(hub.store.entry_player, entry, room["id"])
    showing = await hub.db(hub.store.showing, room["id"])
    if hidden and showing and showing["player"] == player:
        await hub.db(hub.store.set_showing, room["id"], None)
    await hub.publish(room["id"])
    return JSONResponse({"entry": entry, "hidden": hidden})


async def rename(request: Request) -> Response:
    """Rename the student of an entry ({entry, name}); the name as at joining."""
    hub, room = await lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    entry = _entry_id(doc)
    try:
        name = await hub.db(hub.store.rename, entry, doc.get("name"), room["id"])
    except NameTakenError as taken:
        raise RefusedError(409, "name", "class.error.name_taken", name=taken.name) from None
    except ValueError:
        raise RefusedError(400, "name", "class.error.name", n=NAME_MAX) from None
    if name is None:
        raise RefusedError(404, "entry", "class.error.no_entry")
    showing = await hub.db(hub.store.showing, room["id"])
    if showing and showing["player"] == await hub.db(hub.store.entry_player, entry, room["id"]):
        await hub.db(hub.store.set_showing, room["id"], {**showing, "name": name})
    await hub.publish(room["id"])
    return JSONResponse({"entry": entry, "name": name})


async def show(request: Request) -> Response:
    """Put an entry's replay on the projector ({"entry": null} takes it off)."""
    hub, room = await lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    await _show(hub, room["id"], None if doc.get("entry") is None else _entry_id(doc))
    await hub.publish(room["id"])
    return JSONResponse({"replay": await hub.db(keyed_replay, hub.store, room["id"])})


async def entries(request: Request) -> Response:
    """Every entry of the current (or ?challenge=) challenge, hidden ones too (the
    lecturer's list)."""
    hub, room = await lecturer(request)
    row = await _challenge_asked(request, hub, room)
    if row is None:
        return JSONResponse({"challenge": None, "entries": [], "rejected": 0})
    listed = await hub.db(hub.store.entries, row["id"])
    doc = challenge_info(row)
    showing = await hub.db(hub.store.showing, room["id"])
    return JSONResponse(
        {
            "challenge": doc,
            "entries": listed,
            "rejected": row["rejected"],
            "showing": showing["entry"] if showing else None,
        }
    )


async def challenges(request: Request) -> Response:
    """The class's challenges, newest first, with games and students counted (the term)."""
    hub, room = await lecturer(request, query=True)
    rows = await hub.db(hub.store.challenges, room["id"])
    listed = [
        {
            **challenge_info(r),
            "games": r["games"],
            "students": r["students"],
            "rejected": r["rejected"],
        }
        for r in rows
    ]
    return JSONResponse({"class": _room_doc(room), "challenges": listed})
