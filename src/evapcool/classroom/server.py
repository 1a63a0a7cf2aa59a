"""`evapcool class`'s web server (Starlette): challenges, students, verified games, pages.

Games are replayed in worker processes, shared fairly between addresses (fairqueue); a
submission is answered 200 only after its entry is committed to SQLite. Store calls run one
at a time on a thread of their own. The lecturer's token is kept only as a digest.
"""

from __future__ import annotations

import asyncio
import hashlib
import hmac
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
from starlette.exceptions import HTTPException
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response, StreamingResponse
from starlette.routing import Route

from evapcool.classroom import pages
from evapcool.classroom.challenge import challenge_doc, parse_challenge
from evapcool.classroom.debrief import Law, Showing, debrief_doc, every_frame, law_of, without_names
from evapcool.classroom.errors import RefusedError, read_json, refused_response
from evapcool.classroom.fairqueue import FairQueue
from evapcool.classroom.ratelimit import Rate, RateLimiter
from evapcool.classroom.store import NAME_MAX, ClassFullError, NameTakenError, Store
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
#: The store's names of the digests of the lecturer's token and the projector's key.
LECTURER_SECRET = "lecturer"
PROJECTOR_SECRET = "projector"


#: API requests per client address (a class behind one NAT address shares it).
CLIENT_RATE = Rate(burst=600, per_second=100)
#: Submissions per student token.
SUBMIT_RATE = Rate(burst=5, per_second=0.5)
#: Joins per client address: a lecture hall behind one address joins at once, then
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


def new_lecturer_token(store: Store) -> str:
    """A new lecturer's token (the last one stops working); the store keeps its digests."""
    token = secrets.token_urlsafe(24)
    store.set_secret(LECTURER_SECRET, digest(token))
    store.set_secret(PROJECTOR_SECRET, digest(projector_key(token)))
    return token


def _same(given: str, wanted: str | None) -> bool:
    """Whether a secret given matches a stored digest (in constant time)."""
    return wanted is not None and secrets.compare_digest(digest(given), wanted)


@dataclass
class Listener:
    """One open event stream: its queue, its address, and whether it holds the key."""

    queue: asyncio.Queue[str]
    address: str
    keyed: bool


