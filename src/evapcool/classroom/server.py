"""`evapcool class`'s web server (Starlette): challenges, students, verified games, pages.

Games are replayed in worker processes; a submission is answered 200 only after its entry
is committed to SQLite. Store calls run one at a time on a thread of their own.
"""

from __future__ import annotations

import asyncio
import json
import multiprocessing
import secrets
import time
from collections.abc import AsyncIterator, Callable
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from contextlib import asynccontextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response, StreamingResponse
from starlette.routing import Route

from evapcool.classroom import pages
from evapcool.classroom.challenge import challenge_doc, parse_challenge
from evapcool.classroom.errors import RefusedError, read_json, refused_response
from evapcool.classroom.ratelimit import Rate, RateLimiter
from evapcool.classroom.store import NAME_MAX, Store
from evapcool.classroom.verifier import check_submission, warm
from evapcool.classroom.words import Words, raw
from evapcool.game.replay import decode

T = TypeVar("T")
#: Seconds between keep-alive comments on an idle event stream.
KEEP_ALIVE = 15.0
#: Headers on every answer: no referrer (the lecturer's link holds the token), no sniffing.
SAFE_HEADERS = {
    "Referrer-Policy": "no-referrer",
    "X-Content-Type-Options": "nosniff",
    "X-Frame-Options": "DENY",
}


#: API requests per client address (a class behind one NAT address shares it).
CLIENT_RATE = Rate(burst=600, per_second=100)
#: Submissions per student token.
SUBMIT_RATE = Rate(burst=5, per_second=0.5)


@dataclass(frozen=True)
class Limits:
    """Request limits: body size, request rates, event-stream listeners."""

    body_bytes: int = 256 * 1024
    client: Rate = CLIENT_RATE
    submit: Rate = SUBMIT_RATE
    listeners: int = 1000


@dataclass
class Hub:
    """The server's state: store, pools, tokens, limiters, the streams' queues."""

    store: Store
    lecturer_token: str
    limits: Limits
    pool: ProcessPoolExecutor
    db_thread: ThreadPoolExecutor = field(default_factory=lambda: ThreadPoolExecutor(1))
    words: Words = field(default_factory=Words)
    listeners: set[asyncio.Queue[str]] = field(default_factory=set)
    showing: dict[str, Any] | None = None

    def __post_init__(self) -> None:
        self.per_client = RateLimiter(self.limits.client)
        self.per_token = RateLimiter(self.limits.submit)

    async def db(self, fn: Callable[..., T], *args: Any) -> T:
        """Run a Store call on the store's thread (one at a time, off the event loop)."""
        return await asyncio.get_running_loop().run_in_executor(self.db_thread, fn, *args)

    async def board(self) -> dict[str, Any]:
        """The leaderboard of the current (open, else last) challenge."""
        return await self.db(_board, self.store, self.showing)

    async def publish(self) -> None:
        """Send the leaderboard to every event stream; a slow one keeps only the newest."""
        text = json.dumps(await self.board())
        for queue in list(self.listeners):
            if queue.full():
                queue.get_nowait()
            queue.put_nowait(text)


def _board(store: Store, showing: dict[str, Any] | None) -> dict[str, Any]:
    """The leaderboard document (see docs/class.md)."""
    current = store.latest()
    if current is None:
        return {"challenge": None, "open": False, "entries": [], "rejected": 0, "replay": showing}
    rows = store.leaderboard(int(current["id"]))  # type: ignore[call-overload]
    entries = [
        {"rank": i, "name": r[1], "score": r[2], "frames": r[3], "edition": r[4]}
        for i, r in enumerate(rows, 1)
    ]
    return {
        "challenge": current["id"],
        "open": _is_open(current),
        "entries": entries,
        "rejected": current["rejected"],
        "replay": showing,
    }


def _is_open(challenge: dict[str, Any] | None, now: float | None = None) -> bool:
    """Whether a challenge takes games now (open, and its time window not over)."""
    if challenge is None or not challenge.get("open"):
        return False
    closes = challenge.get("closes_at")
    return closes is None or (time.time() if now is None else now) < closes


def hub_of(request: Request) -> Hub:
    """The app's Hub."""
    hub: Hub = request.app.state.hub
    return hub


def _bearer(request: Request) -> str:
    """The Bearer token of a request ('' if none)."""
    auth = request.headers.get("authorization", "")
    return auth[7:].strip() if auth.lower().startswith("bearer ") else ""


