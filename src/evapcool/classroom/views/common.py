"""What every room of the class server asks of a request: the Hub (within the client's
rate), the class it is for, the lecturer's token, the projector's key; the entry and the
challenge a request names, and the replay the projector plays."""

from __future__ import annotations

import secrets
from typing import Any

from starlette.requests import Request

from evapcool.classroom.boards import showing_of
from evapcool.classroom.debrief import Showing
from evapcool.classroom.errors import RefusedError
from evapcool.classroom.halls import KEY, LECTURER, STUDENT, client_address, student_token, take
from evapcool.classroom.hub import Hub
from evapcool.classroom.numbers import whole_number
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.session import CSRF_HEADER, LECTURER_COOKIE, check_csrf
from evapcool.classroom.tokens import (
    LECTURER_SECRET,
    PROJECTOR_SECRET,
    matches_digest,
    room_projector_key,
)
from evapcool.game.replay import decode


def hub_of(request: Request) -> Hub:
    """The app's Hub."""
    hub: Hub = request.app.state.hub
    return hub


def bearer_token(request: Request) -> str:
    """The Bearer token of a request ('' if none)."""
    auth = request.headers.get("authorization", "")
    return auth[7:].strip() if auth.lower().startswith("bearer ") else ""


def address(request: Request) -> str:
    """The client's address (a class behind one NAT address shares it)."""
    return client_address(request)


def guard(request: Request) -> Hub:
    """The Hub, after the request's rate is checked (429 over it): its student's token's,
    projector key's or lecturer's when this process has checked it, else its address's."""
    hub = hub_of(request)
    take(hub.buckets, request)
    return hub


async def student_of(request: Request, hub: Hub, room: int) -> str | None:
    """The student's token a request gives (Bearer, or ?token= on the stream) if it is one
    of this class's, else None; remembered as checked (its limits follow it from now on)."""
    token = student_token(request)
    if not 0 < len(token) <= 64:
        return None
    if hub.buckets.known.of(token) == (STUDENT, room):
        return token
    if await hub.db(hub.store.player_name, token, room) is None:
        return None
    hub.buckets.known.note(token, STUDENT, room)
    return token


async def room_of(request: Request, hub: Hub) -> dict[str, Any]:
    """The class a request is for: /c/{code}/... names it, the other paths are the single
    class's (404 naming "class" for an unknown code)."""
    given = request.path_params.get("code")
    if given is None:
        room = await hub.db(hub.store.room, DEFAULT_ROOM)
    else:
        from evapcool.classroom.guessing import room_by_given_code

        room = await room_by_given_code(hub, address(request), str(given))
    if room is None:
        raise RefusedError(404, "class", "class.error.no_class")
    if hub.buckets.known.of(student_token(request)) is None:
        await student_of(request, hub, room["id"])  # its next requests count against it
    return room


async def _lecturer_digest(hub: Hub, room: dict[str, Any]) -> str | None:
    """The digest of the token that may act on a class: its lecturer's, or (the single
    class, no lecturer) the one `evapcool class` made."""
    if room["lecturer"] is None:
        return await hub.db(hub.store.secret, LECTURER_SECRET)
    return str(room["digest"])


async def lecturer(request: Request, query: bool = False) -> tuple[Hub, dict[str, Any]]:
    """The Hub and the class if the request carries the class's lecturer's token, else
    403 (another lecturer's token too); a token from the cookie alone must come with the
    page's CSRF token on anything but a GET."""
    hub = guard(request)
    room = await room_of(request, hub)
    token = _lecturer_token(request, query)
    if not matches_digest(token, await _lecturer_digest(hub, room)):
        raise RefusedError(403, "token", "class.error.lecturer")
    hub.buckets.known.note(token, LECTURER, room["id"])
    if request.method not in ("GET", "HEAD") and not bearer_token(request):
        check_csrf(token, request.headers.get(CSRF_HEADER, ""))
    return hub, room


def _lecturer_token(request: Request, query: bool) -> str:
    """The token a request gives: as Bearer, or (query=True, the pages) in ?token=, or
    the cookie its link left in the browser."""
    given = bearer_token(request) or (request.query_params.get("token", "") if query else "")
    return given or request.cookies.get(LECTURER_COOKIE, "")


async def keyed(request: Request, hub: Hub, room: dict[str, Any]) -> bool:
    """Whether the request holds the class's projector key (?key=); 403 for a wrong one."""
    given = request.query_params.get("key")
    if given is None:
        return False
    if room["lecturer"] is None:
        ok = matches_digest(given, await hub.db(hub.store.secret, PROJECTOR_SECRET))
    else:
        ok = secrets.compare_digest(given, room_projector_key(room["digest"], room["code"]))
    if not ok:
        raise RefusedError(403, "key", "class.error.key")
    hub.buckets.known.note(given, KEY, room["id"])
    return True


def _base(room: dict[str, Any]) -> str:
    """The path prefix of a class's pages and API ('' for the single class's)."""
    return "" if room["id"] == DEFAULT_ROOM else f"/c/{room['code']}"


def join_url_of(request: Request, room: dict[str, Any]) -> str:
    """The students' address of a class: the one given at start (or the one this page was
    read at), and the class's path."""
    root = (request.app.state.join_url or str(request.base_url)).rstrip("/")
    return f"{root}{_base(room)}/"


def _room_doc(room: dict[str, Any]) -> dict[str, Any]:
    """What the API says of a class (never its lecturer's digest)."""
    return {"code": room["code"], "name": room["name"], "path": _base(room) + "/"}


def _entry_id(doc: dict[str, Any]) -> int:
    """The entry a lecturer's action names (400 if not a whole number SQLite can hold)."""
    entry = doc.get("entry")
    if not isinstance(entry, int) or isinstance(entry, bool) or not 0 < entry < 2**63:
        raise RefusedError(400, "entry", "class.error.no_entry")
    return entry


async def _challenge_asked(request: Request, hub: Hub, room: dict[str, Any]) -> Any:
    """The challenge ?challenge= names (a past one of the class's), else the current one
    (None if the class has none); 400 for what is not an id, 404 for one not of this class."""
    asked = request.query_params.get("challenge")
    if asked is None:
        return await hub.db(hub.store.latest, room["id"])
    row = await hub.db(hub.store.challenge, whole_number(asked, "challenge"), room["id"])
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    return row


def moves_summary(code: str) -> dict[str, Any]:
    """What the projector says of a game's moves: frames, trap moves, first and last height."""
    rec = decode(code)
    heights = [h for h, _ in rec.moves]
    return {
        "frames": rec.frames,
        "runs": len(rec.moves),
        "score": rec.score,
        "first": f"{heights[0]:.0f}" if heights else "-",
        "last": f"{heights[-1]:.0f}" if heights else "-",
    }


async def _show(hub: Hub, room: int, entry: int | None) -> None:
    """The replay a room's projector plays: an entry's of the room (404 if none), or none."""
    showing = None
    if entry is not None:
        found = await hub.db(hub.store.entry_code, entry, room)
        if found is None:
            raise RefusedError(404, "entry", "class.error.no_entry")
        name, code, challenge = found
        showing = {
            "entry": entry,
            "name": name,
            "code": code,
            "summary": moves_summary(code),
            "challenge": challenge,
            "player": await hub.db(hub.store.entry_player, entry, room),
        }
    await hub.db(hub.store.set_showing, room, showing)


async def debrief_state(hub: Hub, room: int) -> Showing:
    """What a room's lecturer set the debrief to show (in the store: every process sees it)."""
    return showing_of(await hub.db(hub.store.debrief_state, room))
