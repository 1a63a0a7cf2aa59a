"""Join and play: the game page in class mode, the open challenge, a student's join, their
standing, and their games sent to be verified."""

from __future__ import annotations

import asyncio
import time
from typing import Any

from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response

from evapcool.classroom import pages
from evapcool.classroom.boards import _is_open
from evapcool.classroom.challenge import challenge_doc
from evapcool.classroom.errors import RefusedError, read_json
from evapcool.classroom.halls import STUDENT
from evapcool.classroom.hub import Hub
from evapcool.classroom.store import NAME_MAX, ClassFullError, NameTakenError
from evapcool.classroom.verifier import check_submission, code_chars_ok
from evapcool.classroom.views.common import _base, address, bearer_token, guard, room_of


async def game(request: Request) -> Response:
    """The browser edition in class mode (a department's root is its join page instead)."""
    hub = guard(request)
    room = await room_of(request, hub)
    text, policy = pages.game_page(_base(room) + "/api")
    # The projector plays replays in the game page in a frame of its own (same origin).
    headers = {"Content-Security-Policy": policy, "X-Frame-Options": "SAMEORIGIN"}
    return HTMLResponse(text, headers=headers)


async def get_challenge(request: Request) -> Response:
    """The open challenge, or 404."""
    hub = guard(request)
    room = await room_of(request, hub)
    row = await hub.db(hub.store.open_one, room["id"])
    if not _is_open(row):
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    assert row is not None
    return JSONResponse(challenge_doc(row))


async def join(request: Request) -> Response:
    """A student's token for a name (cleaned: visible characters, at most NAME_MAX, not
    looking like another student's), within the address's join rate and the class's bound.

    With the token of an earlier join ("token"), that student again, by the name the
    server has (an applet started anew keeps its place and name); a token of another class
    is not known here (each class keeps its own student, the page and the desktop keep one
    token per class). The answer names the class (its join code) the token is for.
    """
    hub = guard(request)
    room = await room_of(request, hub)
    doc = await read_json(request, hub.limits.body_bytes)
    earlier = doc.get("token")
    if isinstance(earlier, str) and 0 < len(earlier) <= 64:
        known = await hub.db(hub.store.player_name, earlier, room["id"])
        if known is not None:
            hub.buckets.known.note(earlier, STUDENT, room["id"])
            return JSONResponse({"token": earlier, "name": known, "class": room["code"]})
    # Per class and address: a lecture hall joins its class at once, whatever other
    # classes behind the same address (a campus's NAT) do.
    where = f"{room['id']}@{address(request)}"
    wait = await hub.db(hub.store.take, "join", where, hub.limits.join)
    if wait:
        raise RefusedError(429, "client", "class.error.slow_down", retry_after=wait, n=wait)
    try:
        token = await hub.db(hub.store.join, doc.get("name"), hub.limits.students, room["id"])
    except ClassFullError:
        raise RefusedError(409, "class", "class.error.full", n=hub.limits.students) from None
    except NameTakenError as taken:
        raise RefusedError(409, "name", "class.error.name_taken", name=taken.name) from None
    except ValueError:
        raise RefusedError(400, "name", "class.error.name", n=NAME_MAX) from None
    name = await hub.db(hub.store.player_name, token, room["id"])
    hub.buckets.known.note(token, STUDENT, room["id"])  # from now on, its own limits
    return JSONResponse({"token": token, "name": name, "class": room["code"]})


async def _student(request: Request, hub: Hub, room: int) -> str:
    """The student token of a request (401 if none known in this class), within its
    submission rate."""
    token = bearer_token(request)
    if not token or len(token) > 64 or await hub.db(hub.store.player_name, token, room) is None:
        raise RefusedError(401, "token", "class.error.token")
    wait = await hub.db(hub.store.take, "submit", token, hub.limits.submit)
    if wait:
        raise RefusedError(429, "token", "class.error.slow_down", retry_after=wait, n=wait)
    return token


