"""The class server's store: names cleaned, entries committed, CSV safe (issue 22)."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.classroom.store import (
    BIDI_CONTROLS,
    NAME_MAX,
    ClassFullError,
    NameTakenError,
    Store,
    clean_name,
)

HOSTILE = [
    "<script>alert(1)</script>",
    '=HYPERLINK("http://x")',
    "a\u202egnp.exe",
    "bell\x07\x00\nname",
    "x" * 10_000,
]


@given(st.text(max_size=200))
@settings(max_examples=200, deadline=None)
def test_clean_names_are_short_visible_and_without_bidi(raw: str) -> None:
    try:
        name = clean_name(raw)
    except ValueError as exc:
        assert "name" in str(exc)
        return
    assert 1 <= len(name) <= NAME_MAX and name == name.strip()
    assert not any(ch in BIDI_CONTROLS or (ch.isspace() and ch != " ") for ch in name)
    assert all(ch.isprintable() for ch in name)


@pytest.mark.parametrize(
    "raw", ["", "   ", "\u202e\u202d", "\x00\x01", 42, "\u3164\u3164", "\u2800 \u2800", "\ufe0f"]
)
def test_empty_or_non_text_names_are_refused(raw: object) -> None:
    with pytest.raises(ValueError, match="name"):
        clean_name(raw)


def test_entries_survive_reopening_and_csv_is_formula_safe(tmp_path: Path) -> None:
    path = tmp_path / "class.sqlite"
    store = Store(path)
    challenge = store.open_challenge({"n_atoms": 49}, seed=7, max_frames=3600, attempts=3)
    tokens = [store.join(name) for name in HOSTILE]
    for i, token in enumerate(tokens):
        store.add_entry(challenge, token, score=20 + i, frames=1000, edition="web")
    store.count_rejected(challenge)
    store.close()  # no checkpoint needed: a new connection reads the WAL

    again = Store(path)
    opened = again.open_one()
    assert opened is not None and opened["id"] == challenge and opened["rejected"] == 1
    board = again.leaderboard(challenge)
    assert [row[2] for row in board] == [24, 23, 22, 21, 20]
    again.hide(board[0][0])
    assert len(again.leaderboard(challenge)) == 4
    rows = list(csv.reader(io.StringIO(again.results_csv(challenge))))
    assert rows[0][:3] == ["rank", "name", "score"]
    names = [row[1] for row in rows[1:]]
    assert all(not n.startswith(("=", "+", "-", "@")) for n in names)
    assert '\'=HYPERLINK("http://x")' in names
    assert all(len(n) <= NAME_MAX + 1 for n in names)
    assert not any(ch in BIDI_CONTROLS for n in names for ch in n)


def test_entries_refused_after_the_window_closes_or_attempts_run_out(tmp_path: Path) -> None:
    store = Store(tmp_path / "class.sqlite")
    challenge = store.open_challenge({}, seed=1, max_frames=100, attempts=2, closes_at=1000.0)
    token = store.join("Ann")
    game = (5, 50, "web", "EC1.x.y", "moves")
    assert isinstance(store.add_if_allowed(challenge, token, game, now=999.0), int)
    assert store.add_if_allowed(challenge, token, game, now=1000.0) == "challenge"
    assert isinstance(store.add_if_allowed(challenge, token, game, now=1.0), int)
    assert store.add_if_allowed(challenge, token, game, now=1.0) == "attempts"
    first = store.entries(challenge)[0]["entry"]
    assert store.entry_code(first) == ("Ann", "EC1.x.y", challenge)  # type: ignore[arg-type]
    store.close_challenge(challenge)
    assert store.add_if_allowed(challenge, store.join("Bob"), game, now=1.0) == "challenge"
    assert store.open_one() is None and store.latest() is not None


def test_look_alike_names_refused_and_each_player_ranked_once(tmp_path: Path) -> None:
    store = Store(tmp_path / "class.sqlite")
    challenge = store.open_challenge({}, seed=1, max_frames=100, attempts=None)
    first, second = store.join("Sam"), store.join("Samuel")
    for twin in ("Sam", " SAM ", "S\u0430m", "\uff33am", "Sarn"):  # Cyrillic a, fullwidth S, rn
        with pytest.raises(NameTakenError) as taken:
            store.join(twin)
        assert taken.value.name == "Sam"
    store.add_entry(challenge, first, 3, 10, "web")
    store.add_entry(challenge, second, 4, 10, "web")
    store.add_entry(challenge, second, 2, 10, "web")
    assert [row[2] for row in store.leaderboard(challenge)] == [4, 3]
    assert (store.rank(challenge, second), store.rank(challenge, first)) == (1, 2)
    with pytest.raises(ClassFullError):
        store.join("Third", max_players=2)


def test_a_file_of_the_first_schema_gains_the_new_columns(tmp_path: Path) -> None:
    import sqlite3

    from evapcool.classroom.store import SCHEMA

    path = tmp_path / "old.sqlite"
    with sqlite3.connect(path) as old:
        old.executescript(SCHEMA)
    store = Store(path)
    challenge = store.open_challenge({}, seed=1, max_frames=100, attempts=None, closes_at=5.0)
    assert store.latest() == {**(store.open_one() or {}), "id": challenge, "closes_at": 5.0}


def test_a_round_keeps_the_time_it_ended(tmp_path: Path) -> None:
    """Closed by hand (with or without a window) or by a new round: the time it closed;
    closed by its window's end: that end (the history's times, issue 45)."""
    import time

    store = Store(tmp_path / "class.sqlite")
    by_hand = store.open_challenge({}, seed=1, max_frames=100, attempts=None)
    early = store.open_challenge({}, seed=2, max_frames=100, attempts=None, closes_at=4e9)
    before = time.time()
    store.close_challenge(early)  # by_hand was closed by this round's opening
    ran_out = store.open_challenge({}, seed=3, max_frames=100, attempts=None, closes_at=5.0)
    store.close_challenge(ran_out)
    after = time.time()
    ended = {c["id"]: c["closes_at"] for c in store.challenges()}
    assert before - 1 <= ended[by_hand] <= ended[early] <= after  # type: ignore[operator]
    assert ended[ran_out] == 5.0
    assert not store.close_challenge(early) and ended == {
        c["id"]: c["closes_at"] for c in store.challenges()
    }
