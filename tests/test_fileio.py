"""Atomic writes, stale temporaries, non-blocking capped reads, output paths, the lock."""

from __future__ import annotations

import os
import random
import signal
import stat
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from evapcool.fileio import (
    FileTooLargeError,
    LockTimeoutError,
    NotRegularFileError,
    _tmp_prefix,
    atomic_write_bytes,
    atomic_write_text,
    check_writable,
    locked,
    read_user_bytes,
    set_aside,
)


def test_atomic_write_replaces_whole_file_with_umask_mode(tmp_path) -> None:
    target = tmp_path / "out.csv"
    atomic_write_text(target, "a\n")
    atomic_write_text(target, "b\n")
    assert target.read_text() == "b\n"
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~umask
    assert [p.name for p in tmp_path.iterdir()] == ["out.csv"]  # no temporary left behind


def test_atomic_write_keeps_an_existing_files_mode(tmp_path) -> None:
    target = tmp_path / "scores.json"
    target.write_text("{}")
    target.chmod(0o640)
    atomic_write_bytes(target, b"[]")
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


def test_failed_write_leaves_old_file_and_no_temporary(tmp_path) -> None:
    target = tmp_path / "keep.txt"
    target.write_text("old")
    with pytest.raises(TypeError):
        atomic_write_bytes(target, "not bytes")  # type: ignore[arg-type]
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.txt"]


def test_set_aside_renames_beside_and_never_overwrites(tmp_path) -> None:
    a = tmp_path / "s.json"
    a.write_text("x")
    first = set_aside(a)
    a.write_text("y")
    second = set_aside(a)
    assert first != second and first.read_text() == "x" and second.read_text() == "y"
    assert not a.exists() and first.name.startswith("s.json.corrupt-")


# -- issue 18: stale temporaries, non-blocking reads, output paths, the lock -----------------
def _age(path: Path, seconds: float = 60.0) -> None:
    past = time.time() - seconds
    os.utime(path, (past, past))


def _leftover(target: Path) -> Path:
    """A temporary as a write killed between creating and renaming leaves it."""
    fd, tmp = tempfile.mkstemp(prefix=_tmp_prefix(target), suffix=".tmp", dir=target.parent)
    os.write(fd, b"half a fi")
    os.close(fd)
    _age(Path(tmp))
    return Path(tmp)


def test_next_write_removes_temporaries_of_killed_writes(tmp_path) -> None:
    target = tmp_path / "highscores.json"
    stale = [_leftover(target) for _ in range(3)]
    other = _leftover(tmp_path / "settings.json")  # another file's: not this write's business
    foreign = tmp_path / ".highscores.json.abc123.tmp"  # not made by evapcool
    foreign.write_text("keep")
    _age(foreign)
    atomic_write_text(target, "{}")
    assert not any(p.exists() for p in stale)
    assert other.exists() and foreign.exists()
    assert target.read_text() == "{}"


POSIX = pytest.mark.skipif(os.name == "nt", reason="POSIX signals and flock")
LINUX = pytest.mark.skipif(not Path("/proc/version").exists(), reason="Linux paths")


@POSIX
def test_a_fresh_or_live_temporary_is_left_alone(tmp_path) -> None:
    target = tmp_path / "out.csv"
    fresh = _leftover(target)
    os.utime(fresh)  # just made: maybe a writer between creating and locking it
    live = _leftover(target)
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "import fcntl, os, sys, time\n"
            "fd = os.open(sys.argv[1], os.O_RDWR)\n"
            "fcntl.flock(fd, fcntl.LOCK_EX)\n"
            "print('locked', flush=True)\n"
            "time.sleep(30)\n",
            str(live),
        ],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert holder.stdout.readline().strip() == "locked"
        atomic_write_text(target, "x")
        assert fresh.exists() and live.exists()
    finally:
        holder.kill()
        holder.wait()
    _age(fresh)
    atomic_write_text(target, "y")
    assert not fresh.exists() and not live.exists()


_WRITER = """
import sys
from evapcool.fileio import atomic_write_bytes
data = b"x" * (8 << 20)
print("go", flush=True)
while True:
    atomic_write_bytes(sys.argv[1], data)
"""