async def _open_for(hub: Hub, doc: dict[str, Any], token: str, room: int) -> dict[str, Any]:
    """The open challenge a submission names, if it may take one more game from `token`."""
    row = await hub.db(hub.store.open_one, room)
    if not _is_open(row):
        raise RefusedError(409, "challenge", "class.error.closed")
    assert row is not None
    if doc.get("challenge") != row["id"]:
        raise RefusedError(409, "challenge", "class.error.other_challenge", id=row["id"])
    limit = row["attempts"]
    if isinstance(limit, int) and await hub.db(hub.store.attempts, row["id"], token) >= limit:
        raise RefusedError(409, "attempts", "class.error.attempts", n=limit)
    return row


async def me(request: Request) -> Response:
    """A student's standing in the current challenge: games sent and accepted of the
    limit, best score and place (the student's page shows them before each game)."""
    hub = guard(request)
    room = await room_of(request, hub)
    token = bearer_token(request)
    name = await hub.db(hub.store.player_name, token, room["id"]) if 0 < len(token) <= 64 else None
    if name is None:
        raise RefusedError(401, "token", "class.error.token")
    row = await hub.db(hub.store.latest, room["id"])
    if row is None:
        return JSONResponse({"name": name, "challenge": None})
    return JSONResponse({"name": name, **await _standing(hub, row, token)})


async def _standing(hub: Hub, row: dict[str, Any], token: str) -> dict[str, Any]:
    """{challenge, attempts (the limit), lost (lost games taken), used, best, best_entry
    (the best's, as the board lists it), rank, count (students on the board)} of a student."""
    got = await hub.db(hub.store.standing, row["id"], token)
    return {"challenge": row["id"], "attempts": row["attempts"], "lost": bool(row["lost"]), **got}


def _game_of(doc: dict[str, Any]) -> tuple[object, str]:
    """The submitted game: (a code, "code") or (a recording, "recording"); else 400.

    A code's characters are checked first (ASCII letters, digits, . - _), before anything
    reads it.
    """
    if doc.get("code") is not None:
        if not isinstance(doc["code"], str):
            raise RefusedError(400, "code", "class.error.no_code")
        if not code_chars_ok(doc["code"]):
            raise RefusedError(400, "code", "class.error.code_chars")
        return doc["code"], "code"
    if isinstance(doc.get("recording"), dict):
        return doc["recording"], "recording"
    raise RefusedError(400, "code", "class.error.no_code")


async def submit(request: Request) -> Response:
    """A game replayed in a worker; 200 only once its entry is committed."""
    hub = guard(request)
    room = (await room_of(request, hub))["id"]
    token = await _student(request, hub, room)
    doc = await read_json(request, hub.limits.body_bytes)
    item, how = _game_of(doc)
    row = await _open_for(hub, doc, token, room)
    loop = asyncio.get_running_loop()

    def verify() -> asyncio.Future[dict[str, Any]]:
        return loop.run_in_executor(hub.pool, check_submission, item, how, row)

    # Served in turn by class and address: a hall behind one address is one turn-taker.
    got = await hub.queue.run(f"{room}@{address(request)}", token, verify)
    if "error" in got:
        await _refuse(hub, row, got["error"])
    result = (got["score"], got["frames"], got["edition"], got["code"], got["moves"])
    entry = await hub.db(
        hub.store.add_if_allowed, row["id"], token, result, time.time(), got["path"]
    )
    if entry == "code":
        await _refuse(hub, row, {"field": "code", "key": "class.error.copied", "args": {}})
    if isinstance(entry, str):
        key = "class.error.attempts" if entry == "attempts" else "class.error.closed"
        raise RefusedError(409, entry, key, n=row["attempts"] or 0)
    await hub.publish(room)
    standing = await _standing(hub, row, token)
    return JSONResponse(
        {"entry": entry, "score": got["score"], "frames": got["frames"], **standing}
    )


async def _refuse(hub: Hub, challenge: dict[str, Any], error: dict[str, Any]) -> None:
    """Count a refused game, tell the boards, and answer 422 naming the field."""
    await hub.db(hub.store.count_rejected, challenge["id"])
    await hub.publish(challenge["room"])
    raise RefusedError(422, error["field"], error["key"], **error["args"])