@dataclass
class Hub:
    """The server's state: store, pools, secrets' digests, limiters, the streams."""

    store: Store
    limits: Limits
    pool: ProcessPoolExecutor
    workers: int
    db_thread: ThreadPoolExecutor = field(default_factory=lambda: ThreadPoolExecutor(1))
    words: Words = field(default_factory=Words)
    listeners: list[Listener] = field(default_factory=list)
    showing: dict[str, Any] | None = None
    #: The debrief's state (issue 36), the challenges' critical lines, the pair's paths.
    debrief: Showing = field(default_factory=Showing)
    laws: dict[int, Law] = field(default_factory=dict)
    pair_paths: dict[int, dict[str, Any]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.per_client = RateLimiter(self.limits.client)
        self.per_token = RateLimiter(self.limits.submit)
        self.joins = RateLimiter(self.limits.join)
        self.queue = FairQueue(self.workers, self.limits.student_jobs, self.limits.address_jobs)
        self.lecturer_digest = self.store.secret(LECTURER_SECRET)
        self.projector_digest = self.store.secret(PROJECTOR_SECRET)

    async def db(self, fn: Callable[..., T], *args: Any) -> T:
        """Run a Store call on the store's thread (one at a time, off the event loop)."""
        return await asyncio.get_running_loop().run_in_executor(self.db_thread, fn, *args)

    async def board(self, keyed: bool = False) -> dict[str, Any]:
        """The leaderboard of the current (open, else last) challenge; the replay's code
        only for the key's holders while that game's challenge is open."""
        board = await self.db(_board, self.store, self.showing, keyed)
        board["debrief"] = self.debrief.to_json()
        return without_names(board) if self.debrief.anonymous else board

    async def publish(self) -> None:
        """Send the leaderboard to every event stream; a slow one keeps only the newest."""
        texts = {keyed: json.dumps(await self.board(keyed)) for keyed in (False, True)}
        for listener in list(self.listeners):
            if listener.queue.full():
                listener.queue.get_nowait()
            listener.queue.put_nowait(texts[listener.keyed])


def _replay_seen(store: Store, showing: dict[str, Any] | None, keyed: bool) -> Any:
    """The replay on the projector as a reader may see it: without its code while its
    challenge is open, unless the reader holds the projector's key (or is the lecturer)."""
    if showing is None:
        return None
    hidden = {"player"}  # the student's token, never shown
    now_open = store.open_one()
    if not keyed and _is_open(now_open) and now_open and now_open["id"] == showing["challenge"]:
        hidden.add("code")
    return {k: v for k, v in showing.items() if k not in hidden}


def _board(store: Store, showing: dict[str, Any] | None, keyed: bool) -> dict[str, Any]:
    """The leaderboard document (see docs/class.md)."""
    current = store.latest()
    replay = _replay_seen(store, showing, keyed)
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


def _bearer(request: Request) -> str:
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


def lecturer(request: Request, query: bool = False) -> Hub:
    """The Hub if the request carries the lecturer's token, else 403."""
    hub = guard(request)
    if not _same(_lecturer_token(request, query), hub.lecturer_digest):
        raise RefusedError(403, "token", "class.error.lecturer")
    return hub


def _lecturer_token(request: Request, query: bool) -> str:
    """The token a request gives: as Bearer, or (query=True, the pages) in ?token=."""
    return _bearer(request) or (request.query_params.get("token", "") if query else "")


def keyed(request: Request, hub: Hub) -> bool:
    """Whether the request holds the projector's key (?key=); 403 if it gives a wrong one."""
    given = request.query_params.get("key")
    if given is None:
        return False
    if not _same(given, hub.projector_digest):
        raise RefusedError(403, "key", "class.error.key")
    return True


# -- pages -------------------------------------------------------------------------------------


async def game(request: Request) -> Response:
    """The browser edition in class mode."""
    guard(request)
    text, policy = request.app.state.game_page
    # The projector plays replays in the game page in a frame of its own (same origin).
    headers = {"Content-Security-Policy": policy, "X-Frame-Options": "SAMEORIGIN"}
    return HTMLResponse(text, headers=headers)


async def projector(request: Request) -> Response:
    """The projector page: QR code of the join address, the live leaderboard (with the
    projector's key in ?key=, the replays' codes too)."""
    hub = guard(request)
    keyed(request, hub)
    words = hub.words.of(request)
    join_url = request.app.state.join_url or str(request.base_url)
    svg = _qr_svg(join_url)
    text = pages.projector_page(
        lambda k: raw(words, k), words.locale, words.meta["direction"], join_url, svg
    )
    headers = {"Content-Security-Policy": pages.PROJECTOR_POLICY, "Cache-Control": "no-store"}
    return HTMLResponse(text, headers=headers)


async def lecturer_page(request: Request) -> Response:
    """The lecturer's page (403 without the token in ?token=)."""
    hub = lecturer(request, query=True)
    words = hub.words.of(request)
    key = projector_key(_lecturer_token(request, query=True))
    text = pages.lecturer_page(lambda k: raw(words, k), words.locale, words.meta["direction"], key)
    headers = {"Content-Security-Policy": pages.LECTURER_POLICY, "Cache-Control": "no-store"}
    return HTMLResponse(text, headers=headers)


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
    )
    hub.showing = None
    hub.debrief = Showing(anonymous=hub.debrief.anonymous)
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
    """A student's token for a name (cleaned: visible characters, at most NAME_MAX, not
    looking like another student's), within the address's join rate and the class's bound.

    With the token of an earlier join ("token"), that student again, by the name the
    server has (an applet started anew keeps its place and name).
    """
    hub = guard(request)
    doc = await read_json(request, hub.limits.body_bytes)
    earlier = doc.get("token")
    if isinstance(earlier, str) and 0 < len(earlier) <= 64:
        known = await hub.db(hub.store.player_name, earlier)
        if known is not None:
            return JSONResponse({"token": earlier, "name": known})
    wait = hub.joins.take(address(request))
    if wait:
        raise RefusedError(429, "client", "class.error.slow_down", retry_after=wait, n=wait)
    try:
        token = await hub.db(hub.store.join, doc.get("name"), hub.limits.students)
    except ClassFullError:
        raise RefusedError(409, "class", "class.error.full", n=hub.limits.students) from None
    except NameTakenError as taken:
        raise RefusedError(409, "name", "class.error.name_taken", name=taken.name) from None
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


