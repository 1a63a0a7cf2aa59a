"""The class server's state (Hub): the store and its threads, the verifying workers, the
request limits, this process's event streams and the boards sent to them; the watcher
closing challenges as their time windows end."""

from __future__ import annotations

import asyncio
import contextlib
import json
import multiprocessing
import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

from evapcool.classroom.boards import _board, _send_boards, phone_text
from evapcool.classroom.debrief import Law
from evapcool.classroom.fairqueue import FairQueue
from evapcool.classroom.halls import Buckets
from evapcool.classroom.ratelimit import Rate, RateLimiter
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.store import ClassStore, Store, StoreAwayError, is_url
from evapcool.classroom.streamkeys import drop_stale
from evapcool.classroom.verifier import warm
from evapcool.classroom.words import Words

T = TypeVar("T")
#: Seconds between looks at the open challenge's time window: when it ends, the server
#: closes the challenge and tells every page (within this, well inside the pages' 2 s).
WINDOW_CHECK = 0.25
#: Seconds at least between two boards sent to a room's streams (the changes meanwhile
#: make one board).
BOARD_GAP = 0.25
#: Seconds at least between two boards sent to a room's joined students (a phone shows its
#: place: once a second is enough); a new round, its close or the debrief's view go at once.
PHONE_GAP = 1.0
#: Seconds between forgetting idle rate buckets held in the database.
BUCKET_SWEEP = 60.0
#: Seconds a client is told to wait (Retry-After) while the database does not answer.
STORE_RETRY = 5
#: Threads (and pooled connections) for a store shared by several processes.
SHARED_DB_THREADS = 8
#: API requests per client address without a checked secret (halls.py): the pages, joins,
#: wrong codes. A hall of 300 behind one NAT address opens the page, reads the board and
#: joins (3 each) inside the burst; its students' calls then count against their tokens.
CLIENT_RATE = Rate(burst=1500, per_second=100)
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
    #: Verifications in flight or waiting, per student token and per class and address (a
    #: hall of 300 sending at once fits; the fair queue serves each class and address in turn).
    student_jobs: int = 2
    hall_jobs: int = 600
    #: Players a class file holds (`evapcool class --max-students`).
    students: int = 2000
    #: Open event streams (halls.py): in all; without a student's token in all and per
    #: client address; per student token, and per class and address (a hall's); the
    #: projector's and the lecturer's (with the projector key) have their own bound per
    #: class and never wait for these.
    listeners: int = 6000
    anonymous_listeners: int = 1000
    address_listeners: int = 20
    token_listeners: int = 3
    hall_listeners: int = 800
    keyed_listeners: int = 16


