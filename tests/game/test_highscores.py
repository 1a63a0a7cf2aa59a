"""High-score table: storing, ordering, top-10 cut, reset, corrupt and unwritable files."""

from __future__ import annotations

import json
import os
import tempfile
from datetime import datetime, timedelta
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool.game.highscores import (
    DEFAULT_NAME,
    MAX_ENTRIES,
    NAME_MAX,
    Entry,
    HighScoreTable,
    clean_name,
    format_seconds,
)

T0 = datetime(2024, 3, 1, 9, 0, 0)


def _table(tmp_path: Path) -> HighScoreTable:
    return HighScoreTable(tmp_path / "scores" / "highscores.json")


def test_missing_file_is_an_empty_table_without_notice(tmp_path: Path) -> None:
    table = _table(tmp_path)
    assert table.entries == []
    assert table.take_notices() == []


def test_stored_entry_survives_a_reload(tmp_path: Path) -> None:
    table = _table(tmp_path)
    rank = table.add("Ada", 23, 61.234, when=T0)
    assert rank == 1
    assert table.take_notices() == []
    again = HighScoreTable(table.path)
    assert again.entries == [Entry("Ada", 23, 61.23, "2024-03-01 09:00:00")]
    data = json.loads(table.path.read_text(encoding="utf-8"))
    assert data["entries"][0]["score"] == 23


def test_order_is_score_then_time_then_date(tmp_path: Path) -> None:
    table = _table(tmp_path)
    table.add("late-slow", 10, 90.0, when=T0 + timedelta(days=2))
    table.add("best", 30, 200.0, when=T0 + timedelta(days=3))
    table.add("early-slow", 10, 90.0, when=T0)
    table.add("fast", 10, 40.0, when=T0 + timedelta(days=5))
    assert [e.name for e in table.entries] == ["best", "fast", "early-slow", "late-slow"]
    assert [e.name for e in HighScoreTable(table.path).entries] == [
        "best",
        "fast",
        "early-slow",
        "late-slow",
    ]


def test_only_the_top_ten_are_kept(tmp_path: Path) -> None:
    table = _table(tmp_path)
    for i in range(MAX_ENTRIES):
        assert table.add(f"p{i}", 10 + i, 50.0, when=T0 + timedelta(minutes=i)) is not None
    assert len(table.entries) == MAX_ENTRIES
    # Too few atoms: not asked, not stored.
    assert not table.qualifies(5, 1.0)
    assert table.add("weak", 5, 1.0, when=T0) is None
    # A tie with the last row on score and time loses to the earlier date.
    assert not table.qualifies(10, 50.0)
    assert table.add("tie", 10, 50.0, when=T0 + timedelta(days=1)) is None
    # A better result enters at its rank and pushes the last one out.
    assert table.qualifies(15, 10.0)
    assert table.add("new", 15, 10.0, when=T0 + timedelta(days=1)) == 5
    names = [e.name for e in HighScoreTable(table.path).entries]
    assert len(names) == MAX_ENTRIES
    assert "p0" not in names and "weak" not in names and "tie" not in names
    assert names[4] == "new"


def test_reset_empties_the_table_on_disk(tmp_path: Path) -> None:
    table = _table(tmp_path)
    table.add("Ada", 20, 30.0, when=T0)
    assert table.reset() is True
    assert table.entries == []
    assert HighScoreTable(table.path).entries == []


def test_names_are_cleaned() -> None:
    assert clean_name("  Marie \t Curie\n") == "Marie Curie"
    assert clean_name("a\x00b\x1bc") == "a b c"
    assert clean_name("x" * 100) == "x" * NAME_MAX
    assert clean_name("Émilie du Châtelet") == "Émilie du Châtel"
    assert clean_name("\x07\n ") == ""


def test_empty_name_is_stored_as_default(tmp_path: Path) -> None:
    table = _table(tmp_path)
    table.add("   ", 3, 1.0, when=T0)
    assert table.entries[0].name == DEFAULT_NAME


def test_bad_results_are_refused(tmp_path: Path) -> None:
    table = _table(tmp_path)
    bad = ((-1, 1.0), (2.5, 1.0), (True, 1.0), (3, float("nan")), (3, -1.0), (3, 1e308))
    for score, seconds in bad:
        with pytest.raises(ValueError):
            table.add("x", score, seconds)  # type: ignore[arg-type]
    assert table.entries == []


def test_format_seconds() -> None:
    assert format_seconds(83.25) == "1:23.3"
    assert format_seconds(0) == "0:00.0"
    assert format_seconds(59.96) == "1:00.0"


