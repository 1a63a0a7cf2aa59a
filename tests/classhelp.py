"""The class server's tests' kit: honest recordings made once, a real server in a subprocess."""

from __future__ import annotations

import contextlib
import dataclasses
import json
import os
import re
import signal
import socket
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import IO

import httpx

import evapcool
from evapcool.game.replay import Recorder, Recording, Settings, encode

SRC = Path(evapcool.__file__).resolve().parents[1]
SETTINGS = Settings()
SEED = 11
#: Seconds a server gets to start (the verifying worker loads the compiled engine).
START_TIMEOUT = 90.0
_CACHE: dict[tuple[int, int], Recording] = {}


def student_games(
    students: int, forged_every: int = 10, seed: int = SEED
) -> list[tuple[str, str, bool]]:
    """(name, code, honest) per student: all different honest games on `seed`, and one in
    `forged_every` claiming one atom more than it won (the load test and the benchmark)."""
    out = []
    wins = (rec for k in range(1, 10 * students + 1) if (rec := variant(seed, k)).won)
    for i, rec in zip(range(students), wins, strict=False):
        honest = i % forged_every != 0
        if not honest:
            rec = dataclasses.replace(rec, won=True, score=rec.score + 1)
        out.append((f"Student {i:03d}", encode(rec), honest))
    return out


def variant(seed: int, k: int) -> Recording:
    """Game k on `seed`: the autopilot with its trap nudged by a few px in one stretch.

    Each k is a different game with its true result (played here, so it verifies); a
    few do not win (the server takes only won games unless the challenge says otherwise).
    """
    if (seed, k) not in _CACHE:
        _CACHE[seed, k] = _play(seed, k)
    return _CACHE[seed, k]


def _play(seed: int, k: int, budget: int = 5000) -> Recording:
    from evapcool.game.autopilot import clamp_height, load_strategy, read
    from evapcool.game.rules import Game

    control = load_strategy("demo").controller()
    game = Game(SETTINGS.game_config(seed, "fast"))
    game.toggle_pause()
    start, nudge = (37 * k) % 600, 1.0 + (k % 11)
    for frame in range(budget):
        height = control(read(game.sim, mass=1.0))
        if k and start <= frame < start + 60:
            height += nudge
        game.set_trap_height(clamp_height(height))
        game.run_frames(1)
        if game.won or game.sim.n_trapped == 0:
            break
    return Recorder(SETTINGS, seed, edition="web" if k % 2 else "desktop").finish(game)


def ramp_game(seed: int, k: int, lost_from: int = 28) -> Recording:
    """Game k on `seed` played by a ramp: the trap lowered by 3 to 6 px every 12 + k frames
    to a floor (60 to 100 px); from k = lost_from on, held at 300 px for 1500 frames, a game
    that never wins (the debrief's tests: every k a different game)."""
    from evapcool.game.rules import Game

    lost = k >= lost_from
    step, every, floor = 3 + k % 4, 12 + k, 300 if lost else 60 + 10 * (k % 5)
    game = Game(SETTINGS.game_config(seed, "fast"))
    game.toggle_pause()
    height = 400.0
    for frame in range(1500 if lost else 6000):
        if frame % every == 0 and height > floor:
            height = max(floor, height - step)
        game.set_trap_height(height)
        game.run_frames(1)
        if game.won or game.sim.n_trapped == 0:
            break
    return Recorder(SETTINGS, seed, edition="web").finish(game)


def code(seed: int, k: int) -> str:
    """The replay code of game k on `seed`."""
    return encode(variant(seed, k))


def free_port() -> int:
    """A TCP port free on 127.0.0.1 just now."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@dataclass
class Server:
    """A running `evapcool class` subprocess."""

    proc: subprocess.Popen[str]
    base: str
    token: str
    data: Path | str

    @property
    def lecturer(self) -> dict[str, str]:
        return {"Authorization": f"Bearer {self.token}"}

    def stop(self, kill: bool = False) -> None:
        """SIGKILL (kill=True: the server and its verifying workers, as a crash would) or
        SIGTERM, and wait for the process to end; no worker is left behind either way."""
        if self.proc.poll() is None:
            if kill:
                _signal_group(self.proc.pid, signal.SIGKILL)
            else:
                self.proc.send_signal(signal.SIGTERM)
        try:
            self.proc.wait(15)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait(15)
        _signal_group(self.proc.pid, signal.SIGKILL)
        if self.proc.stdout:
            self.proc.stdout.close()


def _signal_group(pid: int, sig: int) -> None:
    """Signal the server's process group (it leads a session of its own); gone is fine."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pid, sig)


