"""The debrief (issue 36): every student's best game's path and the archetypes, the pair set
side by side, and the lecturer's choice of what the projector shows."""

from __future__ import annotations

import asyncio
from typing import Any

from starlette.requests import Request
from starlette.responses import JSONResponse, Response

from evapcool.classroom.boards import _is_open
from evapcool.classroom.debrief import Law, Showing, every_frame, law_of
from evapcool.classroom.debrief_cache import cached_debrief
from evapcool.classroom.errors import RefusedError, read_json
from evapcool.classroom.hub import Hub
from evapcool.classroom.tokens import matches_digest
from evapcool.classroom.views.common import (
    _challenge_asked,
    _entry_id,
    _lecturer_digest,
    _lecturer_token,
    _show,
    debrief_state,
    guard,
    lecturer,
    room_of,
)


async def _debrief_challenge(
    request: Request, hub: Hub
) -> tuple[dict[str, Any], dict[str, Any], bool]:
    """The class, the challenge debriefed (the current one, or a past round's by
    ?challenge=: every closed round keeps its debrief) and whether its lecturer asks: 409
    while it is open, unless the lecturer asks (their early look; the projector and
    students wait for the close)."""
    room = await room_of(request, hub)
    # The lecturer's token as Bearer or in the cookie their link left (issue 45).
    token = _lecturer_token(request, False)
    is_lecturer = matches_digest(token, await _lecturer_digest(hub, room))
    row = await _challenge_asked(request, hub, room)
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    if _is_open(row) and not is_lecturer:
        raise RefusedError(409, "challenge", "class.error.debrief_open")
    return room, row, is_lecturer


async def _state_of(hub: Hub, room: dict[str, Any], row: dict[str, Any]) -> Showing:
    """What the lecturer set the debrief to show; for a past round only its names hidden
    or not (the game picked and the pair are the latest round's)."""
    state = await debrief_state(hub, room["id"])
    latest = await hub.db(hub.store.latest, room["id"])
    return state if latest and latest["id"] == row["id"] else Showing(state.anonymous)


async def _law(hub: Hub, row: dict[str, Any]) -> Law:
    """The critical line of a challenge (computed once, in a worker)."""
    if row["id"] not in hub.laws:
        loop = asyncio.get_running_loop()
        law = await loop.run_in_executor(hub.pool, law_of, row["settings"], row["seed"])
        hub.laws[row["id"]] = law
    return hub.laws[row["id"]]


async def debrief(request: Request) -> Response:
    """The debrief document: every student's best game's path, the archetypes, and (with a
    student's token) `you`. Names left out in anonymous mode, except for the lecturer."""
    hub = guard(request)
    room, row, is_lecturer = await _debrief_challenge(request, hub)
    state = await _state_of(hub, room, row)
    return await cached_debrief(request, hub, room, row, is_lecturer, _law, state)  # issue 46


async def debrief_pair(request: Request) -> Response:
    """The two games the lecturer set side by side: their paths at every frame, codes."""
    hub = guard(request)
    room, row, is_lecturer = await _debrief_challenge(request, hub)
    state = await _state_of(hub, room, row)
    if state.pair is None:
        raise RefusedError(404, "pair", "class.error.no_entry")
    loop = asyncio.get_running_loop()
    ranks = {g["entry"]: g["rank"] for g in await hub.db(hub.store.best_games, row["id"])}
    games = []
    for entry in state.pair:
        found = await hub.db(hub.store.entry_code, entry, room["id"])
        if found is None or found[2] != row["id"]:
            raise RefusedError(404, "pair", "class.error.no_entry")
        if entry not in hub.pair_paths:
            path = await loop.run_in_executor(hub.pool, every_frame, found[1])
            hub.pair_paths[entry] = path
        name = None if state.anonymous and not is_lecturer else found[0]
        path = hub.pair_paths[entry]
        # The code: the projector plays both replays in step (codes are public once closed).
        game = {"entry": entry, "name": name, "rank": ranks.get(entry), "path": path}
        games.append({**game, "code": found[1]})
    return JSONResponse({"challenge": row["id"], "games": games})


def _pair_of(doc: dict[str, Any]) -> tuple[int, int] | None:
    """The pair a lecturer names: two different entries, or null (400 otherwise)."""
    pair = doc.get("pair")
    if pair is None:
        return None
    if not isinstance(pair, list) or len(pair) != 2 or pair[0] == pair[1]:
        raise RefusedError(400, "pair", "class.error.value", allowed="[entry, entry]")
    a, b = (_entry_id({"entry": e}) for e in pair)
    return (a, b)


async def set_debrief(request: Request) -> Response:
    """The lecturer sets the debrief: {anonymous: bool, pick: entry | null (its replay on
    the projector, in the pair's place), pair: [entry, entry] | null (side by side)};
    fields left out stay."""
    hub, room = await lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    state = await debrief_state(hub, room["id"])
    anonymous = doc.get("anonymous", state.anonymous)
    if not isinstance(anonymous, bool):
        raise RefusedError(400, "anonymous", "class.error.value", allowed="true, false")
    pick, pair = state.pick, state.pair
    if "pick" in doc:
        pick = None if doc["pick"] is None else _entry_id({"entry": doc["pick"]})
        await _show(hub, room["id"], pick)
        pair = None  # the picked game's replay takes the pair's place
    if "pair" in doc:
        pair = _pair_of(doc)
        for entry in pair or ():
            if await hub.db(hub.store.entry_code, entry, room["id"]) is None:
                raise RefusedError(404, "pair", "class.error.no_entry")
    new = Showing(anonymous, pick, pair)
    await hub.db(hub.store.set_debrief_state, room["id"], new.to_json())
    await hub.publish(room["id"])
    return JSONResponse(new.to_json())