async def me(request: Request) -> Response:
    """A student's standing in the current challenge: games sent and accepted of the
    limit, best score and place (the student's page shows them before each game)."""
    hub = guard(request)
    token = _bearer(request)
    name = await hub.db(hub.store.player_name, token) if 0 < len(token) <= 64 else None
    if name is None:
        raise RefusedError(401, "token", "class.error.token")
    row = await hub.db(hub.store.latest)
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
    token = await _student(request, hub)
    doc = await read_json(request, hub.limits.body_bytes)
    item, how = _game_of(doc)
    row = await _open_for(hub, doc, token)
    loop = asyncio.get_running_loop()

    def verify() -> asyncio.Future[dict[str, Any]]:
        return loop.run_in_executor(hub.pool, check_submission, item, how, row)

    got = await hub.queue.run(address(request), token, verify)
    if "error" in got:
        await _refuse(hub, row["id"], got["error"])
    result = (got["score"], got["frames"], got["edition"], got["code"], got["moves"])
    entry = await hub.db(
        hub.store.add_if_allowed, row["id"], token, result, time.time(), got["path"]
    )
    if entry == "code":
        await _refuse(hub, row["id"], {"field": "code", "key": "class.error.copied", "args": {}})
    if isinstance(entry, str):
        key = "class.error.attempts" if entry == "attempts" else "class.error.closed"
        raise RefusedError(409, entry, key, n=row["attempts"] or 0)
    await hub.publish()
    standing = await _standing(hub, row, token)
    return JSONResponse(
        {"entry": entry, "score": got["score"], "frames": got["frames"], **standing}
    )


async def _refuse(hub: Hub, challenge: int, error: dict[str, Any]) -> None:
    """Count a refused game, tell the boards, and answer 422 naming the field."""
    await hub.db(hub.store.count_rejected, challenge)
    await hub.publish()
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
    hub = lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    entry = _entry_id(doc)
    hidden = doc.get("hidden", True)
    if not isinstance(hidden, bool):
        raise RefusedError(400, "hidden", "class.error.value", allowed="true, false")
    if not await hub.db(hub.store.hide, entry, hidden):
        raise RefusedError(404, "entry", "class.error.no_entry")
    player = await hub.db(hub.store.entry_player, entry)
    if hidden and hub.showing and hub.showing["player"] == player:
        hub.showing = None
    await hub.publish()
    return JSONResponse({"entry": entry, "hidden": hidden})


async def rename(request: Request) -> Response:
    """Rename the student of an entry ({entry, name}); the name as at joining."""
    hub = lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    entry = _entry_id(doc)
    try:
        name = await hub.db(hub.store.rename, entry, doc.get("name"))
    except NameTakenError as taken:
        raise RefusedError(409, "name", "class.error.name_taken", name=taken.name) from None
    except ValueError:
        raise RefusedError(400, "name", "class.error.name", n=NAME_MAX) from None
    if name is None:
        raise RefusedError(404, "entry", "class.error.no_entry")
    if hub.showing and hub.showing["player"] == await hub.db(hub.store.entry_player, entry):
        hub.showing = {**hub.showing, "name": name}
    await hub.publish()
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
    hub = lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    await _show(hub, None if doc.get("entry") is None else _entry_id(doc))
    await hub.publish()
    return JSONResponse({"replay": await hub.db(_replay_seen, hub.store, hub.showing, True)})


