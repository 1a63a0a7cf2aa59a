"""`evapcool class`'s web server (Starlette): classes, challenges, students, verified games.

Games are replayed in worker processes, shared fairly between addresses (fairqueue); a
submission is answered 200 only after its entry is committed to the store (SQLite, or
PostgreSQL for a department). SQLite's calls run one at a time on a thread of their own,
PostgreSQL's on a few threads with a pool of connections. Tokens are kept only as digests.

A single-class server serves its one class at /, /projector, /lecturer and /api/...; every
class of a department's server has the same under /c/{code}/. With PostgreSQL several
processes serve one department: a changed board is announced through the database
(LISTEN/NOTIFY) and each process sends it to its own streams.
"""

from __future__ import annotations

import asyncio
import contextlib
import hashlib
import hmac
import json
import multiprocessing
import secrets
import time
from collections.abc import AsyncIterator, Callable
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar
from urllib.parse import quote

from starlette.exceptions import HTTPException
from starlette.requests import Request
from starlette.responses import (
    HTMLResponse,
    JSONResponse,
    RedirectResponse,
    Response,
    StreamingResponse,
)

from evapcool.classroom import pages
from evapcool.classroom.challenge import challenge_doc, parse_challenge
from evapcool.classroom.debrief import Law, Showing, debrief_doc, every_frame, law_of, without_names
from evapcool.classroom.errors import RefusedError, read_json, refused_response
from evapcool.classroom.fairqueue import FairQueue
from evapcool.classroom.ratelimit import Rate, RateLimiter
from evapcool.classroom.rooms import DEFAULT_ROOM, normal_code
from evapcool.classroom.store import (
    NAME_MAX,
    ClassFullError,
    ClassStore,
    NameTakenError,
    Store,
    StoreAwayError,
    is_url,
)
from evapcool.classroom.verifier import check_submission, code_chars_ok, reference_frames, warm
from evapcool.classroom.words import Words, raw
from evapcool.game.replay import decode

T = TypeVar("T")
#: Seconds between keep-alive comments on an idle event stream.
KEEP_ALIVE = 15.0
#: Seconds between looks at the open challenge's time window: when it ends, the server
#: closes the challenge and tells every page (within this, well inside the pages' 2 s).
WINDOW_CHECK = 0.25
#: Headers on every answer: no referrer (the lecturer's link holds the token), no sniffing.
SAFE_HEADERS = {
    "Referrer-Policy": "no-referrer",
    "X-Content-Type-Options": "nosniff",
    "X-Frame-Options": "DENY",
}
#: The policy of answers that are not pages (JSON, CSV, events): nothing may run or load.
DATA_POLICY = "default-src 'none'; frame-ancestors 'none'"
#: The store's names of the digests of the single class's lecturer's token, its projector's
#: key, and the department's administrator's token.
LECTURER_SECRET = "lecturer"
PROJECTOR_SECRET = "projector"
ADMIN_SECRET = "admin"
#: Seconds between forgetting idle rate buckets held in the database.
BUCKET_SWEEP = 60.0
#: Seconds a client is told to wait (Retry-After) while the database does not answer.
STORE_RETRY = 5
#: Threads (and pooled connections) for a store shared by several processes.
SHARED_DB_THREADS = 8


#: API requests per client address (a class behind one NAT address shares it).
CLIENT_RATE = Rate(burst=600, per_second=100)
#: Submissions per student token.
SUBMIT_RATE = Rate(burst=5, per_second=0.5)
#: Joins per class and client address: a lecture hall behind one address joins at once, then
#: one more every 10 s (a flood of joins adds at most 360 players an hour).
JOIN_RATE = Rate(burst=320, per_second=0.1)


