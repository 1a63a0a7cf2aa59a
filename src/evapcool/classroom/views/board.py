"""The board and its event stream: the projector's page (QR code of the join address), the
leaderboard, and its Server-Sent Events."""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator

from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response, StreamingResponse

from evapcool.classroom import pages
from evapcool.classroom.boards import _board, _is_open, phone_text, rounds_of
from evapcool.classroom.errors import RefusedError
from evapcool.classroom.halls import stream_refusal
from evapcool.classroom.hub import Hub, Listener
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.views.common import (
    _base,
    _challenge_asked,
    address,
    guard,
    join_url_of,
    keyed,
    lecturer,
    room_of,
    student_of,
)
from evapcool.classroom.words import raw

#: Seconds between keep-alive comments on an idle event stream.
KEEP_ALIVE = 15.0


async def projector(request: Request) -> Response:
    """The projector page: QR code of the join address, the live leaderboard (with the
    projector's key in ?key=, the replays' codes too)."""
    hub = guard(request)
    room = await room_of(request, hub)
    await keyed(request, hub, room)
    words = hub.words.of(request)
    join_url = join_url_of(request, room)
    svg = _qr_svg(join_url)
    # A department's class: its join code, typed on the join page at the short address.
    code = room["code"] if room["id"] != DEFAULT_ROOM else None
    short = _short(join_url if code is None else join_url.removesuffix(f"{_base(room)}/"))
    text = pages.projector_page(
        lambda k: raw(words, k),
        words.locale,
        words.meta["direction"],
        join_url,
        svg,
        _base(room),
        getattr(request.app.state, "lan_command", None),
        join=(code, short),
    )
    headers = {"Content-Security-Policy": pages.PROJECTOR_POLICY, "Cache-Control": "no-store"}
    return HTMLResponse(text, headers=headers)


def _short(url: str) -> str:
    """An address as said aloud: no scheme, no trailing slash."""
    return url.split("://", 1)[-1].rstrip("/")


def _qr_svg(url: str) -> str:
    """The QR code of a URL as inline SVG (dark modules on white)."""
    import segno

    # No fixed size (a viewBox instead): the projector's style scales it to the screen.
    svg: str = segno.make(url, error="m").svg_inline(
        omitsize=True, border=2, dark="#000", light="#fff"
    )
    return svg


async def leaderboard(request: Request) -> Response:
    """The current challenge's leaderboard (the replay's code as for the stream), or a
    closed past round's (?challenge=: its board kept; 409 while open, 404 not the class's)."""
    hub = guard(request)
    room = await room_of(request, hub)
    with_key = await keyed(request, hub, room)
    if request.query_params.get("challenge") is None:
        return JSONResponse(await hub.board(room["id"], with_key))
    row = await _challenge_asked(request, hub, room)
    if _is_open(row):
        raise RefusedError(409, "challenge", "class.error.debrief_open")
    return JSONResponse(await hub.db(_board, hub.store, room["id"], with_key, row["id"]))


async def rounds(request: Request) -> Response:
    """The class's closed rounds, newest first, for the projector's history (its key, or
    the lecturer's token as Bearer: 403 otherwise)."""
    hub = guard(request)
    room = await room_of(request, hub)
    if not await keyed(request, hub, room):
        await lecturer(request)
    return JSONResponse({"rounds": await hub.db(rounds_of, hub.store, room["id"])})


async def stream(request: Request) -> Response:
    """Server-Sent Events: the leaderboard at connect and after every change."""
    hub = guard(request)
    room = await room_of(request, hub)
    with_key = await keyed(request, hub, room)
    # A student's stream (?token=) counts against the token, a hall's against its class.
    token = None if with_key else await student_of(request, hub, room["id"])
    refused = stream_refusal(
        hub.limits, hub.listeners, address(request), room["id"], with_key, token
    )
    if refused:
        raise refused
    listener = Listener(asyncio.Queue(maxsize=4), address(request), with_key, room["id"])
    listener.key = request.query_params.get("key") if with_key else None
    listener.token = token
    hub.listeners.append(listener)
    if token is None:
        first = json.dumps(await hub.board(room["id"], with_key))
    else:  # a joined student's page: the board with its own row alone (hub.send)
        board, mine = await hub.phones_board(room["id"])
        first = phone_text(board, mine.get(token))
    return StreamingResponse(
        _events(hub, listener, first),
        media_type="text/event-stream",
        headers={"Cache-Control": "no-cache", "X-Accel-Buffering": "no"},
    )


async def _events(hub: Hub, listener: Listener, first: str) -> AsyncIterator[str]:
    """The event stream of one listener; a comment every KEEP_ALIVE seconds when idle."""
    try:
        yield f"data: {first}\n\n"
        while True:
            try:
                text = await asyncio.wait_for(listener.queue.get(), KEEP_ALIVE)
            except asyncio.TimeoutError:
                yield ": keep-alive\n\n"
                continue
            if listener.closed:  # its key went stale (streamkeys)
                return
            yield f"data: {text}\n\n"
    finally:
        hub.listeners.remove(listener)
