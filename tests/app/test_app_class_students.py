"""`evapcool --class URL` for the students of issue 45 (desktop side, a real class server):
a game lost for good is sent when the challenge counts lost games, and only then; a
student of two classes keeps a token for each, and is herself again in each."""

from __future__ import annotations

import json
import time
from collections.abc import Iterator
from pathlib import Path

import httpx
import pygame
import pytest
from apphelp import frames, key
from classhelp import SEED, SETTINGS, Server, open_challenge, start_server

from evapcool.app.applet import HEIGHT_STEP, App
from evapcool.app.classlink import TOKENS_FILE, ClassLink, class_key
from evapcool.game.rules import HEIGHT_MAX, Game, GameConfig

pytestmark = pytest.mark.usefixtures("own_folders")


@pytest.fixture
def server(tmp_path: Path) -> Iterator[Server]:
    running = start_server(tmp_path / "class.sqlite")
    yield running
    running.stop()


@pytest.fixture
def apps() -> Iterator[list[App]]:
    made: list[App] = []
    yield made
    for a in made:
        a.close()


def join_app(apps: list[App], data: Path, url: str, name: str = "Ada") -> App:
    app = App(
        Game(GameConfig()),
        data_dir=data / "data",
        config_dir=data / "config",
        screen=(1600, 1000),
        classroom=ClassLink(url, name, timeout=20),
    )
    apps.append(app)
    return app


def frames_until(app: App, done, seconds: float = 90.0) -> None:
    deadline = time.monotonic() + seconds
    while not done():
        assert time.monotonic() < deadline, app.visible_notices
        frames(app)
        time.sleep(0.01)


def lose(app: App) -> None:
    """The player drops the trap to the floor (Down, held) and plays: one atom is left
    above Tc(1) after a few seconds, a game lost for good."""
    key(app, pygame.K_DOWN, times=int(HEIGHT_MAX / HEIGHT_STEP) + 2)
    key(app, pygame.K_SPACE)
    frames_until(app, lambda: app.game.lost, seconds=120)
    assert not app.game.won


def test_a_game_lost_for_good_is_sent_when_lost_games_count(server, apps, tmp_path):
    open_challenge(server, lost=True)
    app = join_app(apps, tmp_path, server.base + "/")
    frames_until(app, lambda: app.challenge is not None)
    assert app.challenge.lost and app.game.sim.seed == SEED
    lose(app)
    frames_until(app, lambda: any(n.startswith("Class: rank") for n in app.visible_notices))
    assert "rank 1, 0 atoms" in app.visible_notices[-1]
    frames(app, 60)  # the lost game goes on being lost: sent once
    listed = httpx.get(server.base + "/api/entries", headers=server.lecturer).json()
    [entry] = listed["entries"]
    assert (entry["name"], entry["score"], entry["edition"]) == ("Ada", 0, "desktop")


def test_a_lost_game_is_kept_when_the_challenge_takes_wins_only(server, apps, tmp_path):
    open_challenge(server)
    app = join_app(apps, tmp_path, server.base + "/")
    frames_until(app, lambda: app.challenge is not None)
    assert not app.challenge.lost
    lose(app)
    frames(app, 60)
    assert not any("Sending your game" in n for n in app.visible_notices)
    listed = httpx.get(server.base + "/api/entries", headers=server.lecturer).json()
    assert listed["entries"] == [] and listed["rejected"] == 0


@pytest.fixture
def department(tmp_path: Path) -> Iterator[Server]:
    running = start_server(tmp_path / "dept.sqlite", extra=("--department",))
    yield running
    running.stop()


def test_a_student_of_two_classes_keeps_a_token_for_each(department, apps, tmp_path):
    admin = {"Authorization": f"Bearer {department.token}"}
    made = httpx.post(department.base + "/api/admin/lecturers", json={"name": "Lin"}, headers=admin)
    lecturer = {"Authorization": f"Bearer {made.json()['token']}"}
    codes = []
    for name in ("Optics", "Heat"):
        room = httpx.post(department.base + "/api/classes", json={"name": name}, headers=lecturer)
        codes.append(room.json()["code"])
        body = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "seed": SEED}
        opened = httpx.post(
            f"{department.base}/c/{codes[-1]}/api/challenge",
            json={**body, "escape": SETTINGS.escape},
            headers=lecturer,
        )
        assert opened.status_code == 200, opened.text
    urls = [f"{department.base}/c/{c}/" for c in codes]
    tokens = []
    for url in [*urls, urls[0].lower()]:
        app = join_app(apps, tmp_path, url, "Mia")  # the same data folder each time
        frames_until(app, lambda a=app: a.classroom.link.token is not None)
        assert not any("not accepted" in n for n in app.visible_notices), app.visible_notices
        tokens.append(app.classroom.link.token)
        app.close()
        apps.remove(app)
    # Class A again (its code typed in lower case): herself, not a second Mia refused.
    assert tokens[2] == tokens[0] != tokens[1]
    kept = json.loads((tmp_path / "data" / TOKENS_FILE).read_text("utf-8"))
    assert kept == {class_key(urls[0]): tokens[0], class_key(urls[1]): tokens[1]}
