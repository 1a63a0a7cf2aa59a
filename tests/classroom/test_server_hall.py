"""Issue 46: a hall behind one address. 300 students from one loopback address, each with
its token, join, follow the board live, poll it, send games and read the debrief without
one refusal; one address flooding without a token is refused while another class's
student and the projector (the same address) stay served; a flood with one token is
limited to that token."""

from __future__ import annotations

import asyncio
import contextlib
import json
from collections.abc import AsyncIterator, Awaitable, Callable, Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from classhelp import SEED, SETTINGS, Server, open_challenge, start_server

from evapcool.classroom.guessing import WRONG_CODES
from evapcool.classroom.halls import HALL_RATE, KEY_RATE, STUDENT_RATE
from evapcool.classroom.hub import CLIENT_RATE, Limits
from evapcool.classroom.ratelimit import Rate
from evapcool.game.replay import Recording, encode

HALL = 300
#: Frames of the lost games the hall sends (a short challenge: 300 cheap replays).
FRAMES = 60
OTHER_ADDRESS = "127.0.0.2"
#: The hall's phones are this many HTTP clients (all from 127.0.0.1).
GROUPS = 15


def lost_game(k: int) -> str:
    """Student k's game: the trap held at its own height until the frame limit, lost (0
    atoms), a different game for every k."""
    return encode(Recording(SETTINGS, SEED, ((320.0 + 0.25 * k, FRAMES),), False, 0, FRAMES))