@pytest.mark.parametrize(
    "content",
    [
        "{not json",
        "[1, 2, 3]",
        '{"entries": "nope"}',
        '{"entries": [{"name": "x", "score": -4, "seconds": 1, "date": "2024-01-01 00:00:00"}]}',
        '{"entries": [{"name": "x", "score": 4, "seconds": 1, "date": "yesterday"}]}',
        # A time of 1e308 s (the table's m:ss.s of it overflowed) and one past the limit.
        '{"entries": [{"name": "x", "score": 4, "seconds": 1e308, "date": "2024-01-01 00:00:00"}]}',
        '{"entries": [{"name": "x", "score": 4, "seconds": 1e10, "date": "2024-01-01 00:00:00"}]}',
    ],
)
def test_corrupt_file_is_set_aside_and_a_new_table_started(tmp_path: Path, content: str) -> None:
    path = tmp_path / "highscores.json"
    path.write_text(content, encoding="utf-8")
    table = HighScoreTable(path)
    assert table.entries == []
    notices = table.take_notices()
    assert len(notices) == 1 and "damaged" in notices[0]
    kept = list(tmp_path.glob("highscores.json.corrupt-*"))
    assert len(kept) == 1 and kept[0].read_text(encoding="utf-8") == content
    assert not path.exists()
    # The new table works and is written afresh.
    assert table.add("Ada", 7, 12.0, when=T0) == 1
    assert [e.name for e in HighScoreTable(path).entries] == ["Ada"]


def test_binary_garbage_is_set_aside(tmp_path: Path) -> None:
    path = tmp_path / "highscores.json"
    path.write_bytes(b"\xff\xfe\x00garbage")
    table = HighScoreTable(path)
    assert table.entries == [] and "damaged" in table.take_notices()[0]
    assert len(list(tmp_path.glob("highscores.json.corrupt-*"))) == 1


def test_data_folder_that_cannot_be_created_gives_a_notice(tmp_path: Path) -> None:
    # A plain file where the folder should be: fails for root too.
    blocker = tmp_path / "evapcool"
    blocker.write_text("", encoding="utf-8")
    table = HighScoreTable(blocker / "highscores.json")
    assert table.add("Ada", 9, 5.0, when=T0) == 1  # kept for the session
    assert table.entries[0].name == "Ada"
    notices = table.take_notices()
    assert len(notices) == 1 and "could not be saved" in notices[0]
    assert table.reset() is False


def _chmod_is_effective(folder: Path) -> bool:
    probe = folder / "probe"
    try:
        probe.write_text("x", encoding="utf-8")
    except OSError:
        return True
    probe.unlink()
    return False


def test_read_only_data_folder_gives_a_notice_not_a_crash(tmp_path: Path) -> None:
    folder = tmp_path / "ro"
    folder.mkdir()
    path = folder / "highscores.json"
    HighScoreTable(path).add("Old", 4, 9.0, when=T0)
    os.chmod(folder, 0o500)
    try:
        if not _chmod_is_effective(folder):
            pytest.skip("chmod does not stop this user writing (root?)")
        table = HighScoreTable(path)
        assert [e.name for e in table.entries] == ["Old"]  # still readable
        assert table.add("Ada", 9, 5.0, when=T0) == 1
        notices = table.take_notices()
        assert len(notices) == 1 and "could not be saved" in notices[0]
        assert [e.name for e in table.entries] == ["Ada", "Old"]
    finally:
        os.chmod(folder, 0o700)
    assert [e.name for e in HighScoreTable(path).entries] == ["Old"]


_results = st.tuples(
    st.integers(min_value=0, max_value=60),
    st.floats(min_value=0, max_value=500, allow_nan=False).map(lambda s: round(s, 2)),
    st.integers(min_value=0, max_value=10_000),  # minutes after T0
)


@settings(max_examples=40, deadline=None)
@given(st.lists(_results, max_size=25))
def test_table_is_always_the_best_ten_in_order(results: list[tuple[int, float, int]]) -> None:
    with tempfile.TemporaryDirectory() as d:
        table = HighScoreTable(Path(d) / "highscores.json")
        for i, (score, seconds, minutes) in enumerate(results):
            table.add(f"p{i}", score, seconds, when=T0 + timedelta(minutes=minutes))
        rows = table.entries
        assert len(rows) == min(MAX_ENTRIES, len(results))
        keys = [(-e.score, e.seconds, e.date) for e in rows]
        assert keys == sorted(keys)
        # Exactly the best ten by (score desc, time asc, date asc), ties keep insertion order.
        expect = sorted(
            (
                (-s, sec, (T0 + timedelta(minutes=m)).strftime("%Y-%m-%d %H:%M:%S"), f"p{i}")
                for i, (s, sec, m) in enumerate(results)
            ),
            key=lambda k: k[:3],
        )[:MAX_ENTRIES]
        assert [e.name for e in rows] == [k[3] for k in expect]
        assert HighScoreTable(table.path).entries == rows