@dataclass
class Listener:
    """One open event stream: its queue, its address, its class, whether it holds the key."""

    queue: asyncio.Queue[str]
    address: str
    keyed: bool
    room: int = DEFAULT_ROOM
    #: The key it was opened with (checked for the stream's life), and whether it ended.
    key: str | None = None
    closed: bool = False
    #: The student's token it was opened with (its limits follow the token), if any.
    token: str | None = None

    def close(self) -> None:
        """End the stream: its generator returns at its next look (an empty text wakes it)."""
        self.closed = True
        if self.queue.full():
            self.queue.get_nowait()
        self.queue.put_nowait("")


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
    #: Each room's count of announced changes (what this process built from it is stale).
    generation: dict[int, int] = field(default_factory=dict)
    #: Requests whose client left mid-body (logged once, at the stop).
    cut_uploads: int = 0
    #: When each room's board was last sent to this process's streams (monotonic).
    sent_at: dict[int, float] = field(default_factory=dict)
    #: ... to its joined students' streams, with what must reach them at once (PHONE_GAP),
    #: and the rooms whose phones wait for a board.
    phones_at: dict[int, float] = field(default_factory=dict)
    phone_phase: dict[int, str] = field(default_factory=dict)
    phones_late: set[int] = field(default_factory=set)

    def __post_init__(self) -> None:
        # Request buckets are one process's flood guard; submissions and joins are counted
        # in the store (across processes when it is shared).
        self.buckets = Buckets(RateLimiter(self.limits.client))
        self.queue = FairQueue(self.workers, self.limits.student_jobs, self.limits.hall_jobs)
        self.wake = asyncio.Event()

    async def db(self, fn: Callable[..., T], *args: Any) -> T:
        """Run a store call on the store's threads (off the event loop)."""
        return await asyncio.get_running_loop().run_in_executor(self.db_thread, fn, *args)

    async def board(self, room: int, keyed: bool = False) -> dict[str, Any]:
        """The leaderboard of a room's current (open, else last) challenge; the replay's
        code only for the key's holders while that game's challenge is open; the debrief's
        state (no names in its anonymous mode)."""
        return await self.db(_board, self.store, room, keyed)

    async def phones_board(self, room: int) -> tuple[dict[str, Any], dict[str, dict[str, Any]]]:
        """The board of joined students' streams and each one's own row (boards.phone_text)."""
        _, board, mine = await self.db(_send_boards, self.store, room, set(), True)
        return board, mine

    async def publish(self, room: int) -> None:
        """A room's board changed: tell every process sharing the store, or (one process)
        have it sent to this one's streams (`forward`)."""
        self.generation[room] = self.generation.get(room, 0) + 1  # stale here at once
        if self.store.shared:
            # if the database is away, every process sends all its boards anew once it hears
            # from the database again
            with contextlib.suppress(StoreAwayError):
                await self.db(self.store.notify, room)
        elif self._due(room) and room not in self.pending:
            await self.send(room)  # at once, as it happens (a burst's next ones wait)
        else:
            self.changed(room)

    def _due(self, room: int) -> bool:
        """Whether a room's board may be sent now (none sent in the last BOARD_GAP)."""
        return time.monotonic() - self.sent_at.get(room, float("-inf")) >= BOARD_GAP

    async def send(self, room: int) -> None:
        """Send a room's leaderboard to this process's streams of it (its joined students'
        as `_phones_due` allows); a slow one keeps only the newest."""
        self.sent_at[room] = time.monotonic()
        await drop_stale(self, [s for s in self.listeners if s.room == room and s.keyed])
        here = [s for s in self.listeners if s.room == room and not s.closed]
        if not here:
            return  # no stream of it here: nothing to read
        kinds = {s.keyed for s in here if s.token is None}
        phones = any(s.token is not None for s in here)
        texts, board, mine = await self.db(_send_boards, self.store, room, kinds, phones)
        if phones and not self._phones_due(room, board):
            here = [s for s in here if s.token is None]
        for listener in here:
            if listener.queue.full():
                listener.queue.get_nowait()
            token = listener.token
            text = texts[listener.keyed] if token is None else phone_text(board, mine.get(token))
            listener.queue.put_nowait(text)

    def _phones_due(self, room: int, board: dict[str, Any]) -> bool:
        """Whether a room's joined students get this board: a new round, its close or the
        debrief's view at once, else at most one every PHONE_GAP (the newest is sent then)."""
        now = time.monotonic()
        phase = json.dumps([board["challenge"], board["open"], board["debrief"]])
        wait = self.phones_at.get(room, float("-inf")) + PHONE_GAP - now
        if phase == self.phone_phase.get(room) and wait > 0:
            if room not in self.phones_late:
                self.phones_late.add(room)
                asyncio.get_running_loop().call_later(wait, self._phones_wait_over, room)
            return False
        self.phone_phase[room], self.phones_at[room] = phase, now
        return True

    def _phones_wait_over(self, room: int) -> None:
        self.phones_late.discard(room)
        self.pending.add(room)
        self.wake.set()

    def changed(self, room: int | None) -> None:
        """A notice from the store (on the event loop): a room's board changed (None: any
        may have, after the connection was lost): what was built from it is stale. A send
        itself changes nothing (a debrief built meanwhile is kept)."""
        listened = {s.room for s in self.listeners}
        for stale in [room] if room is not None else {*self.generation, *listened}:
            self.generation[stale] = self.generation.get(stale, 0) + 1
        self.pending.update([room] if room is not None else listened)
        self.wake.set()

    async def forward(self) -> None:
        """Send the boards of the rooms announced changed: at once, but a room at most once
        every BOARD_GAP (the changes meanwhile make one board): a hall of 300 phones
        sending 25 games a second gets 4 boards a second each, not 25."""
        while True:
            await self.wake.wait()
            self.wake.clear()
            due = {room for room in self.pending if self._due(room)}
            self.pending -= due
            if self.pending:  # look again when the earliest of the others is due
                since = min(self.sent_at.get(r, 0.0) for r in self.pending)
                wait = max(0.01, since + BOARD_GAP - time.monotonic())
                asyncio.get_running_loop().call_later(wait, self.wake.set)
            unsent = set()
            for room in due:
                try:
                    await self.send(room)
                except StoreAwayError:
                    unsent.add(room)
            if unsent:  # sent once the database answers again
                await asyncio.sleep(STORE_RETRY)
                self.pending |= unsent
                self.wake.set()


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