def guard(request: Request) -> Hub:
    """The Hub, after the client's request rate is checked (429 over it)."""
    hub = hub_of(request)
    wait = hub.per_client.take(request.client.host if request.client else "?")
    if wait:
        raise RefusedError(429, "client", "class.error.slow_down", retry_after=wait, n=wait)
    return hub


def lecturer(request: Request, query: bool = False) -> Hub:
    """The Hub if the request carries the lecturer's token, else 403."""
    hub = guard(request)
    given = _bearer(request) or (request.query_params.get("token", "") if query else "")
    if not secrets.compare_digest(given.encode(), hub.lecturer_token.encode()):
        raise RefusedError(403, "token", "class.error.lecturer")
    return hub


# -- pages -------------------------------------------------------------------------------------


async def game(request: Request) -> Response:
    """The browser edition in class mode."""
    guard(request)
    return HTMLResponse(request.app.state.game_html)


async def projector(request: Request) -> Response:
    """The projector page: QR code of the join address, the live leaderboard."""
    hub = guard(request)
    words = hub.words.of(request)
    join_url = request.app.state.join_url or str(request.base_url)
    svg = _qr_svg(join_url)
    text = pages.projector_page(
        lambda k: raw(words, k), words.locale, words.meta["direction"], join_url, svg
    )
    return HTMLResponse(text)


async def lecturer_page(request: Request) -> Response:
    """The lecturer's page (403 without the token in ?token=)."""
    hub = lecturer(request, query=True)
    words = hub.words.of(request)
    text = pages.lecturer_page(lambda k: raw(words, k), words.locale, words.meta["direction"])
    return HTMLResponse(text, headers={"Cache-Control": "no-store"})


def _qr_svg(url: str) -> str:
    """The QR code of a URL as inline SVG (dark modules on white)."""
    import segno

    # No fixed size (a viewBox instead): the projector's style scales it to the screen.
    svg: str = segno.make(url, error="m").svg_inline(
        omitsize=True, border=2, dark="#000", light="#fff"
    )
    return svg


# -- challenge -----------------------------------------------------------------------------


async def get_challenge(request: Request) -> Response:
    """The open challenge, or 404."""
    hub = guard(request)
    row = await hub.db(hub.store.open_one)
    if not _is_open(row):
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    assert row is not None
    return JSONResponse(challenge_doc(row))


async def open_challenge(request: Request) -> Response:
    """Open a challenge (closing the one open); the lecturer's."""
    hub = lecturer(request)
    new = parse_challenge(await read_json(request, hub.limits.body_bytes))
    cid = await hub.db(
        hub.store.open_challenge,
        new.settings,
        new.seed,
        new.max_frames,
        new.attempts,
        new.closes_at,
    )
    hub.showing = None
    await hub.publish()
    row = await hub.db(hub.store.open_one)
    assert row is not None and row["id"] == cid
    return JSONResponse(challenge_doc(row))


async def close_challenge(request: Request) -> Response:
    """Close the open challenge; the lecturer's."""
    hub = lecturer(request)
    row = await hub.db(hub.store.open_one)
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    await hub.db(hub.store.close_challenge, row["id"])
    await hub.publish()
    return JSONResponse({"id": row["id"], "open": False})


# -- students ----------------------------------------------------------------------------------


async def join(request: Request) -> Response:
    """A student's token for a name (cleaned: visible characters, at most NAME_MAX)."""
    hub = guard(request)
    doc = await read_json(request, hub.limits.body_bytes)
    try:
        token = await hub.db(hub.store.join, doc.get("name"))
    except ValueError:
        raise RefusedError(400, "name", "class.error.name", n=NAME_MAX) from None
    name = await hub.db(hub.store.player_name, token)
    return JSONResponse({"token": token, "name": name})


async def _student(request: Request, hub: Hub) -> str:
    """The student token of a request (401 if none known), within its submission rate."""
    token = _bearer(request)
    if not token or len(token) > 64 or await hub.db(hub.store.player_name, token) is None:
        raise RefusedError(401, "token", "class.error.token")
    wait = hub.per_token.take(token)
    if wait:
        raise RefusedError(429, "token", "class.error.slow_down", retry_after=wait, n=wait)
    return token