@dataclass(frozen=True)
class Limits:
    """Request limits: body size, request rates, verifications, players, event streams."""

    body_bytes: int = 256 * 1024
    client: Rate = CLIENT_RATE
    submit: Rate = SUBMIT_RATE
    join: Rate = JOIN_RATE
    #: Verifications in flight or waiting, per student token and per client address.
    student_jobs: int = 2
    address_jobs: int = 64
    #: Players a class file holds (`evapcool class --max-students`).
    students: int = 2000
    #: Open event streams: in all, and per client address; the projector's and the
    #: lecturer's (with the projector key) have their own bound and never wait for these.
    listeners: int = 1000
    address_listeners: int = 20
    keyed_listeners: int = 16


def digest(secret: str) -> str:
    """What the store keeps of a secret (SHA-256, hex)."""
    return hashlib.sha256(secret.encode()).hexdigest()


def projector_key(lecturer_token: str) -> str:
    """The projector's key, made from the lecturer's token (so the lecturer's page can give
    it, though the server keeps only digests); it shows replay codes, nothing more."""
    mac = hmac.new(lecturer_token.encode(), b"evapcool projector", hashlib.sha256)
    return mac.hexdigest()[:32]


def room_projector_key(lecturer_digest: str, code: str) -> str:
    """A department class's projector key, made from its lecturer's digest and its code
    (the lecturer's page gives it; the server checks it without storing it)."""
    mac = hmac.new(lecturer_digest.encode(), b"evapcool projector " + code.encode(), "sha256")
    return mac.hexdigest()[:32]


def new_lecturer_token(store: ClassStore) -> str:
    """A new lecturer's token (the last one stops working); the store keeps its digests."""
    token = secrets.token_urlsafe(24)
    store.set_secret(LECTURER_SECRET, digest(token))
    store.set_secret(PROJECTOR_SECRET, digest(projector_key(token)))
    return token


def matches_digest(given: str, wanted: str | None) -> bool:
    """Whether a secret given matches a stored digest (in constant time)."""
    return wanted is not None and secrets.compare_digest(digest(given), wanted)


@dataclass
class Listener:
    """One open event stream: its queue, its address, its class, whether it holds the key."""

    queue: asyncio.Queue[str]
    address: str
    keyed: bool
    room: int = DEFAULT_ROOM