async def _show(hub: Hub, entry: int | None) -> None:
    """The replay the projector plays: an entry's (404 if none), or none."""
    if entry is None:
        hub.showing = None
        return
    found = await hub.db(hub.store.entry_code, entry)
    if found is None:
        raise RefusedError(404, "entry", "class.error.no_entry")
    name, code, challenge = found
    hub.showing = {
        "entry": entry,
        "name": name,
        "code": code,
        "summary": moves_summary(code),
        "challenge": challenge,
        "player": await hub.db(hub.store.entry_player, entry),
    }


# -- the debrief (issue 36) ----------------------------------------------------------------


async def _debrief_challenge(request: Request, hub: Hub) -> tuple[dict[str, Any], bool]:
    """The challenge debriefed and whether the lecturer asks: 409 while it is open, unless
    the lecturer asks (their early look; the projector and students wait for the close)."""
    is_lecturer = _same(_bearer(request), hub.lecturer_digest)
    row = await hub.db(hub.store.latest)
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    if _is_open(row) and not is_lecturer:
        raise RefusedError(409, "challenge", "class.error.debrief_open")
    return row, is_lecturer


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
    row, is_lecturer = await _debrief_challenge(request, hub)
    games = await hub.db(hub.store.best_games, row["id"])
    law = await _law(hub, row)
    viewer = None if is_lecturer else _bearer(request) or None
    anonymous = hub.debrief.anonymous and not is_lecturer
    doc = debrief_doc(row, games, law, anonymous, viewer)
    doc["showing"] = hub.debrief.to_json()
    return JSONResponse(doc, headers={"Cache-Control": "no-store"})


async def debrief_pair(request: Request) -> Response:
    """The two games the lecturer set side by side, their paths at every frame."""
    hub = guard(request)
    row, is_lecturer = await _debrief_challenge(request, hub)
    if hub.debrief.pair is None:
        raise RefusedError(404, "pair", "class.error.no_entry")
    loop = asyncio.get_running_loop()
    ranks = {g["entry"]: g["rank"] for g in await hub.db(hub.store.best_games, row["id"])}
    games = []
    for entry in hub.debrief.pair:
        found = await hub.db(hub.store.entry_code, entry)
        if found is None or found[2] != row["id"]:
            raise RefusedError(404, "pair", "class.error.no_entry")
        if entry not in hub.pair_paths:
            path = await loop.run_in_executor(hub.pool, every_frame, found[1])
            hub.pair_paths[entry] = path
        name = None if hub.debrief.anonymous and not is_lecturer else found[0]
        path = hub.pair_paths[entry]
        games.append({"entry": entry, "name": name, "rank": ranks.get(entry), "path": path})
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
    hub = lecturer(request)
    doc = await read_json(request, hub.limits.body_bytes)
    state = hub.debrief
    anonymous = doc.get("anonymous", state.anonymous)
    if not isinstance(anonymous, bool):
        raise RefusedError(400, "anonymous", "class.error.value", allowed="true, false")
    pick, pair = state.pick, state.pair
    if "pick" in doc:
        pick = None if doc["pick"] is None else _entry_id({"entry": doc["pick"]})
        await _show(hub, pick)
        pair = None  # the picked game's replay takes the pair's place
    if "pair" in doc:
        pair = _pair_of(doc)
        for entry in pair or ():
            if await hub.db(hub.store.entry_code, entry) is None:
                raise RefusedError(404, "pair", "class.error.no_entry")
    hub.debrief = Showing(anonymous, pick, pair)
    await hub.publish()
    return JSONResponse(hub.debrief.to_json())


async def entries(request: Request) -> Response:
    """Every entry of the current challenge, hidden ones too (the lecturer's list)."""
    hub = lecturer(request)
    row = await hub.db(hub.store.latest)
    if row is None:
        return JSONResponse({"challenge": None, "entries": [], "rejected": 0})
    listed = await hub.db(hub.store.entries, row["id"])
    doc = challenge_info(row)
    showing = hub.showing["entry"] if hub.showing else None
    return JSONResponse(
        {"challenge": doc, "entries": listed, "rejected": row["rejected"], "showing": showing}
    )


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
    """The current challenge's leaderboard (the replay's code as for the stream)."""
    hub = guard(request)
    return JSONResponse(await hub.board(keyed(request, hub)))