async def _open_for(hub: Hub, doc: dict[str, Any], token: str) -> dict[str, Any]:
    """The open challenge a submission names, if it may take one more game from `token`."""
    row = await hub.db(hub.store.open_one)
    if not _is_open(row):
        raise RefusedError(409, "challenge", "class.error.closed")
    assert row is not None
    if doc.get("challenge") != row["id"]:
        raise RefusedError(409, "challenge", "class.error.other_challenge", id=row["id"])
    limit = row["attempts"]
    if isinstance(limit, int) and await hub.db(hub.store.attempts, row["id"], token) >= limit:
        raise RefusedError(409, "attempts", "class.error.attempts", n=limit)
    return row


def _game_of(doc: dict[str, Any]) -> tuple[object, str]:
    """The submitted game: (a code, "code") or (a recording, "recording"); else 400."""
    if doc.get("code") is not None:
        if not isinstance(doc["code"], str):
            raise RefusedError(400, "code", "class.error.no_code")
        return doc["code"], "code"
    if isinstance(doc.get("recording"), dict):
        return doc["recording"], "recording"
    raise RefusedError(400, "code", "class.error.no_code")


async def submit(request: Request) -> Response:
    """A game replayed in a worker; 200 only once its entry is committed."""
    hub = guard(request)
    token = await _student(request, hub)
    doc = await read_json(request, hub.limits.body_bytes)
    row = await _open_for(hub, doc, token)
    item, how = _game_of(doc)
    loop = asyncio.get_running_loop()
    got = await loop.run_in_executor(hub.pool, check_submission, item, how, row)
    if "error" in got:
        await hub.db(hub.store.count_rejected, row["id"])
        await hub.publish()
        err = got["error"]
        raise RefusedError(422, err["field"], err["key"], **err["args"])
    result = (got["score"], got["frames"], got["edition"], got["code"])
    entry = await hub.db(hub.store.add_if_allowed, row["id"], token, result, time.time())
    if isinstance(entry, str):
        key = "class.error.attempts" if entry == "attempts" else "class.error.closed"
        raise RefusedError(409, entry, key, n=row["attempts"] or 0)
    await hub.publish()
    return JSONResponse(
        {
            "entry": entry,
            "score": got["score"],
            "frames": got["frames"],
            "rank": await hub.db(hub.store.rank, row["id"], token),
        }
    )


# -- the lecturer's actions --------------------------------------------------------------------


def _entry_id(doc: dict[str, Any]) -> int:
    """The entry a lecturer's action names (400 if not a whole number)."""
    entry = doc.get("entry")
    if not isinstance(entry, int) or isinstance(entry, bool):
        raise RefusedError(400, "entry", "class.error.no_entry")
    return entry


async def hide(request: Request) -> Response:
    """Hide an entry from the leaderboard."""
    hub = lecturer(request)
    entry = _entry_id(await read_json(request, hub.limits.body_bytes))
    if not await hub.db(hub.store.hide, entry):
        raise RefusedError(404, "entry", "class.error.no_entry")
    if hub.showing and hub.showing["entry"] == entry:
        hub.showing = None
    await hub.publish()
    return JSONResponse({"entry": entry, "hidden": True})


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


async def show(request: Request) -> Response:
    """Put an entry's replay on the projector ({"entry": null} takes it off)."""
    hub = lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    if doc.get("entry") is None:
        hub.showing = None
    else:
        entry = _entry_id(doc)
        found = await hub.db(hub.store.entry_code, entry)
        if found is None:
            raise RefusedError(404, "entry", "class.error.no_entry")
        name, code = found
        hub.showing = {"entry": entry, "name": name, "code": code, "summary": moves_summary(code)}
    await hub.publish()
    return JSONResponse({"replay": hub.showing})


async def entries(request: Request) -> Response:
    """Every entry of the current challenge, hidden ones too (the lecturer's list)."""
    hub = lecturer(request)
    row = await hub.db(hub.store.latest)
    if row is None:
        return JSONResponse({"challenge": None, "entries": [], "rejected": 0})
    listed = await hub.db(hub.store.entries, row["id"])
    doc = {**challenge_doc(row), "open": _is_open(row)}
    return JSONResponse({"challenge": doc, "entries": listed, "rejected": row["rejected"]})


async def export_csv(request: Request) -> Response:
    """The current challenge's leaderboard as CSV (token as Bearer or ?token=)."""
    hub = lecturer(request, query=True)
    row = await hub.db(hub.store.latest)
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    text = await hub.db(hub.store.results_csv, row["id"])
    name = f"evapcool-class-{row['id']}.csv"
    return Response(
        text,
        media_type="text/csv; charset=utf-8",
        headers={
            "Content-Disposition": f'attachment; filename="{name}"',
            "Cache-Control": "no-store",
        },
    )