def start_server(
    data: Path | str,
    workers: int = 1,
    port: int | None = None,
    token: str | None = None,
    extra: tuple[str, ...] = (),
    wrap: tuple[str, ...] = (),
) -> Server:
    """`evapcool class` on a free port with `data`; returns once it answers.

    data: a SQLite file, or a PostgreSQL database's URL (--db). token: the lecturer's
    token of a store served before (it prints none then; a new one with
    extra=("--new-link",)). wrap: a command to run the server's command line in (a sandbox).
    """
    import httpx

    port = port or free_port()
    env = {**os.environ, "PYTHONPATH": str(SRC), "LANG": "C.UTF-8", "LANGUAGE": "en"}
    cmd = [
        *wrap,
        sys.executable,
        "-m",
        "evapcool",
        "class",
        "--port",
        str(port),
        "--db" if isinstance(data, str) else "--data",
        str(data),
        "--workers",
        str(workers),
        *extra,
    ]
    proc = subprocess.Popen(
        cmd,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env=env,
        start_new_session=True,  # its own process group: a kill reaches its workers too
    )
    assert proc.stdout is not None
    first = lecturer_line(proc.stdout)
    found = re.search(r"token=(\S+)", first)
    if not (found or token):
        _signal_group(proc.pid, signal.SIGKILL)  # nothing left running behind a failure
        proc.wait(15)
        raise AssertionError(f"no lecturer link in {first!r}")
    server = Server(proc, f"http://127.0.0.1:{port}", found.group(1) if found else str(token), data)
    deadline = time.monotonic() + START_TIMEOUT
    while time.monotonic() < deadline:
        assert proc.poll() is None, "the server ended while starting"
        try:
            if httpx.get(server.base + "/api/leaderboard", timeout=2).status_code == 200:
                return server
        except httpx.TransportError:
            time.sleep(0.2)
    server.stop(kill=True)
    raise AssertionError("the server did not answer in time")


def lecturer_line(out: IO[str]) -> str:
    """The first line about the lecturer's page, or (--department) the administrator's
    (the engine may say it compiles first)."""
    for _ in range(20):
        line = out.readline()
        if not line or line.startswith(("Lecturer", "Administrator")):
            return line
    return ""


def open_challenge(server: Server, **params: object) -> dict[str, object]:
    """Open a challenge on the test seed and settings (params override)."""
    import httpx

    body = {
        "n_atoms": SETTINGS.n_atoms,
        "radius": SETTINGS.radius,
        "escape": SETTINGS.escape,
        "seed": SEED,
        **params,
    }
    answer = httpx.post(server.base + "/api/challenge", json=body, headers=server.lecturer)
    assert answer.status_code == 200, answer.text
    doc: dict[str, object] = answer.json()
    return doc


def join(server: Server, name: str) -> dict[str, str]:
    """A student's Authorization header."""
    import httpx

    answer = httpx.post(server.base + "/api/join", json={"name": name})
    assert answer.status_code == 200, answer.text
    return {"Authorization": f"Bearer {answer.json()['token']}"}


def browse(base: str, path: str, token: str) -> httpx.Response:
    """A page opened from its link as a browser does (issue 45): the ?token= answered by a
    redirect keeping it in a cookie, followed; the page as the browser then sees it."""
    import httpx

    with httpx.Client(base_url=base, follow_redirects=True) as client:
        return client.get(path, params={"token": token})


def projector_key(server: Server) -> str:
    """The projector's key, from the link on the lecturer's page."""
    page = browse(server.base, "/lecturer", server.token).text
    found = re.search(r'href="/projector\?key=([0-9a-f]+)"', page)
    assert found, "no projector link on the lecturer's page"
    return found.group(1)


async def watch_board(client: httpx.AsyncClient, server: Server, seen: dict[str, float]) -> None:
    """Follow the leaderboard's stream; note when each name first shows (perf_counter)."""
    async with client.stream("GET", server.base + "/api/stream") as events:
        async for line in events.aiter_lines():
            if line.startswith("data: "):
                now = time.perf_counter()
                for e in json.loads(line[6:])["entries"]:
                    seen.setdefault(e["name"], now)


if __name__ == "__main__":
    # `python tests/classhelp.py ramps N SEED`: N ramp games' codes as JSON (the Chromium
    # debrief test sends them).
    if len(sys.argv) == 4 and sys.argv[1] == "ramps":
        n, seed = int(sys.argv[2]), int(sys.argv[3])
        games = [ramp_game(seed, k) for k in range(n)]
        out = [
            {"code": encode(r), "won": r.won, "score": r.score, "frames": r.frames} for r in games
        ]
        print(json.dumps(out))