@dataclass
class Hub:
    """The server's state: store, pools, limiters, this process's streams."""

    store: ClassStore
    limits: Limits
    pool: ProcessPoolExecutor
    workers: int
    db_thread: ThreadPoolExecutor = field(default_factory=lambda: ThreadPoolExecutor(1))
    words: Words = field(default_factory=Words)
    listeners: list[Listener] = field(default_factory=list)
    #: Rooms whose board another process (or this one) announced changed, to send.
    pending: set[int] = field(default_factory=set)
    #: The challenges' critical lines and the pair's paths (issue 36's debrief), computed
    #: once per process (the same in every process: they follow from the games).
    laws: dict[int, Law] = field(default_factory=dict)
    pair_paths: dict[int, dict[str, Any]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        # Requests per address are one process's flood guard; submissions and joins are
        # counted in the store (across processes when it is shared).
        self.per_client = RateLimiter(self.limits.client)
        self.queue = FairQueue(self.workers, self.limits.student_jobs, self.limits.address_jobs)
        self.wake = asyncio.Event()

    async def db(self, fn: Callable[..., T], *args: Any) -> T:
        """Run a store call on the store's threads (off the event loop)."""
        return await asyncio.get_running_loop().run_in_executor(self.db_thread, fn, *args)

    async def board(self, room: int, keyed: bool = False) -> dict[str, Any]:
        """The leaderboard of a room's current (open, else last) challenge; the replay's
        code only for the key's holders while that game's challenge is open; the debrief's
        state (no names in its anonymous mode)."""
        return await self.db(_board, self.store, room, keyed)

    async def publish(self, room: int) -> None:
        """A room's board changed: tell every process sharing the store, or (one process)
        send it to this one's streams now."""
        if self.store.shared:
            # if the database is away, every process sends all its boards anew once it hears
            # from the database again
            with contextlib.suppress(StoreAwayError):
                await self.db(self.store.notify, room)
        else:
            await self.send(room)

    async def send(self, room: int) -> None:
        """Send a room's leaderboard to this process's streams of it; a slow one keeps only
        the newest."""
        here = [s for s in self.listeners if s.room == room]
        texts = {}
        for keyed in {s.keyed for s in here}:
            texts[keyed] = json.dumps(await self.board(room, keyed))
        for listener in here:
            if listener.queue.full():
                listener.queue.get_nowait()
            listener.queue.put_nowait(texts[listener.keyed])

    def changed(self, room: int | None) -> None:
        """A notice from the store (on the event loop): a room's board changed (None: any
        may have, after the connection was lost)."""
        self.pending.update([room] if room is not None else {s.room for s in self.listeners})
        self.wake.set()

    async def forward(self) -> None:
        """Send the boards of the rooms announced changed (several notices, one board)."""
        while True:
            await self.wake.wait()
            self.wake.clear()
            rooms, self.pending = self.pending, set()
            unsent = set()
            for room in rooms:
                try:
                    await self.send(room)
                except StoreAwayError:
                    unsent.add(room)
            if unsent:  # sent once the database answers again
                await asyncio.sleep(STORE_RETRY)
                self.pending |= unsent
                self.wake.set()


def _replay_seen(store: ClassStore, room: int, keyed: bool) -> Any:
    """The replay on the projector as a reader may see it: without its code while its
    challenge is open, unless the reader holds the projector's key (or is the lecturer)."""
    showing = store.showing(room)
    if showing is None:
        return None
    hidden = {"player"}  # the student's token, never shown
    now_open = store.open_one(room)
    if not keyed and _is_open(now_open) and now_open and now_open["id"] == showing["challenge"]:
        hidden.add("code")
    return {k: v for k, v in showing.items() if k not in hidden}


def _leaderboard(store: ClassStore, room: int, keyed: bool) -> dict[str, Any]:
    """The leaderboard of a room's current challenge (see docs/class.md)."""
    current = store.latest(room)
    replay = _replay_seen(store, room, keyed)
    if current is None:
        return {
            "challenge": None,
            "open": False,
            "info": None,
            "entries": [],
            "rejected": 0,
            "replay": replay,
        }
    rows = store.leaderboard(int(current["id"]))  # type: ignore[call-overload]
    entries = [
        {"rank": i, "name": r[1], "score": r[2], "frames": r[3], "edition": r[4]}
        for i, r in enumerate(rows, 1)
    ]
    return {
        "challenge": current["id"],
        "open": _is_open(current),
        "info": challenge_info(current),
        "entries": entries,
        "rejected": current["rejected"],
        "replay": replay,
    }


def _board(store: ClassStore, room: int, keyed: bool) -> dict[str, Any]:
    """The leaderboard document with the debrief's state (see docs/class.md); no names
    in the debrief's anonymous mode."""
    board = _leaderboard(store, room, keyed)
    state = showing_of(store.debrief_state(room))
    board["debrief"] = state.to_json()
    return without_names(board) if state.anonymous else board


def challenge_info(row: dict[str, Any], now: float | None = None) -> dict[str, Any]:
    """What every page shows of a challenge: its API form, whether it is open, and the
    seconds left in its window (`closes_in`, counted from this answer: no clocks compared)."""
    now = time.time() if now is None else now
    closes = row.get("closes_at")
    left = None if closes is None else max(0.0, round(float(closes) - now, 3))
    return {**challenge_doc(row), "open": _is_open(row, now), "closes_in": left}


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


def bearer_token(request: Request) -> str:
    """The Bearer token of a request ('' if none)."""
    auth = request.headers.get("authorization", "")
    return auth[7:].strip() if auth.lower().startswith("bearer ") else ""


def address(request: Request) -> str:
    """The client's address (a class behind one NAT address shares it)."""
    return request.client.host if request.client else "?"


def guard(request: Request) -> Hub:
    """The Hub, after the client's request rate is checked (429 over it)."""
    hub = hub_of(request)
    wait = hub.per_client.take(address(request))
    if wait:
        raise RefusedError(429, "client", "class.error.slow_down", retry_after=wait, n=wait)
    return hub


async def room_of(request: Request, hub: Hub) -> dict[str, Any]:
    """The class a request is for: /c/{code}/... names it, the other paths are the single
    class's (404 naming "class" for an unknown code)."""
    given = request.path_params.get("code")
    code = normal_code(given) if isinstance(given, str) else None
    if given is None:
        room = await hub.db(hub.store.room, DEFAULT_ROOM)
    else:
        room = await hub.db(hub.store.room_by_code, code) if code else None
    if room is None:
        raise RefusedError(404, "class", "class.error.no_class")
    return room


async def _lecturer_digest(hub: Hub, room: dict[str, Any]) -> str | None:
    """The digest of the token that may act on a class: its lecturer's, or (the single
    class, no lecturer) the one `evapcool class` made."""
    if room["lecturer"] is None:
        return await hub.db(hub.store.secret, LECTURER_SECRET)
    return str(room["digest"])


async def lecturer(request: Request, query: bool = False) -> tuple[Hub, dict[str, Any]]:
    """The Hub and the class if the request carries the class's lecturer's token, else
    403 (another lecturer's token too)."""
    hub = guard(request)
    room = await room_of(request, hub)
    if not matches_digest(_lecturer_token(request, query), await _lecturer_digest(hub, room)):
        raise RefusedError(403, "token", "class.error.lecturer")
    return hub, room


def _lecturer_token(request: Request, query: bool) -> str:
    """The token a request gives: as Bearer, or (query=True, the pages) in ?token=."""
    return bearer_token(request) or (request.query_params.get("token", "") if query else "")


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
    return True


def _base(room: dict[str, Any]) -> str:
    """The path prefix of a class's pages and API ('' for the single class's)."""
    return "" if room["id"] == DEFAULT_ROOM else f"/c/{room['code']}"


# -- pages -------------------------------------------------------------------------------------


async def game(request: Request) -> Response:
    """The browser edition in class mode (a department's root is its join page instead)."""
    hub = guard(request)
    room = await room_of(request, hub)
    text, policy = pages.game_page(_base(room) + "/api")
    # The projector plays replays in the game page in a frame of its own (same origin).
    headers = {"Content-Security-Policy": policy, "X-Frame-Options": "SAMEORIGIN"}
    return HTMLResponse(text, headers=headers)


async def projector(request: Request) -> Response:
    """The projector page: QR code of the join address, the live leaderboard (with the
    projector's key in ?key=, the replays' codes too)."""
    hub = guard(request)
    room = await room_of(request, hub)
    await keyed(request, hub, room)
    words = hub.words.of(request)
    join_url = join_url_of(request, room)
    svg = _qr_svg(join_url)
    text = pages.projector_page(
        lambda k: raw(words, k), words.locale, words.meta["direction"], join_url, svg, _base(room),
        getattr(request.app.state, "lan_command", None),
    )  # fmt: skip
    headers = {"Content-Security-Policy": pages.PROJECTOR_POLICY, "Cache-Control": "no-store"}
    return HTMLResponse(text, headers=headers)


def join_url_of(request: Request, room: dict[str, Any]) -> str:
    """The students' address of a class: the one given at start (or the one this page was
    read at), and the class's path."""
    root = (request.app.state.join_url or str(request.base_url)).rstrip("/")
    return f"{root}{_base(room)}/"


async def lecturer_page(request: Request) -> Response:
    """The lecturer's page (403 without the token in ?token=); a department's lecturers get
    the list of their classes at /lecturer instead (department.py)."""
    hub, room = await lecturer(request, query=True)
    words = hub.words.of(request)
    token = _lecturer_token(request, query=True)
    if room["lecturer"] is None:
        key = projector_key(token)
    else:
        key = room_projector_key(room["digest"], room["code"])
    text = pages.lecturer_page(
        lambda k: raw(words, k),
        words.locale,
        words.meta["direction"],
        key,
        _base(room),
        _classes_link(request, room),
    )
    headers = {"Content-Security-Policy": pages.LECTURER_POLICY, "Cache-Control": "no-store"}
    return HTMLResponse(text, headers=headers)


def _classes_link(request: Request, room: dict[str, Any]) -> str:
    """The department lecturer's list of classes (/lecturer?token=, as that list links
    here), or "": a single-class server has no list, the single class's token (its room has
    no lecturer) is no department lecturer's, and a token given only as Bearer stays out of
    the page."""
    if not request.app.state.department or room["lecturer"] is None:
        return ""
    token = request.query_params.get("token", "")
    if not matches_digest(token, str(room["digest"])):
        return ""
    return "/lecturer?token=" + quote(token)


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
    room = await room_of(request, hub)
    row = await hub.db(hub.store.open_one, room["id"])
    if not _is_open(row):
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    assert row is not None
    return JSONResponse(challenge_doc(row))


async def open_challenge(request: Request) -> Response:
    """Open a challenge (closing the one open); the lecturer's."""
    hub, room = await lecturer(request)
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


# -- students ----------------------------------------------------------------------------------


async def join(request: Request) -> Response:
    """A student's token for a name (cleaned: visible characters, at most NAME_MAX, not
    looking like another student's), within the address's join rate and the class's bound.

    With the token of an earlier join ("token"), that student again, by the name the
    server has (an applet started anew keeps its place and name).
    """
    hub = guard(request)
    room = await room_of(request, hub)
    doc = await read_json(request, hub.limits.body_bytes)
    earlier = doc.get("token")
    if isinstance(earlier, str) and 0 < len(earlier) <= 64:
        known = await hub.db(hub.store.player_name, earlier, room["id"])
        if known is not None:
            return JSONResponse({"token": earlier, "name": known})
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
    return JSONResponse({"token": token, "name": name})


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
    """{challenge, attempts (the limit), used, best, rank} of a student in a challenge."""
    got = await hub.db(hub.store.standing, row["id"], token)
    return {"challenge": row["id"], "attempts": row["attempts"], **got}


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

    got = await hub.queue.run(address(request), token, verify)
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


# -- the lecturer's actions --------------------------------------------------------------------


def _entry_id(doc: dict[str, Any]) -> int:
    """The entry a lecturer's action names (400 if not a whole number SQLite can hold)."""
    entry = doc.get("entry")
    if not isinstance(entry, int) or isinstance(entry, bool) or not 0 < entry < 2**63:
        raise RefusedError(400, "entry", "class.error.no_entry")
    return entry


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
    hub, room = await lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    await _show(hub, room["id"], None if doc.get("entry") is None else _entry_id(doc))
    await hub.publish(room["id"])
    return JSONResponse({"replay": await hub.db(_replay_seen, hub.store, room["id"], True)})


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


async def _challenge_asked(request: Request, hub: Hub, room: dict[str, Any]) -> Any:
    """The challenge ?challenge= names (a past one of the class's), else the current one
    (None if the class has none); 404 for one not of this class."""
    asked = request.query_params.get("challenge")
    if asked is None:
        return await hub.db(hub.store.latest, room["id"])
    if not asked.isdigit() or not 0 < int(asked) < 2**63:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    row = await hub.db(hub.store.challenge, int(asked), room["id"])
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    return row


# -- the debrief (issue 36) ----------------------------------------------------------------


def showing_of(doc: dict[str, Any] | None) -> Showing:
    """The debrief's state as the store keeps it (JSON), or the default."""
    if not doc:
        return Showing()
    pair = doc.get("pair")
    return Showing(
        bool(doc.get("anonymous")), doc.get("pick"), (pair[0], pair[1]) if pair else None
    )


async def debrief_state(hub: Hub, room: int) -> Showing:
    """What a room's lecturer set the debrief to show (in the store: every process sees it)."""
    return showing_of(await hub.db(hub.store.debrief_state, room))


async def _debrief_challenge(
    request: Request, hub: Hub
) -> tuple[dict[str, Any], dict[str, Any], bool]:
    """The class, the challenge debriefed and whether its lecturer asks: 409 while it is
    open, unless the lecturer asks (their early look; the projector and students wait for
    the close)."""
    room = await room_of(request, hub)
    is_lecturer = matches_digest(bearer_token(request), await _lecturer_digest(hub, room))
    row = await hub.db(hub.store.latest, room["id"])
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    if _is_open(row) and not is_lecturer:
        raise RefusedError(409, "challenge", "class.error.debrief_open")
    return room, row, is_lecturer


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
    games = await hub.db(hub.store.best_games, row["id"])
    law = await _law(hub, row)
    viewer = None if is_lecturer else bearer_token(request) or None
    state = await debrief_state(hub, room["id"])
    doc = debrief_doc(row, games, law, state.anonymous and not is_lecturer, viewer)
    doc["showing"] = state.to_json()
    return JSONResponse(doc, headers={"Cache-Control": "no-store"})


async def debrief_pair(request: Request) -> Response:
    """The two games the lecturer set side by side: their paths at every frame, codes."""
    hub = guard(request)
    room, row, is_lecturer = await _debrief_challenge(request, hub)
    state = await debrief_state(hub, room["id"])
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


def _room_doc(room: dict[str, Any]) -> dict[str, Any]:
    """What the API says of a class (never its lecturer's digest)."""
    return {"code": room["code"], "name": room["name"], "path": _base(room) + "/"}


async def export_csv(request: Request) -> Response:
    """The current (or ?challenge=) challenge's games as CSV (token as Bearer or ?token=)."""
    hub, room = await lecturer(request, query=True)
    row = await _challenge_asked(request, hub, room)
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    text = await hub.db(hub.store.results_csv, row["id"])
    name = f"evapcool-class-{row['id']}.csv"
    if room["id"] != DEFAULT_ROOM:
        name = f"evapcool-class-{room['code']}-{row['id']}.csv"
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
    """The current challenge's leaderboard (the replay's code as for the stream)."""
    hub = guard(request)
    room = await room_of(request, hub)
    return JSONResponse(await hub.board(room["id"], await keyed(request, hub, room)))


def _stream_refusal(hub: Hub, request: Request, with_key: bool, room: int) -> RefusedError | None:
    """Why one more stream is refused: too many in all or from this address (429); the
    key's holders are counted apart (per class), so students' streams never crowd the
    projector out."""
    limits = hub.limits
    if with_key:
        if sum(1 for s in hub.listeners if s.keyed and s.room == room) >= limits.keyed_listeners:
            return RefusedError(
                429, "key", "class.error.streams", retry_after=30, n=limits.keyed_listeners
            )
        return None
    public = [s for s in hub.listeners if not s.keyed]
    if sum(1 for s in public if s.address == address(request)) >= limits.address_listeners:
        return RefusedError(
            429, "client", "class.error.streams", retry_after=30, n=limits.address_listeners
        )
    if len(public) >= limits.listeners:
        return RefusedError(429, "client", "class.error.slow_down", retry_after=30, n=30)
    return None


async def stream(request: Request) -> Response:
    """Server-Sent Events: the leaderboard at connect and after every change."""
    hub = guard(request)
    room = await room_of(request, hub)
    with_key = await keyed(request, hub, room)
    refused = _stream_refusal(hub, request, with_key, room["id"])
    if refused:
        raise refused
    listener = Listener(asyncio.Queue(maxsize=4), address(request), with_key, room["id"])
    hub.listeners.append(listener)
    first = json.dumps(await hub.board(room["id"], with_key))
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
            yield f"data: {text}\n\n"
    finally:
        hub.listeners.remove(listener)


# -- the app -----------------------------------------------------------------------------------


#: A class's pages and API: at these paths for the single class, under /c/{code} for each
#: class of a department's server.
CLASS_ROUTES: list[tuple[str, Callable[[Request], Any], list[str] | None]] = [
    ("/", game, None),
    ("/projector", projector, None),
    ("/lecturer", lecturer_page, None),
    ("/api/challenge", get_challenge, ["GET"]),
    ("/api/challenge", open_challenge, ["POST"]),
    ("/api/challenge/close", close_challenge, ["POST"]),
    ("/api/challenges", challenges, None),
    ("/api/join", join, ["POST"]),
    ("/api/submit", submit, ["POST"]),
    ("/api/me", me, None),
    ("/api/hide", hide, ["POST"]),
    ("/api/rename", rename, ["POST"]),
    ("/api/show", show, ["POST"]),
    ("/api/entries", entries, None),
    ("/api/leaderboard", leaderboard, None),
    ("/api/debrief", debrief, ["GET"]),
    ("/api/debrief", set_debrief, ["POST"]),
    ("/api/debrief/pair", debrief_pair, None),
    ("/api/stream", stream, None),
    ("/api/export.csv", export_csv, None),
]


async def _to_class(request: Request) -> Response:
    """/c/{code} without its slash: the class's game page."""
    return RedirectResponse(f"/c/{request.path_params['code']}/", status_code=308)


async def _refused(request: Request, exc: Exception) -> Response:
    """The JSON answer of a RefusedError."""
    assert isinstance(exc, RefusedError)
    return refused_response(exc, hub_of(request).words.of(request))


async def _store_away(request: Request, exc: Exception) -> Response:
    """503 while the database does not answer (a department's PostgreSQL away)."""
    refusal = RefusedError(503, "store", "class.error.store_away", retry_after=STORE_RETRY)
    return refused_response(refusal, hub_of(request).words.of(request))


async def _no_route(request: Request, exc: Exception) -> Response:
    """The JSON answer of an unknown path (404) or method (405), as any refusal."""
    assert isinstance(exc, HTTPException)
    if exc.status_code == 405:
        refusal = RefusedError(405, "method", "class.error.method", method=request.method)
    else:
        refusal = RefusedError(404, "path", "class.error.not_found")
    answer = refused_response(refusal, hub_of(request).words.of(request))
    answer.headers.update(exc.headers or {})  # Allow, for a 405
    return answer


def _pool(workers: int) -> ProcessPoolExecutor:
    """Worker processes (spawned, not forked from the running server), each warmed once."""
    context = multiprocessing.get_context("spawn")
    return ProcessPoolExecutor(workers, mp_context=context, initializer=warm)


def open_store(where: Path | str, connections: int = SHARED_DB_THREADS) -> ClassStore:
    """The store at a SQLite file, or a PostgreSQL database's URL (postgresql://...)."""
    text = str(where)
    if is_url(text):
        from evapcool.classroom.pgstore import PostgresStore

        return PostgresStore(text, connections)
    return Store(Path(where))


async def _close_on_time(hub: Hub) -> None:
    """Close each open challenge as its time window ends and tell every page at once (not
    only refuse games later). Every process looks; the store closes each once, and the
    process that closed it announces it."""
    swept = time.monotonic()
    while True:
        try:
            for room, challenge in await hub.db(hub.store.due, time.time()):
                if await hub.db(hub.store.close_challenge, challenge):
                    await hub.publish(room)
            if time.monotonic() - swept > BUCKET_SWEEP:
                swept = time.monotonic()
                await hub.db(hub.store.forget_buckets)
        except StoreAwayError:
            await asyncio.sleep(STORE_RETRY)  # closed late, once the database is back
        await asyncio.sleep(WINDOW_CHECK)


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
                headers = list(message.get("headers", []))
                have = {k.lower() for k, _ in headers}
                wanted = {**SAFE_HEADERS, "Content-Security-Policy": DATA_POLICY}
                # An answer's own header (the game page's framing, a page's policy) stays.
                extra = [
                    (k.lower().encode(), v.encode())
                    for k, v in wanted.items()
                    if k.lower().encode() not in have
                ]
                message["headers"] = headers + extra
            await send(message)

        if scope["type"] != "http":
            await self.app(scope, receive, send)
        else:
            await self.app(scope, receive, send_with)
