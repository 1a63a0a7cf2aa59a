"""The debrief built once per close (and again after any change the room announces: the
anonymous mode, a pick, a hidden student), off the event loop, kept serialized and
gzip-compressed with an ETag (304 on a repeat): 300 phones asking at the close cost one
build. The student's own part (`you`) is a few bytes added to the shared document: the
compressor's state after the shared part is kept, so each student's answer is still one
gzip stream without compressing the megabyte again."""

from __future__ import annotations

import asyncio
import hashlib
import json
import zlib
from collections import OrderedDict
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Any

from starlette.requests import Request
from starlette.responses import Response

from evapcool.classroom.boards import _is_open
from evapcool.classroom.debrief import Law, Showing, debrief_doc
from evapcool.classroom.hub import Hub
from evapcool.classroom.views.common import bearer_token

#: Debriefs kept per process (a room's, per challenge and names shown or not).
KEPT = 64


@dataclass
class Built:
    """A debrief serialized up to its `you`, plain and as the start of a gzip stream."""

    prefix: bytes
    gzip_head: bytes
    compressor: Any  # zlib's compress object after the prefix (copied per answer)
    you: dict[str, bytes]  # a student's token -> their `you` (JSON)
    tag: str


def _build(
    row: dict[str, Any],
    games: list[dict[str, Any]],
    law: Law,
    anonymous: bool,
    showing: dict[str, Any],
) -> Built:
    """The shared document (no viewer) serialized and compressed (run in a thread)."""
    doc = debrief_doc(row, games, law, anonymous, None)
    doc.pop("you", None)
    doc["showing"] = showing
    prefix = json.dumps(doc, separators=(",", ":")).encode()[:-1] + b',"you":'
    you = {
        g["player"]: json.dumps({"entry": g["entry"], "rank": g["rank"]}).encode()
        for g in games
        if g.get("player")
    }
    compressor = zlib.compressobj(6, zlib.DEFLATED, 31)
    head = compressor.compress(prefix) + compressor.flush(zlib.Z_SYNC_FLUSH)
    tag = hashlib.sha256(prefix).hexdigest()[:32]
    return Built(prefix, head, compressor, you, tag)


class DebriefCache:
    """This process's built debriefs; one build at a time per key (others await it)."""

    def __init__(self) -> None:
        self.kept: OrderedDict[tuple[int, int, bool], tuple[int, Built]] = OrderedDict()
        self.building: dict[tuple[int, int, bool], asyncio.Task[Built]] = {}

    async def get(
        self, hub: Hub, key: tuple[int, int, bool], make: Callable[[], Awaitable[Built]]
    ) -> Built:
        generation = hub.generation.get(key[0], 0)
        found = self.kept.get(key)
        if found is not None and found[0] == generation:
            self.kept.move_to_end(key)
            return found[1]
        task = self.building.get(key)
        if task is None:
            task = self.building[key] = asyncio.ensure_future(make())
            task.add_done_callback(lambda _: self.building.pop(key, None))
        built = await asyncio.shield(task)
        if hub.generation.get(key[0], 0) == generation:  # nothing changed while it was built
            self.kept[key] = (generation, built)
            while len(self.kept) > KEPT:
                self.kept.popitem(last=False)
        return built


def _cache(hub: Hub) -> DebriefCache:
    cache = getattr(hub, "debriefs", None)
    if cache is None:
        cache = DebriefCache()
        hub.debriefs = cache  # type: ignore[attr-defined]
    return cache


async def cached_debrief(
    request: Request,
    hub: Hub,
    room: dict[str, Any],
    row: dict[str, Any],
    is_lecturer: bool,
    law_of: Callable[[Hub, dict[str, Any]], Awaitable[Law]],
    state: Showing,
) -> Response:
    """The debrief's answer: built once per change of the room (never while the challenge
    is open: the lecturer's early look is built each time), `you` for a student's token."""
    anonymous = state.anonymous and not is_lecturer

    async def make() -> Built:
        games = await hub.db(hub.store.best_games, row["id"])
        law = await law_of(hub, row)
        return await asyncio.to_thread(_build, row, games, law, anonymous, state.to_json())

    if _is_open(row):
        built = await make()
    else:
        built = await _cache(hub).get(hub, (room["id"], row["id"], anonymous), make)
    viewer = None if is_lecturer else bearer_token(request) or None
    you = built.you.get(viewer, b"null") if viewer else b"null"
    return _answer(request, built, you)


def _answer(request: Request, built: Built, you: bytes) -> Response:
    """200 (gzip if the client takes it) or 304 if the client has this very document."""
    tag = f'"{built.tag}-{hashlib.sha256(you).hexdigest()[:12]}"'
    headers = {
        "ETag": tag,
        "Cache-Control": "private, no-cache",
        "Vary": "Accept-Encoding, Authorization",
    }
    asked = request.headers.get("if-none-match", "")
    if tag in (t.strip() for t in asked.split(",")):
        return Response(status_code=304, headers=headers)
    tail = you + b"}"
    if "gzip" in request.headers.get("accept-encoding", "").lower():
        compressor = built.compressor.copy()
        body = built.gzip_head + compressor.compress(tail) + compressor.flush()
        headers["Content-Encoding"] = "gzip"
    else:
        body = built.prefix + tail
    return Response(body, media_type="application/json", headers=headers)
