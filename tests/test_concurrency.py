"""Issue 18: two processes writing the score table or the settings at once lose nothing."""

from __future__ import annotations

import json
import subprocess
import sys
from datetime import datetime, timedelta
from pathlib import Path

import pytest

from evapcool.game.highscores import Entry, HighScoreTable, sorted_entries
from evapcool.game.settings import DEFAULTS, Settings, load_settings, save_settings

ADDS = 200

# Writer k adds scores k, k + 2, k + 4, ...: each add is a new best, so a writer that
# neither re-reads nor locks keeps only its own ten and drops the other's better ones.
_SCORER = """
import sys
from datetime import datetime, timedelta
from evapcool.game.highscores import HighScoreTable
path, k, adds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
table = HighScoreTable(path)
t0 = datetime(2024, 1, 1)
for i in range(adds):
    score = k + 2 * i
    table.add(f"p{k}", score, 1.0, when=t0 + timedelta(seconds=score))
    assert not table.take_notices()
"""


def test_two_processes_adding_200_scores_each_lose_nothing(tmp_path: Path) -> None:
    path = tmp_path / "highscores.json"
    procs = [
        subprocess.Popen([sys.executable, "-c", _SCORER, str(path), str(k), str(ADDS)])
        for k in (0, 1)
    ]
    assert [p.wait(timeout=300) for p in procs] == [0, 0]
    t0 = datetime(2024, 1, 1)
    every = [
        Entry(f"p{s % 2}", s, 1.0, (t0 + timedelta(seconds=s)).strftime("%Y-%m-%d %H:%M:%S"))
        for s in range(2 * ADDS)
    ]
    table = HighScoreTable(path)
    assert table.entries == sorted_entries(every)  # the best 10 of all 400
    assert {e.name for e in table.entries} == {"p0", "p1"}
    assert not table.take_notices()
    assert sorted(p.name for p in tmp_path.iterdir()) == [".highscores.json.lock", path.name]


def test_a_table_open_in_another_window_keeps_its_results(tmp_path: Path) -> None:
    path = tmp_path / "highscores.json"
    t = datetime(2024, 5, 1)
    first, second = HighScoreTable(path), HighScoreTable(path)
    first.add("Ada", 30, 10.0, when=t)
    assert second.add("Bob", 20, 10.0, when=t) == 2  # merged with Ada's, not over it
    assert [e.name for e in HighScoreTable(path).entries] == ["Ada", "Bob"]
    second.reset()  # a reset clears everyone's (the UI asks first)
    first.add("Cy", 5, 1.0, when=t)
    assert [e.name for e in HighScoreTable(path).entries] == ["Cy"]


def test_a_table_that_cannot_be_saved_keeps_results_and_saves_them_later(tmp_path: Path) -> None:
    folder = tmp_path / "data"
    folder.write_text("")  # a file where the folder should be
    table = HighScoreTable(folder / "highscores.json")
    table.add("Ada", 9, 1.0)
    assert table.take_notices()
    folder.unlink()
    table.add("Bob", 3, 1.0)
    assert [e.name for e in HighScoreTable(folder / "highscores.json").entries] == ["Ada", "Bob"]


_SETTER = """
import sys
from dataclasses import replace
from evapcool.game.settings import load_settings, save_settings
path, field, values = sys.argv[1], sys.argv[2], sys.argv[3].split(",")
for v in values:
    base, _ = load_settings(path)
    value = float(v) if field == "radius" else int(v) if field == "n_atoms" else v
    assert save_settings(replace(base, **{field: value}), path, base=base) == []
"""


def test_two_windows_changing_different_settings_keep_both(tmp_path: Path) -> None:
    path = tmp_path / "settings.json"
    save_settings(DEFAULTS, path)
    laws = ",".join(["cup", "seed"] * 50 + ["cup"])
    escapes = ",".join(["knife", "rim"] * 50 + ["knife"])
    procs = [
        subprocess.Popen([sys.executable, "-c", _SETTER, str(path), "tc_law", laws]),
        subprocess.Popen([sys.executable, "-c", _SETTER, str(path), "escape", escapes]),
    ]
    assert [p.wait(timeout=300) for p in procs] == [0, 0]
    assert load_settings(path) == (Settings(tc_law="cup", escape="knife"), [])


def test_save_with_a_base_writes_only_what_changed(tmp_path: Path) -> None:
    path = tmp_path / "settings.json"
    mine = DEFAULTS
    save_settings(mine, path)
    save_settings(Settings(radius=5.0, n_atoms=300), path)  # another window meanwhile
    assert save_settings(Settings(escape="knife"), path, base=mine) == []
    assert load_settings(path)[0] == Settings(radius=5.0, n_atoms=300, escape="knife")
    assert json.loads(path.read_text())["escape"] == "knife"


# Two sweeps into one output folder (two terminals resuming it, or a shared folder): each
# writes part files and merges every part into runs.parquet, then removes the parts.
_SWEEPER = """
import sys
from pathlib import Path

import pytest
from evapcool.lab.sweeps import _consolidate, _Writer
out, k, runs = Path(sys.argv[1]), sys.argv[2], int(sys.argv[3])
writer = _Writer(out)
for i in range(runs):
    writer.add({"run_id": f"{k}-{i}", "status": "ok", "n_final": i}, None)
    writer.flush()
    notices = []
    _consolidate(out, False, notices)
    assert not notices, notices
"""


def test_two_sweeps_merging_into_one_folder_lose_no_run(tmp_path: Path) -> None:
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    from evapcool.lab.sweeps import RUNS_FILE

    runs = 40
    procs = [
        subprocess.Popen([sys.executable, "-c", _SWEEPER, str(tmp_path), k, str(runs)])
        for k in ("a", "b")
    ]
    assert [p.wait(timeout=300) for p in procs] == [0, 0]
    ids = set(pd.read_parquet(tmp_path / RUNS_FILE)["run_id"])
    assert ids == {f"{k}-{i}" for k in ("a", "b") for i in range(runs)}
    assert not list((tmp_path / "parts").glob("*.parquet"))
