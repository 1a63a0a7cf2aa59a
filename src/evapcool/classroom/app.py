"""The class server's app: its routes (a single class's, each class's under /c/{code}, a
department's), its start and stop (the store, the verifying workers, the watcher closing
challenges on time, the thread following other processes' notices), and the app factory
for `uvicorn --factory` configured by the environment."""

from __future__ import annotations

import asyncio
import logging
import threading
from collections.abc import AsyncIterator, Callable
from concurrent.futures import ThreadPoolExecutor
from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.requests import ClientDisconnect, Request
from starlette.routing import Route

from evapcool.classroom import pages
from evapcool.classroom.errors import RefusedError
from evapcool.classroom.hub import (
    SHARED_DB_THREADS,
    Hub,
    Limits,
    _close_on_time,
    _pool,
    _ready,
    open_store,
)
from evapcool.classroom.numbers import digits_value
from evapcool.classroom.store import StoreAwayError
from evapcool.classroom.streamkeys import watch_keys
from evapcool.classroom.views import admin, department
from evapcool.classroom.views.answers import (
    _cut_upload,
    _no_route,
    _refused,
    _SafeHeaders,
    _store_away,
    _to_class,
)
from evapcool.classroom.views.board import leaderboard, projector, rounds, stream
from evapcool.classroom.views.debrief import debrief, debrief_pair, set_debrief
from evapcool.classroom.views.exports import export_csv, export_json
from evapcool.classroom.views.lecturer import (
    challenges,
    close_challenge,
    entries,
    hide,
    lecturer_page,
    open_challenge,
    rename,
    show,
)
from evapcool.classroom.views.play import game, get_challenge, join, me, submit

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
    ("/api/export.json", export_json, None),
    ("/api/rounds", rounds, None),
]


def routes(for_department: bool = False) -> list[Route]:
    """The single class's routes, each class's under /c/{code}, the department's calls; a
    department's root and /lecturer (its join page, a lecturer's classes) come first."""
    out = [Route(path, fn, methods=methods) for path, fn, methods in CLASS_ROUTES]
    out += [Route("/c/{code}" + path, fn, methods=methods) for path, fn, methods in CLASS_ROUTES]
    first = department.ROOT_ROUTES if for_department else []
    return [*first, *out, Route("/c/{code}", _to_class), *admin.ROUTES, *department.ROUTES]


def create_app(
    store_path: Path | str,
    pool_workers: int,
    limits: Limits | None = None,
    join_url: str | None = None,
    department: bool = False,
) -> Starlette:
    """The class server's app: the store at store_path (a SQLite file or a PostgreSQL URL),
    `pool_workers` verifying processes.

    The single class's lecturer's token is the one whose digest the store holds
    (`new_lecturer_token`). join_url: the students' address shown on the projector
    (default: the one it was read at). department: the root is the join-by-code page and
    /lecturer lists a lecturer's classes.
    """

    @asynccontextmanager
    async def lifespan(app: Starlette) -> AsyncIterator[None]:
        store = open_store(store_path)
        threads = SHARED_DB_THREADS if store.shared else 1
        hub = Hub(
            store,
            limits or Limits(),
            _pool(pool_workers),
            pool_workers,
            ThreadPoolExecutor(threads),
        )
        app.state.hub = hub
        pages.game_page()  # read and hashed once, before the first student asks
        loop = asyncio.get_running_loop()
        await asyncio.gather(*(loop.run_in_executor(hub.pool, _ready) for _ in range(pool_workers)))
        tasks = [
            asyncio.create_task(_close_on_time(hub)),
            asyncio.create_task(hub.forward()),
            asyncio.create_task(watch_keys(hub)),
        ]
        stop = threading.Event()
        listening = _listen(hub, loop, stop) if store.shared else None
        try:
            yield
        finally:
            if hub.cut_uploads:  # one line, not one traceback per phone that left
                logging.getLogger("uvicorn.error").warning(
                    "uploads cut mid-body: %d", hub.cut_uploads
                )
            stop.set()
            for task in tasks:
                task.cancel()
            hub.pool.shutdown(cancel_futures=True)
            if listening:
                listening.join(5)
            hub.db_thread.submit(hub.store.close).result()
            hub.db_thread.shutdown()

    handlers = {
        RefusedError: _refused,
        StoreAwayError: _store_away,
        ClientDisconnect: _cut_upload,
        404: _no_route,
        405: _no_route,
    }
    app = Starlette(routes=routes(department), lifespan=lifespan, exception_handlers=handlers)
    app.state.join_url = join_url
    app.state.department = department  # the class pages link to /lecturer's list
    app.add_middleware(_SafeHeaders)
    return app


def _listen(hub: Hub, loop: asyncio.AbstractEventLoop, stop: threading.Event) -> threading.Thread:
    """A thread following the store's notices (its own connection): each changed room is
    handed to the event loop, whose `forward` sends it to this process's streams."""

    def changed(room: int | None) -> None:
        loop.call_soon_threadsafe(hub.changed, room)

    thread = threading.Thread(
        target=hub.store.listen, args=(changed, stop), daemon=True, name="listen"
    )
    thread.start()
    return thread


#: The environment `app_from_env` reads (uvicorn --factory ... --workers N).
ENV_DB = "EVAPCOOL_CLASS_DB"
ENV_WORKERS = "EVAPCOOL_CLASS_WORKERS"
ENV_JOIN_URL = "EVAPCOOL_CLASS_URL"
ENV_STUDENTS = "EVAPCOOL_CLASS_MAX_STUDENTS"


def app_from_env() -> Starlette:
    """A department's app configured by the environment, for
    `uvicorn --factory evapcool.classroom.app:app_from_env --workers N`:
    EVAPCOOL_CLASS_DB (the PostgreSQL URL), EVAPCOOL_CLASS_WORKERS (verifying processes of
    each server process, 1), EVAPCOOL_CLASS_URL (the students' address),
    EVAPCOOL_CLASS_MAX_STUDENTS (per class, 2000)."""
    import os

    where = os.environ.get(ENV_DB)
    if not where:
        raise ValueError(f"{ENV_DB}: give the database (postgresql://... or a SQLite file)")
    workers = _env_int(ENV_WORKERS, 1, 64, 1)
    students = _env_int(ENV_STUDENTS, 1, 100_000, Limits().students)
    return create_app(
        where,
        workers,
        Limits(students=students),
        join_url=os.environ.get(ENV_JOIN_URL),
        department=True,
    )


def _env_int(name: str, low: int, high: int, default: int) -> int:
    """A whole number low..high from the environment (ValueError naming it otherwise)."""
    import os

    text = os.environ.get(name)
    if text is None:
        return default
    value = digits_value(text, low, high)
    if value is None:
        raise ValueError(f"{name}: must be a whole number {low}..{high} (got {text!r})")
    return value
