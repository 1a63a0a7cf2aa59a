"""The class server's store: names cleaned, entries committed, CSV safe (issue 22)."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.classroom.store import BIDI_CONTROLS, NAME_MAX, Store, clean_name

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


@pytest.mark.parametrize("raw", ["", "   ", "\u202e\u202d", "\x00\x01", 42])
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