@POSIX
def test_writes_killed_at_random_moments_leave_nothing_after_the_next_write(tmp_path) -> None:
    target = tmp_path / "big.bin"
    rng = random.Random(5)
    # Kill at random moments until 3 kills have landed mid-write (a busy machine may give
    # the writer no time before some kills); at most 40 writers.
    for _ in range(40):
        if len([p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]) >= 3:
            break
        child = subprocess.Popen(
            [sys.executable, "-c", _WRITER, str(target)], stdout=subprocess.PIPE, text=True
        )
        assert child.stdout.readline().strip() == "go"
        time.sleep(rng.uniform(0.0, 0.3))
        child.send_signal(signal.SIGKILL)
        child.wait()
        child.stdout.close()
        if target.exists():
            assert target.stat().st_size == 8 << 20  # never torn
    leftovers = [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]
    assert leftovers  # the kills did land mid-write
    for p in leftovers:
        _age(p)
    atomic_write_bytes(target, b"done")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.bin"]


def test_temporary_names_fit_beside_a_long_name(tmp_path) -> None:
    target = tmp_path / ("n" * 250 + ".csv")
    atomic_write_text(target, "ok")
    assert target.read_text() == "ok"


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="POSIX FIFOs")
def test_a_fifo_is_refused_without_blocking(tmp_path) -> None:
    fifo = tmp_path / "settings.json"
    os.mkfifo(fifo)
    with pytest.raises(NotRegularFileError):
        read_user_bytes(fifo, 100)
    with pytest.raises(NotRegularFileError):
        read_user_bytes(tmp_path, 100)


def test_reads_are_capped(tmp_path) -> None:
    p = tmp_path / "big.json"
    p.write_bytes(b" " * 101)
    with pytest.raises(FileTooLargeError):
        read_user_bytes(p, 100)
    assert read_user_bytes(p, 101) == b" " * 101


@pytest.mark.parametrize(
    ("path", "words"),
    [
        (lambda d: d / ("x" * 300 + ".csv"), "at most 255 bytes"),
        pytest.param(lambda d: Path("/proc/version.csv"), "takes no new file", marks=LINUX),
        (lambda d: d / "missing" / "r.csv", "existing folder"),
        (lambda d: d, "not a directory"),
        pytest.param(lambda d: Path("/dev/null"), "regular file", marks=POSIX),
        (lambda d: Path(""), "name a file"),
    ],
)
def test_output_paths_are_checked_with_a_probe(tmp_path, path, words) -> None:
    with pytest.raises(ValueError, match=words):
        check_writable(path(tmp_path), "out")
    assert sorted(tmp_path.iterdir()) == []  # the probe is gone


def test_a_writable_path_passes_and_leaves_nothing(tmp_path) -> None:
    check_writable(tmp_path / "r.csv", "out")
    assert list(tmp_path.iterdir()) == []


_COUNTER = """
import sys
from pathlib import Path
from evapcool.fileio import atomic_write_text, locked
path = Path(sys.argv[1])
for _ in range(200):
    with locked(path):
        n = int(path.read_text()) if path.exists() else 0
        atomic_write_text(path, str(n + 1))
"""


def test_the_lock_serialises_two_processes(tmp_path) -> None:
    path = tmp_path / "count.txt"
    procs = [subprocess.Popen([sys.executable, "-c", _COUNTER, str(path)]) for _ in range(2)]
    assert [p.wait(timeout=120) for p in procs] == [0, 0]
    assert path.read_text() == "400"  # read-modify-write under the lock loses nothing


def test_a_held_lock_times_out(tmp_path) -> None:
    path = tmp_path / "t.json"
    with locked(path), pytest.raises(LockTimeoutError), locked(path, timeout=0.05):
        pass
    with locked(path):  # released again
        pass


def test_the_lock_serialises_threads_of_one_process(tmp_path) -> None:
    import threading

    path = tmp_path / "count.txt"

    def add() -> None:
        for _ in range(50):
            with locked(path):
                n = int(path.read_text()) if path.exists() else 0
                time.sleep(0.0005)  # widen the window a lost update needs
                atomic_write_text(path, str(n + 1))

    threads = [threading.Thread(target=add) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert path.read_text() == "200"