# -- leaderboard ------------------------------------------------------------------------------


async def leaderboard(request: Request) -> Response:
    """The current challenge's leaderboard."""
    hub = guard(request)
    return JSONResponse(await hub.board())


async def stream(request: Request) -> Response:
    """Server-Sent Events: the leaderboard at connect and after every change."""
    hub = guard(request)
    if len(hub.listeners) >= hub.limits.listeners:
        raise RefusedError(429, "client", "class.error.slow_down", retry_after=30, n=30)
    queue: asyncio.Queue[str] = asyncio.Queue(maxsize=4)
    hub.listeners.add(queue)
    first = json.dumps(await hub.board())
    return StreamingResponse(
        _events(hub, queue, first),
        media_type="text/event-stream",
        headers={"Cache-Control": "no-cache", "X-Accel-Buffering": "no"},
    )


async def _events(hub: Hub, queue: asyncio.Queue[str], first: str) -> AsyncIterator[str]:
    """The event stream of one listener; a comment every KEEP_ALIVE seconds when idle."""
    try:
        yield f"data: {first}\n\n"
        while True:
            try:
                text = await asyncio.wait_for(queue.get(), KEEP_ALIVE)
            except asyncio.TimeoutError:
                yield ": keep-alive\n\n"
                continue
            yield f"data: {text}\n\n"
    finally:
        hub.listeners.discard(queue)


# -- the app -----------------------------------------------------------------------------------


ROUTES = [
    Route("/", game),
    Route("/projector", projector),
    Route("/lecturer", lecturer_page),
    Route("/api/challenge", get_challenge, methods=["GET"]),
    Route("/api/challenge", open_challenge, methods=["POST"]),
    Route("/api/challenge/close", close_challenge, methods=["POST"]),
    Route("/api/join", join, methods=["POST"]),
    Route("/api/submit", submit, methods=["POST"]),
    Route("/api/hide", hide, methods=["POST"]),
    Route("/api/show", show, methods=["POST"]),
    Route("/api/entries", entries),
    Route("/api/leaderboard", leaderboard),
    Route("/api/stream", stream),
    Route("/api/export.csv", export_csv),
]


async def _refused(request: Request, exc: Exception) -> Response:
    """The JSON answer of a RefusedError."""
    assert isinstance(exc, RefusedError)
    return refused_response(exc, hub_of(request).words.of(request))


def _pool(workers: int) -> ProcessPoolExecutor:
    """Worker processes (spawned, not forked from the running server), each warmed once."""
    context = multiprocessing.get_context("spawn")
    return ProcessPoolExecutor(workers, mp_context=context, initializer=warm)


def create_app(
    store_path: Path | str,
    lecturer_token: str,
    pool_workers: int,
    limits: Limits | None = None,
    join_url: str | None = None,
) -> Starlette:
    """The class server's app: SQLite at store_path, `pool_workers` verifying processes.

    join_url: the students' address shown on the projector (default: the one it was read at).
    """

    @asynccontextmanager
    async def lifespan(app: Starlette) -> AsyncIterator[None]:
        hub = Hub(Store(Path(store_path)), lecturer_token, limits or Limits(), _pool(pool_workers))
        app.state.hub = hub
        app.state.game_html = pages.game_page()
        loop = asyncio.get_running_loop()
        await asyncio.gather(*(loop.run_in_executor(hub.pool, _ready) for _ in range(pool_workers)))
        try:
            yield
        finally:
            hub.pool.shutdown(cancel_futures=True)
            hub.db_thread.submit(hub.store.close).result()
            hub.db_thread.shutdown()

    app = Starlette(routes=ROUTES, lifespan=lifespan, exception_handlers={RefusedError: _refused})
    app.state.join_url = join_url
    app.add_middleware(_SafeHeaders)
    return app


def _ready() -> bool:
    """A no-op run in each worker at start (its initializer has warmed the engine)."""
    return True


class _SafeHeaders:
    """ASGI middleware adding SAFE_HEADERS to every answer."""

    def __init__(self, app: Any) -> None:
        self.app = app

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        async def send_with(message: Any) -> None:
            if message["type"] == "http.response.start":
                extra = [(k.lower().encode(), v.encode()) for k, v in SAFE_HEADERS.items()]
                message["headers"] = list(message.get("headers", [])) + extra
            await send(message)

        if scope["type"] != "http":
            await self.app(scope, receive, send)
        else:
            await self.app(scope, receive, send_with)
