"""`evapcool --class URL` (issue 22.4, desktop side): the applet joins a real class server,
plays its challenge's atoms, sends each win and shows the verified rank; without a server
the game goes on after one notice."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import ClassVar

import httpx
import pygame
import pytest
from apphelp import frames, key, play_ramp
from classhelp import SEED, SETTINGS, Server, code, free_port, open_challenge, start_server

from evapcool.app import cli
from evapcool.app.applet import App
from evapcool.app.classlink import ClassLink
from evapcool.game.rules import Game, GameConfig

pytestmark = pytest.mark.usefixtures("own_folders")


@pytest.fixture
def server(tmp_path: Path) -> Iterator[Server]:
    running = start_server(tmp_path / "class.sqlite")
    yield running
    running.stop()


@pytest.fixture
def class_app(tmp_path: Path) -> Iterator[list[App]]:
    apps: list[App] = []
    yield apps
    for a in apps:
        a.close()


def join_app(
    apps: list[App], tmp_path: Path, url: str, name: str = "Ada", named: bool = True
) -> App:
    """An App with --class url --name name (named=False: the login's name, no --name),
    as the command line makes it."""
    app = App(
        Game(GameConfig()),
        data_dir=tmp_path / "data",
        config_dir=tmp_path / "config",
        screen=(1600, 1000),
        classroom=ClassLink(url, name, timeout=10, named=named),
    )
    apps.append(app)
    return app


def frames_until(app: App, done, seconds: float = 60.0) -> None:
    """Frames (the game paused or on) until done() holds; the network answers meanwhile."""
    deadline = time.monotonic() + seconds
    while not done():
        assert time.monotonic() < deadline, app.visible_notices
        frames(app)
        time.sleep(0.01)


def test_the_applet_joins_plays_the_challenge_and_its_win_is_ranked(server, class_app, tmp_path):
    challenge = open_challenge(server)
    app = join_app(class_app, tmp_path, server.base + "/")
    frames_until(app, lambda: app.challenge is not None)
    assert app.challenge.id == challenge["id"] and app.game.sim.seed == SEED
    assert app.game.config.n_atoms == SETTINGS.n_atoms
    assert any(f"Class challenge {challenge['id']}" in n for n in app.visible_notices)
    key(app, pygame.K_r)  # a restart keeps the class's atoms
    assert app.game.sim.seed == SEED
    play_ramp(app)
    frames_until(app, lambda: any(n.startswith("Class: rank") for n in app.visible_notices))
    board = httpx.get(server.base + "/api/leaderboard").json()
    [entry] = board["entries"]
    assert (entry["name"], entry["score"], entry["edition"]) == ("Ada", app.game.score, "desktop")
    assert f"rank 1, {app.game.score} atoms" in app.visible_notices[-1]
    # --name was given: the local table takes it, no "Type your name" (issue 49.8).
    assert app.scores.name_box is None and app.scores.ready_for_next
    assert [(e.name, e.score) for e in app.scores.table.entries] == [("Ada", app.game.score)]


def test_without_a_name_given_the_win_asks_for_one(server, class_app, tmp_path):
    open_challenge(server)
    app = join_app(class_app, tmp_path, server.base + "/", "login", named=False)
    frames_until(app, lambda: app.challenge is not None)
    key(app, pygame.K_r)
    play_ramp(app)
    assert app.game.won and app.scores.name_box is not None


def test_started_again_the_applet_is_the_same_student(server, class_app, tmp_path):
    open_challenge(server)
    first = join_app(class_app, tmp_path, server.base + "/")
    frames_until(first, lambda: first.classroom.link.token is not None)
    first.close()
    class_app.remove(first)
    again = join_app(class_app, tmp_path, server.base + "/")  # the same data folder
    frames_until(again, lambda: again.classroom.link.token is not None)
    assert again.classroom.link.token == first.classroom.link.token
    assert not any("not accepted" in n for n in again.visible_notices)
    elsewhere = join_app(class_app, tmp_path / "other", server.base + "/")  # another Ada
    frames_until(elsewhere, lambda: any("not accepted" in n for n in elsewhere.visible_notices))
    assert "Too like Ada" in elsewhere.visible_notices[-1]


def test_a_refusal_is_shown_in_the_servers_words(server, class_app, tmp_path):
    app = join_app(class_app, tmp_path, server.base)  # no challenge open yet
    frames_until(app, lambda: any("not accepted" in n for n in app.visible_notices))
    assert app.challenge is None and "challenge" in app.visible_notices[-1].lower()


class _AwayOnce(BaseHTTPRequestHandler):
    """Passes requests on to the class server, but answers the first game sent with 503 (a
    department's database away for a moment), Retry-After 1."""

    upstream = ""
    submits: ClassVar[list[int]] = []

    def do_GET(self) -> None:
        self._pass(httpx.get(self.upstream + self.path, headers=self._headers()))

    def do_POST(self) -> None:
        body = self.rfile.read(int(self.headers["Content-Length"]))
        if self.path.endswith("/api/submit"):
            self.submits.append(len(self.submits))
            if len(self.submits) == 1:
                self.send_response(503)
                self.send_header("Retry-After", "1")
                self.send_header("Content-Type", "application/json")
                self.end_headers()
                self.wfile.write(b'{"error": {"field": "store", "message": "away"}}')
                return
        url = self.upstream + self.path
        self._pass(httpx.post(url, content=body, headers=self._headers(), timeout=60))

    def _headers(self) -> dict[str, str]:
        return {k: v for k, v in self.headers.items() if k.lower() != "host"}

    def _pass(self, answer: httpx.Response) -> None:
        self.send_response(answer.status_code)
        self.send_header("Content-Type", answer.headers.get("content-type", "text/plain"))
        self.end_headers()
        self.wfile.write(answer.content)

    def log_message(self, *args: object) -> None:
        pass


def test_a_game_answered_503_is_sent_again(server):
    challenge = open_challenge(server)
    _AwayOnce.upstream, _AwayOnce.submits = server.base, []
    proxy = ThreadingHTTPServer(("127.0.0.1", 0), _AwayOnce)
    threading.Thread(target=proxy.serve_forever, daemon=True).start()
    try:
        link = ClassLink(f"http://127.0.0.1:{proxy.server_address[1]}/", "Ro", timeout=10)
        link.start()
        seen = []
        deadline = time.monotonic() + 60
        while not any(e.kind == "joined" for e in seen):
            assert time.monotonic() < deadline and not any(e.kind != "joined" for e in seen), seen
            seen += link.poll()
            time.sleep(0.05)
        link.submit(code(SEED, 1))
        while not any(e.kind == "result" for e in seen):
            assert time.monotonic() < deadline, seen
            seen += link.poll()
            time.sleep(0.05)
    finally:
        proxy.shutdown()
    assert _AwayOnce.submits == [0, 1]  # refused once, then taken
    result = next(e for e in seen if e.kind == "result")
    assert result.value["challenge"] == challenge["id"] and result.value["rank"] == 1


def test_no_server_is_one_notice_and_the_game_goes_on(class_app, tmp_path):
    app = join_app(class_app, tmp_path, f"http://127.0.0.1:{free_port()}/")
    frames_until(app, lambda: any("did not answer" in n for n in app.visible_notices))
    key(app, pygame.K_SPACE)
    frames(app, 10)
    assert app.game.sim.time == 11.0  # the frame after Space, and ten more
    assert sum("did not answer" in n for n in app.visible_notices) == 1


@pytest.mark.parametrize("url", ["example.org", "ftp://h/", "http://", "http://h/?x=1"])
def test_a_bad_class_url_is_one_line_and_exit_2(url, capsys):
    assert cli.main(["--class", url, "--frames", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--class" in err[0] and "http://" in err[0]


def test_name_without_class_is_refused(capsys):
    assert cli.main(["--name", "Ada", "--frames", "1"]) == 2
    assert "--name needs --class" in capsys.readouterr().err


def test_a_name_longer_than_the_leaderboard_shows_is_refused(capsys):
    """One number everywhere (issue 34): the server keeps 24 characters, so --name takes 24."""
    from evapcool.limits import CLASS_NAME_MAX

    long = "Maximilian Alexander Schmidt"  # 28 characters: the server would keep 24
    args = ["--class", "http://127.0.0.1:9/", "--name", long, "--frames", "1"]
    assert cli.main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--name" in err[0] and f"at most {CLASS_NAME_MAX}" in err[0]