def _stream_refusal(hub: Hub, request: Request, with_key: bool) -> RefusedError | None:
    """Why one more stream is refused: too many in all or from this address (429); the
    key's holders are counted apart, so students' streams never crowd the projector out."""
    limits = hub.limits
    if with_key:
        if sum(1 for s in hub.listeners if s.keyed) >= limits.keyed_listeners:
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
    with_key = keyed(request, hub)
    refused = _stream_refusal(hub, request, with_key)
    if refused:
        raise refused
    listener = Listener(asyncio.Queue(maxsize=4), address(request), with_key)
    hub.listeners.append(listener)
    first = json.dumps(await hub.board(with_key))
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


ROUTES = [
    Route("/", game),
    Route("/projector", projector),
    Route("/lecturer", lecturer_page),
    Route("/api/challenge", get_challenge, methods=["GET"]),
    Route("/api/challenge", open_challenge, methods=["POST"]),
    Route("/api/challenge/close", close_challenge, methods=["POST"]),
    Route("/api/join", join, methods=["POST"]),
    Route("/api/submit", submit, methods=["POST"]),
    Route("/api/me", me),
    Route("/api/hide", hide, methods=["POST"]),
    Route("/api/rename", rename, methods=["POST"]),
    Route("/api/show", show, methods=["POST"]),
    Route("/api/entries", entries),
    Route("/api/leaderboard", leaderboard),
    Route("/api/debrief", debrief, methods=["GET"]),
    Route("/api/debrief", set_debrief, methods=["POST"]),
    Route("/api/debrief/pair", debrief_pair),
    Route("/api/stream", stream),
    Route("/api/export.csv", export_csv),
]


async def _refused(request: Request, exc: Exception) -> Response:
    """The JSON answer of a RefusedError."""
    assert isinstance(exc, RefusedError)
    return refused_response(exc, hub_of(request).words.of(request))


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


def create_app(
    store_path: Path | str,
    pool_workers: int,
    limits: Limits | None = None,
    join_url: str | None = None,
) -> Starlette:
    """The class server's app: SQLite at store_path, `pool_workers` verifying processes.

    The lecturer's token is the one whose digest the store holds (`new_lecturer_token`).
    join_url: the students' address shown on the projector (default: the one it was read at).
    """

    @asynccontextmanager
    async def lifespan(app: Starlette) -> AsyncIterator[None]:
        store = Store(Path(store_path))
        hub = Hub(store, limits or Limits(), _pool(pool_workers), pool_workers)
        app.state.hub = hub
        app.state.game_page = pages.game_page()
        loop = asyncio.get_running_loop()
        await asyncio.gather(*(loop.run_in_executor(hub.pool, _ready) for _ in range(pool_workers)))
        watcher = asyncio.create_task(_close_on_time(hub))
        try:
            yield
        finally:
            watcher.cancel()
            hub.pool.shutdown(cancel_futures=True)
            hub.db_thread.submit(hub.store.close).result()
            hub.db_thread.shutdown()

    handlers = {RefusedError: _refused, 404: _no_route, 405: _no_route}
    app = Starlette(routes=ROUTES, lifespan=lifespan, exception_handlers=handlers)
    app.state.join_url = join_url
    app.add_middleware(_SafeHeaders)
    return app


async def _close_on_time(hub: Hub) -> None:
    """Close the open challenge as its time window ends and tell every page at once
    (not only refuse games later): projector, lecturer and students see it together."""
    while True:
        row = await hub.db(hub.store.open_one)
        if row is not None and row["closes_at"] is not None and not _is_open(row):
            await hub.db(hub.store.close_challenge, row["id"])
            await hub.publish()
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