def bearer(token: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {token}"}


@contextlib.asynccontextmanager
async def stream(client: httpx.AsyncClient, url: str) -> AsyncIterator[tuple[int, Any]]:
    """An open event stream: its status and its lines (read only when asked)."""
    async with client.stream("GET", url) as events:
        if events.status_code != 200:
            await events.aread()
        yield events.status_code, events.aiter_lines()


async def next_board(lines: Any, done: Callable[[dict[str, Any]], bool]) -> dict[str, Any]:
    """The first board on a stream for which `done` holds."""
    async for line in lines:
        if line.startswith("data: ") and done(board := json.loads(line[6:])):
            found: dict[str, Any] = board
            return found
    raise AssertionError("the stream ended")


async def _hall(server: Server, challenge: object) -> dict[str, Any]:
    """Every student of the hall as the page goes: the board, the join, the stream with
    the token, the standing, a poll (the page's without its stream), the game; then the
    close, seen on every stream, and the debrief."""
    statuses: list[tuple[str, int]] = []
    finals: list[tuple[int, dict[str, Any]]] = []
    joined = asyncio.Event()
    closed = asyncio.Event()
    count = 0

    async def call(client: httpx.AsyncClient, what: str, fn: Awaitable[httpx.Response]) -> Any:
        answer = await fn
        statuses.append((what, answer.status_code))
        return answer.json() if answer.status_code == 200 else None

    async def student(client: httpx.AsyncClient, k: int) -> None:
        nonlocal count
        api = server.base + "/api/"
        await call(client, "board", client.get(api + "leaderboard"))
        doc = await call(client, "join", client.post(api + "join", json={"name": f"Hall {k}"}))
        token = doc["token"]
        async with stream(client, api + f"stream?token={token}") as (status, lines):
            statuses.append(("stream", status))
            await next_board(lines, lambda b: True)
            await call(client, "me", client.get(api + "me", headers=bearer(token)))
            await call(client, "poll", client.get(api + "leaderboard", headers=bearer(token)))
            count += 1
            if count == HALL:
                joined.set()
            await joined.wait()  # all 300 streams open at once
            body = {"challenge": challenge, "code": lost_game(k)}
            await call(
                client, "submit", client.post(api + "submit", json=body, headers=bearer(token))
            )
            await closed.wait()
            finals.append((k, await next_board(lines, lambda b: not b["info"]["open"])))
            await call(client, "debrief", client.get(api + "debrief", headers=bearer(token)))

    async def lecturer(client: httpx.AsyncClient) -> None:
        await joined.wait()
        while sum(1 for what, s in statuses if what == "submit") < HALL:
            await asyncio.sleep(0.2)
        closing = client.post(server.base + "/api/challenge/close", headers=server.lecturer)
        assert (await closing).status_code == 200
        closed.set()

    # Phones in groups, each with its own connections (one pool of 600 is slow to search).
    limits = httpx.Limits(max_connections=2 * HALL // GROUPS + 10)
    async with contextlib.AsyncExitStack() as stack:
        clients = [
            await stack.enter_async_context(httpx.AsyncClient(timeout=120, limits=limits))
            for _ in range(GROUPS)
        ]
        phones = (student(clients[k % GROUPS], k) for k in range(HALL))
        await asyncio.gather(lecturer(clients[0]), *phones)
    return {"statuses": statuses, "finals": finals}


def test_a_hall_behind_one_address_is_never_refused(server: Server) -> None:
    challenge = open_challenge(server, lost=True, max_frames=FRAMES)["id"]
    got = asyncio.run(asyncio.wait_for(_hall(server, challenge), 300))
    refused = [(what, status) for what, status in got["statuses"] if status != 200]
    assert refused == []
    assert len(got["statuses"]) == HALL * 7
    # every stream followed the board live to the close, all 300 games on it; each phone's
    # stream carries its own row alone (not 300 rows four times a second)
    assert len(got["finals"]) == HALL
    for k, board in got["finals"]:
        assert board["players"] == HALL and "replay" not in board
        assert [row["name"] for row in board["entries"]] == [f"Hall {k}"]
    # more than the address alone would have been let through at once
    assert CLIENT_RATE.burst < HALL * 7 and Limits().address_listeners < HALL


@pytest.fixture
def department(store_at: Path | str) -> Iterator[Server]:
    running = start_server(store_at, extra=("--department",))
    yield running
    running.stop()


def _two_classes(server: Server) -> tuple[dict[str, str], dict[str, str], str]:
    """Two classes of one lecturer (each a dict with its code and projector link), and the
    lecturer's token."""
    made = httpx.post(
        server.base + "/api/admin/lecturers", json={"name": "Ada"}, headers=server.lecturer
    )
    lecturer = made.json()["token"]
    for name in ("Flooded", "Other"):
        answer = httpx.post(
            server.base + "/api/classes", json={"name": name}, headers=bearer(lecturer)
        )
        assert answer.status_code == 200, answer.text
    classes = httpx.get(server.base + "/api/classes", headers=bearer(lecturer)).json()["classes"]
    by_name = {c["name"]: c for c in classes}
    return by_name["Flooded"], by_name["Other"], lecturer


async def _flood(
    client: httpx.AsyncClient,
    url: str,
    head: dict[str, str],
    got: list[tuple[int, str]],
    stop: asyncio.Event,
) -> None:
    """Requests 20 at a time until `stop`; each answer's status and refused field in `got`."""

    async def one() -> None:
        while not stop.is_set():
            answer = await client.get(url, headers=head)
            field = answer.json()["error"]["field"] if answer.status_code == 429 else ""
            got.append((answer.status_code, field))

    await asyncio.gather(*(one() for _ in range(20)))


async def _while_refused(
    client: httpx.AsyncClient,
    url: str,
    head: dict[str, str],
    others: Callable[[], Awaitable[dict[str, int]]],
) -> tuple[list[tuple[int, str]], dict[str, int]]:
    """A flood of `url` until it is refused; then `others` (the statuses of their calls)
    while it goes on."""
    got: list[tuple[int, str]] = []
    stop = asyncio.Event()
    flood = asyncio.create_task(_flood(client, url, head, got, stop))
    while not any(status == 429 for status, _ in got):
        await asyncio.sleep(0.05)
    try:
        served = await others()
    finally:
        stop.set()
        await flood
    return got, served


async def _served(
    client: httpx.AsyncClient, calls: dict[str, tuple[str, str, dict[str, str], Any]]
) -> dict[str, int]:
    """Each call's status: (method, url, headers, JSON body); "stream" ones opened and
    read to their first board."""
    out = {}
    for name, (method, url, head, body) in calls.items():
        if method == "STREAM":
            async with client.stream("GET", url, headers=head) as events:
                out[name] = events.status_code
                if events.status_code == 200:
                    await next_board(events.aiter_lines(), lambda b: True)
            continue
        answer = await client.request(method, url, headers=head, json=body)
        out[name] = answer.status_code
    return out


Flooded = tuple[list[tuple[int, str]], dict[str, int]]


async def _other_class(
    server: Server, flooded: dict[str, str], other: dict[str, str], lecturer: str
) -> Flooded:
    rules = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "escape": SETTINGS.escape}
    rules |= {"seed": SEED, "lost": True, "max_frames": FRAMES}
    base_b = server.base + f"/c/{other['code']}/api/"
    key = "?" + other["projector"].split("?", 1)[1]
    elsewhere = httpx.AsyncHTTPTransport(local_address=OTHER_ADDRESS)
    async with (
        httpx.AsyncClient(timeout=60, limits=httpx.Limits(max_connections=60)) as client,
        httpx.AsyncClient(timeout=60, transport=elsewhere) as far,
    ):
        opened = await client.post(base_b + "challenge", json=rules, headers=bearer(lecturer))
        # Before the flood: the projector page opened, the student joined (as in a lecture).
        assert (await client.get(server.base + other["projector"])).status_code == 200
        token = (await client.post(base_b + "join", json={"name": "Bo"})).json()["token"]
        game = {"challenge": opened.json()["id"], "code": lost_game(1)}
        calls = {
            "student's stream": ("STREAM", base_b + f"stream?token={token}", {}, None),
            "student's poll": ("GET", base_b + "leaderboard", bearer(token), None),
            "student's standing": ("GET", base_b + "me", bearer(token), None),
            "student's game": ("POST", base_b + "submit", bearer(token), game),
            "projector's stream": ("STREAM", base_b + "stream" + key, {}, None),
            "projector's board": ("GET", base_b + "leaderboard" + key, {}, None),
            "projector's page": ("GET", server.base + other["projector"], {}, None),
        }

        async def others() -> dict[str, int]:
            served = await _served(client, calls)
            served["another address"] = (await far.get(base_b + "leaderboard")).status_code
            return served

        # a cheap call (the class, then 401): the address's burst is spent in a few seconds
        flooded_me = server.base + f"/c/{flooded['code']}/api/me"
        return await _while_refused(client, flooded_me, {}, others)


def test_an_address_flooding_without_a_token_leaves_others_served(department: Server) -> None:
    flooded, other, lecturer = _two_classes(department)
    got, served = asyncio.run(
        asyncio.wait_for(_other_class(department, flooded, other, lecturer), 120)
    )
    assert {field for status, field in got if status == 429} == {"client"}
    # the address's whole burst went through before (less the setup's few calls)
    assert sum(1 for status, _ in got if status == 401) >= CLIENT_RATE.burst - 20
    assert served == dict.fromkeys(served, 200) and len(served) == 8, served


async def _one_token(
    server: Server, flooder: str, honest: str, challenge: object
) -> tuple[list[int], str, list[tuple[int, str]], dict[str, int]]:
    api = server.base + "/api/"
    async with httpx.AsyncClient(timeout=60, limits=httpx.Limits(max_connections=60)) as client:
        async with contextlib.AsyncExitStack() as held:
            streams = []
            for _ in range(Limits().token_listeners + 1):
                events = await held.enter_async_context(
                    client.stream("GET", api + f"stream?token={flooder}")
                )
                if events.status_code != 200:
                    await events.aread()
                streams.append((events.status_code, events))
        statuses = [status for status, _ in streams]
        last = streams[-1][1]
        stream_field = last.json()["error"]["field"] if statuses[-1] == 429 else ""
        game = {"challenge": challenge, "code": lost_game(2)}
        calls = {
            "another student's stream": ("STREAM", api + f"stream?token={honest}", {}, None),
            "another student's standing": ("GET", api + "me", bearer(honest), None),
            "another student's game": ("POST", api + "submit", bearer(honest), game),
            "the address without a token": ("GET", api + "leaderboard", {}, None),
        }
        got, served = await _while_refused(
            client, api + "me", bearer(flooder), lambda: _served(client, calls)
        )
    return statuses, stream_field, got, served


def test_a_flood_with_one_token_is_limited_to_that_token(server: Server) -> None:
    challenge = open_challenge(server, lost=True, max_frames=FRAMES)["id"]
    flooder, honest = (
        httpx.post(server.base + "/api/join", json={"name": n}).json()["token"]
        for n in ("Flooder", "Honest")
    )
    statuses, stream_field, got, served = asyncio.run(
        asyncio.wait_for(_one_token(server, flooder, honest, challenge), 120)
    )
    bound = Limits().token_listeners
    assert statuses == [200] * bound + [429] and stream_field == "token"
    assert {field for status, field in got if status == 429} == {"token"}
    assert served == dict.fromkeys(served, 200) and len(served) == 4, served


def _rate(rate: Rate) -> str:
    """A bucket as the guide says it."""
    if rate.per_second >= 1:
        return f"{rate.burst:.0f} at once, then {rate.per_second:.0f} a second"
    return f"{rate.burst:.0f} at once, then one every {1 / rate.per_second:.0f} s"


def test_the_guide_states_the_limits() -> None:
    guide = " ".join(
        (Path(__file__).resolve().parents[2] / "docs" / "class.md").read_text().split()
    )
    limits = Limits()
    rows = [
        ("requests without a checked secret", "client address", _rate(limits.client)),
        ("a student's requests", "token", _rate(STUDENT_RATE)),
        ("one class's students' requests", "class and client address", _rate(HALL_RATE)),
        ("the projector's and lecturer's requests", "key or token", _rate(KEY_RATE)),
        ("games sent (across processes)", "token", _rate(limits.submit)),
        ("joins (across processes)", "class and client address", _rate(limits.join)),
        ("wrong join codes (across processes)", "client address", _rate(WRONG_CODES)),
        (
            "verifications in flight or waiting",
            "token; class and client address",
            f"{limits.student_jobs}; {limits.hall_jobs}",
        ),
        ("event streams in all (without the key)", "process", f"{limits.listeners}"),
        (
            "a student's event streams",
            "token; class and client address",
            f"{limits.token_listeners}; {limits.hall_listeners}",
        ),
        (
            "event streams without a token",
            "client address; process",
            f"{limits.address_listeners}; {limits.anonymous_listeners}",
        ),
        (
            "the projector's and lecturer's event streams (key)",
            "class",
            f"{limits.keyed_listeners}",
        ),
    ]
    for row in rows:
        assert "| " + " | ".join(row) + " |" in guide, row
    assert f"`--max-students`, {limits.students} unless set" in guide
