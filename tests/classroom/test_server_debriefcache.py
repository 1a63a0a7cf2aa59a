"""Issue 46: the debrief kept built, serialized and gzip-compressed with an ETag: a repeat
is 304, a student's own part is theirs, and any change the lecturer makes is seen at once."""

from __future__ import annotations

import gzip
import json

import httpx
from classhelp import SEED, Server, join, open_challenge, variant

from evapcool.game.replay import encode


def _get(server: Server, headers: dict[str, str] | None = None) -> httpx.Response:
    return httpx.get(server.base + "/api/debrief", headers=headers or {})


def test_the_debrief_is_kept_compressed_with_an_etag(server: Server) -> None:
    challenge = open_challenge(server)["id"]
    wins = [k for k in range(1, 12) if variant(SEED, k).won][:2]
    students = {}
    for k in wins:
        who = join(server, f"Ada{k}")
        body = {"challenge": challenge, "code": encode(variant(SEED, k))}
        sent = httpx.post(server.base + "/api/submit", json=body, headers=who, timeout=60)
        assert sent.status_code == 200, sent.text
        students[sent.json()["entry"]] = who
    httpx.post(server.base + "/api/challenge/close", headers=server.lecturer)
    first = _get(server, {"Accept-Encoding": "gzip"})
    assert first.status_code == 200 and first.headers["content-encoding"] == "gzip"
    doc = first.json()
    assert doc["you"] is None and {g["entry"] for g in doc["games"]} == set(students)
    tag = first.headers["etag"]
    assert _get(server, {"If-None-Match": tag}).status_code == 304
    plain = _get(server, {"Accept-Encoding": "identity"})
    assert "content-encoding" not in plain.headers and plain.json() == doc
    # each student's own place, in one valid gzip stream with the shared part
    for entry, who in students.items():
        url, asks = server.base + "/api/debrief", {**who, "Accept-Encoding": "gzip"}
        with httpx.stream("GET", url, headers=asks) as raw:
            mine = json.loads(gzip.decompress(b"".join(raw.iter_raw())))  # bytes as sent
        assert mine["you"]["entry"] == entry and mine["games"] == doc["games"]
        assert raw.headers["etag"] != tag
        assert _get(server, {**who, "If-None-Match": raw.headers["etag"]}).status_code == 304
    # a change of the lecturer's is seen at once (never the kept one)
    pick = next(iter(students))
    changed = httpx.post(server.base + "/api/debrief", json={"pick": pick}, headers=server.lecturer)
    assert changed.status_code == 200, changed.text
    again = _get(server, {"If-None-Match": tag})
    assert again.status_code == 200 and again.json()["showing"]["pick"] == pick
    httpx.post(server.base + "/api/debrief", json={"anonymous": True}, headers=server.lecturer)
    hidden = _get(server).json()
    assert all(g["name"] is None for g in hidden["games"]) and hidden["anonymous"] is True


def test_many_asking_at_once_cost_one_build() -> None:
    import asyncio
    from types import SimpleNamespace

    from evapcool.classroom.debrief_cache import DebriefCache

    builds = []

    async def run() -> list[object]:
        cache, hub = DebriefCache(), SimpleNamespace(generation={})

        async def make() -> object:
            builds.append(1)
            await asyncio.sleep(0.05)  # a build that takes a while: the others wait for it
            return object()

        got = await asyncio.gather(*(cache.get(hub, (1, 1, False), make) for _ in range(300)))  # type: ignore[arg-type]
        got.append(await cache.get(hub, (1, 1, False), make))  # type: ignore[arg-type]
        hub.generation[1] = 1  # the room announced a change: built anew
        got.append(await cache.get(hub, (1, 1, False), make))  # type: ignore[arg-type]
        return got

    got = asyncio.run(run())
    assert len(builds) == 2
    assert len({id(g) for g in got[:301]}) == 1 and got[301] is not got[0]


def test_a_board_sent_while_a_debrief_is_built_keeps_it() -> None:
    """Sending a room's board changes nothing: a debrief built meanwhile is kept (it was
    rebuilt by the next asker, seconds in a full hall); a change announced makes it stale."""
    import asyncio

    from evapcool.classroom.debrief_cache import DebriefCache
    from evapcool.classroom.hub import Hub

    builds = []

    async def run() -> None:
        hub = Hub.__new__(Hub)  # the state send and changed use, no store: nobody listens
        hub.sent_at, hub.generation, hub.listeners, hub.pending = {}, {}, [], set()
        hub.wake = asyncio.Event()
        cache = DebriefCache()

        async def make() -> object:
            builds.append(1)
            await hub.send(1)  # the board goes out while the debrief is built
            return object()

        first = await cache.get(hub, (1, 1, False), make)
        assert await cache.get(hub, (1, 1, False), make) is first
        hub.changed(1)  # another process (or this one) changed the room's games
        assert await cache.get(hub, (1, 1, False), make) is not first
        hub.changed(None)  # the store was away: any room may have changed
        await cache.get(hub, (1, 1, False), make)

    asyncio.run(run())
    assert len(builds) == 3
