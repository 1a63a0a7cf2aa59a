"""The students of issue 45, against a really started department server: a token per class
(the page's API and the desktop's `classlink`), lost games taken and ranked when the
challenge counts them, a student's place found by her entry (names hidden too), `?lang=`
carried through the join page and its redirects."""

from __future__ import annotations

import json
import time
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest
from classhelp import SEED, SETTINGS, Server, code, start_server

from evapcool.app.classlink import TOKENS_FILE, ClassLink, class_key
from evapcool.game.replay import Recorder, encode
from evapcool.game.rules import HEIGHT_MIN, Game


@pytest.fixture
def department(tmp_path: Path) -> Iterator[Server]:
    running = start_server(tmp_path / "class.sqlite", extra=("--department",))
    yield running
    running.stop()


def bearer(token: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {token}"}


def two_classes(server: Server) -> tuple[str, str, str]:
    """A lecturer's token and two classes' join codes."""
    made = httpx.post(
        server.base + "/api/admin/lecturers", json={"name": "Lin"}, headers=bearer(server.token)
    )
    lecturer = str(made.json()["token"])
    codes = []
    for name in ("Physics 1", "Physics 2"):
        doc = httpx.post(
            server.base + "/api/classes", json={"name": name}, headers=bearer(lecturer)
        ).json()
        codes.append(str(doc["code"]))
    return lecturer, codes[0], codes[1]


def open_in(server: Server, code_: str, lecturer: str, **extra: object) -> int:
    body = {"n_atoms": SETTINGS.n_atoms, "radius": SETTINGS.radius, "escape": SETTINGS.escape}
    answer = httpx.post(
        f"{server.base}/c/{code_}/api/challenge",
        json={**body, "seed": SEED, **extra},
        headers=bearer(lecturer),
    )
    assert answer.status_code == 200, answer.text
    return int(answer.json()["id"])


def join(server: Server, code_: str, name: str, token: str | None = None) -> httpx.Response:
    body = {"name": name} if token is None else {"name": name, "token": token}
    return httpx.post(f"{server.base}/c/{code_}/api/join", json=body)


def test_a_student_of_two_classes_is_herself_in_each(department: Server) -> None:
    _, a, b = two_classes(department)
    in_a, in_b = join(department, a, "Mia").json(), join(department, b, "Mia").json()
    assert (in_a["class"], in_b["class"]) == (a, b) and in_a["token"] != in_b["token"]
    # Each class's saved token brings her back as herself, by the name the class has.
    again_a = join(department, a, "Mia", in_a["token"]).json()
    again_b = join(department, b, "Mia", in_b["token"]).json()
    assert again_a == in_a and again_b == in_b
    # One token for the whole server (before issue 45) is a stranger in the other class.
    refused = join(department, a, "Mia", in_b["token"])
    assert refused.status_code == 409 and "Mia" in refused.json()["error"]["message"]


def test_the_desktop_keeps_one_token_per_class(department: Server, tmp_path: Path) -> None:
    lecturer, a, b = two_classes(department)
    for c in (a, b):
        open_in(department, c, lecturer)
    tokens = {}
    # The same class typed two ways (lower case and a dash) is one class.
    typed = {a: f"{department.base}/c/{a}/", b: f"{department.base}/c/{b[:3].lower()}-{b[3:]}"}
    for round_ in range(2):
        for c, url in typed.items():
            link = ClassLink(url, "Mia", timeout=20)
            link.remember_in(tmp_path)
            link.start()
            events = wait_events(link, 1)
            assert [e.kind for e in events] == ["joined"], events
            assert events[0].name == "Mia"
            if round_ == 0:
                tokens[c] = link.token
            assert link.token == tokens[c]  # started again: the same student in each
    kept = json.loads((tmp_path / TOKENS_FILE).read_text("utf-8"))
    assert kept == {class_key(typed[a]): tokens[a], class_key(typed[b]): tokens[b]}
    assert class_key(typed[b]) == f"{department.base}/c/{b}/"


def wait_events(link: ClassLink, n: int, seconds: float = 60.0) -> list:
    """The link's first n events (its thread answers meanwhile)."""
    got: list = []
    deadline = time.monotonic() + seconds
    while len(got) < n:
        assert time.monotonic() < deadline, got
        got += link.poll()
        time.sleep(0.02)
    return got


def test_class_key_is_the_server_and_the_class() -> None:
    assert class_key("http://Host:80/c/abc-123") == "http://host/c/ABC123/"
    assert class_key("https://h.example:8443/") == "https://h.example:8443/"
    assert class_key("http://[::1]:8765/c/x7k2pq/") == "http://[::1]:8765/c/X7K2PQ/"
    with pytest.raises(ValueError, match="--class must be"):
        class_key("ftp://host/")


def lost_code() -> str:
    """A game lost for good on the test seed: the trap dropped to the floor at once, played
    until one atom is left (above Tc(1))."""
    game = Game(SETTINGS.game_config(SEED, "fast"))
    game.toggle_pause()
    game.set_trap_height(HEIGHT_MIN)
    while not game.lost:
        game.run_frames(1)
        assert not game.won and game.sim.time < 3000
    return encode(Recorder(SETTINGS, SEED, edition="web").finish(game))


def test_lost_games_count_when_the_challenge_says_so(department: Server) -> None:
    lecturer, a, b = two_classes(department)
    open_in(department, a, lecturer, lost=True)
    open_in(department, b, lecturer)  # wins only
    lost = lost_code()
    doc = httpx.get(f"{department.base}/c/{a}/api/challenge").json()
    assert doc["lost"] is True
    players = {}
    games = (("Ann", code(SEED, 1)), ("Ben", lost), ("Cy", code(SEED, 3)), ("Dee", lost))
    for name, game in games:
        token = join(department, a, name).json()["token"]
        players[name] = token
        challenge = httpx.get(f"{department.base}/c/{a}/api/challenge").json()["id"]
        sent = httpx.post(
            f"{department.base}/c/{a}/api/submit",
            json={"challenge": challenge, "code": game},
            headers=bearer(token),
            timeout=120,
        )
        assert sent.status_code == 200, sent.text
    got = sent.json()  # Dee lost the same way as Ben: a lost game is never a copy
    assert got["lost"] is True and got["count"] == 4 and got["best"] == 0
    ben = httpx.get(f"{department.base}/c/{a}/api/me", headers=bearer(players["Ben"])).json()
    # A lost game is ranked with 0 atoms: after the wins (ties: fewer frames, then earlier).
    assert (ben["best"], ben["rank"], ben["count"], ben["used"]) == (0, 3, 4, 1)
    board = httpx.get(f"{department.base}/c/{a}/api/leaderboard").json()
    by_entry = {e["entry"]: e for e in board["entries"]}
    assert by_entry[ben["best_entry"]] == {**by_entry[ben["best_entry"]], "name": "Ben", "score": 0}
    # The challenge taking wins only refuses the same lost game before replaying it.
    token = join(department, b, "Ben").json()["token"]
    challenge = httpx.get(f"{department.base}/c/{b}/api/challenge").json()["id"]
    refused = httpx.post(
        f"{department.base}/c/{b}/api/submit",
        json={"challenge": challenge, "code": lost},
        headers=bearer(token),
    )
    assert refused.status_code == 422 and refused.json()["error"]["field"] == "won"


def test_a_student_finds_her_place_by_entry_with_names_hidden(department: Server) -> None:
    lecturer, a, _ = two_classes(department)
    challenge = open_in(department, a, lecturer)
    tokens = {}
    for k, name in enumerate(("Ann", "Ben", "Cy", "Dee"), 1):
        tokens[name] = join(department, a, name).json()["token"]
        sent = httpx.post(
            f"{department.base}/c/{a}/api/submit",
            json={"challenge": challenge, "code": code(SEED, k)},
            headers=bearer(tokens[name]),
            timeout=120,
        )
        assert sent.status_code == 200, sent.text
    hidden = httpx.post(
        f"{department.base}/c/{a}/api/debrief", json={"anonymous": True}, headers=bearer(lecturer)
    )
    assert hidden.status_code == 200, hidden.text
    board = httpx.get(f"{department.base}/c/{a}/api/leaderboard").json()
    assert {e["name"] for e in board["entries"]} == {None}
    rows = {e["entry"]: e["rank"] for e in board["entries"]}
    assert sorted(rows.values()) == [1, 2, 3, 4]
    for token in tokens.values():
        me = httpx.get(f"{department.base}/c/{a}/api/me", headers=bearer(token)).json()
        assert rows[me["best_entry"]] == me["rank"] and me["count"] == 4


def test_lang_is_carried_through_the_join_page_and_its_redirects(department: Server) -> None:
    _, a, _ = two_classes(department)
    page = httpx.get(department.base + "/", params={"lang": "de"})
    assert '<html lang="de"' in page.text and "Einer Klasse beitreten" in page.text
    assert '<input type="hidden" name="lang" value="de">' in page.text
    # The form's GET carries lang; the redirect keeps it into the class's page.
    went = httpx.get(department.base + "/", params={"code": a.lower(), "lang": "de"})
    assert went.status_code == 303 and went.headers["location"] == f"/c/{a}/?lang=de"
    slash = httpx.get(f"{department.base}/c/{a.lower()}", params={"lang": "ar"})
    assert slash.status_code == 308 and slash.headers["location"] == f"/c/{a.lower()}/?lang=ar"
    followed = httpx.get(f"{department.base}/c/{a}", params={"lang": "de"}, follow_redirects=True)
    assert followed.status_code == 200 and str(followed.url).endswith(f"/c/{a}/?lang=de")
    wrong = httpx.get(department.base + "/", params={"code": "ZZZZZZ", "lang": "de"})
    assert "Keine Klasse hat diesen Code" in wrong.text
    # Without lang: the browser's language, and no lang added on the way.
    plain = httpx.get(department.base + "/", params={"code": a})
    assert plain.headers["location"] == f"/c/{a}/"
    arabic = httpx.get(department.base + "/", headers={"accept-language": "ar"})
    assert 'dir="rtl"' in arabic.text and "lang" not in arabic.text.split("<form")[1]
