"""Files the program writes and reads back.

- Atomic replacement: readers see the old file or the new one, never a torn one; a
  temporary left by a killed write is removed by the next write to the same place.
- A cross-platform lock (fcntl on POSIX, msvcrt on Windows) for files that several
  processes update: take it, re-read, merge, write.
- User files are read without ever blocking (a FIFO is refused, not opened for a
  reader that never comes) and with a size cap; a damaged file is set aside.
- Output paths are checked before a long run, by creating and removing a probe.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from pathlib import Path

from evapcool.limits import ParameterError

#: Temporary files are named '.<name>.evapcool-<random>.tmp' beside their target.
_TMP_TAG = ".evapcool-"
_TMP_SUFFIX = ".tmp"
#: A temporary this old whose writer holds no lock on it is a dead write's leftover.
STALE_SECONDS = 1.0
#: How long `locked` waits for another process before giving up (seconds).
LOCK_TIMEOUT = 10.0


class NotRegularFileError(OSError):
    """The path names a FIFO, a device, a socket or a folder, not a file."""


class FileTooLargeError(ValueError):
    """A user file larger than its cap: damaged, or not what it claims to be."""


class LockTimeoutError(OSError):
    """Another process held the lock for longer than the timeout."""


# -- names ------------------------------------------------------------------------------
def _name_max(folder: Path) -> int:
    try:
        return int(os.pathconf(folder, "PC_NAME_MAX"))
    except (OSError, ValueError, AttributeError):
        return 255


def _tmp_prefix(target: Path) -> str:
    """'.<name>.evapcool-', the name cut so a temporary's name still fits the folder."""
    room = _name_max(target.parent) - len(_TMP_TAG) - len(_TMP_SUFFIX) - 12
    name = target.name.encode("utf-8", "surrogateescape")[: max(room - 1, 1)]
    return "." + name.decode("utf-8", "ignore") + _TMP_TAG


# -- locks ----------------------------------------------------------------------------------
if os.name == "nt":  # pragma: no cover - exercised on Windows only
    import msvcrt

    def _try_lock(fd: int) -> bool:
        os.lseek(fd, 0, os.SEEK_SET)
        try:
            msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)
        except OSError:
            return False
        return True

    def _unlock(fd: int) -> None:
        os.lseek(fd, 0, os.SEEK_SET)
        msvcrt.locking(fd, msvcrt.LK_UNLCK, 1)

else:
    import fcntl

    def _try_lock(fd: int) -> bool:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            if exc.errno in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
                return False
            raise
        return True

    def _unlock(fd: int) -> None:
        fcntl.flock(fd, fcntl.LOCK_UN)


def lock_path(path: str | os.PathLike[str]) -> Path:
    """The lock file of path: '.<name>.lock' beside it (kept: removing it would race)."""
    p = Path(path)
    return p.with_name(f".{p.name}.lock")


#: One thread lock per lock file: where the OS lock is per process (POSIX record locks,
#: which Linux uses for flock on NFS), threads of one process still take turns.
_THREAD_LOCKS: dict[str, threading.Lock] = {}
_THREAD_LOCKS_GUARD = threading.Lock()


@contextlib.contextmanager
def locked(path: str | os.PathLike[str], timeout: float = LOCK_TIMEOUT) -> Iterator[None]:
    """Hold an exclusive OS lock on path's lock file (other processes and threads wait).

    A lock held by a process that dies is released by the OS. LockTimeoutError after
    timeout seconds; OSError if the folder cannot hold the lock file.
    """
    lp = lock_path(path)
    with _THREAD_LOCKS_GUARD:
        mine = _THREAD_LOCKS.setdefault(os.path.abspath(lp), threading.Lock())
    deadline = time.monotonic() + timeout
    if not mine.acquire(timeout=max(timeout, 0.0)):
        raise LockTimeoutError(f"{path} is locked by another thread ({timeout:g} s)")
    try:
        with _os_lock(lp, path, deadline, timeout):
            yield
    finally:
        mine.release()


@contextlib.contextmanager
def _os_lock(lp: Path, path: object, deadline: float, timeout: float) -> Iterator[None]:
    fd = os.open(lp, os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0), 0o666)
    try:
        pause = 0.001
        while not _try_lock(fd):
            if time.monotonic() > deadline:
                raise LockTimeoutError(f"{path} is locked by another process ({timeout:g} s)")
            time.sleep(pause)
            pause = min(pause * 2, 0.05)
        try:
            yield
        finally:
            _unlock(fd)
    finally:
        os.close(fd)


# -- atomic writes ------------------------------------------------------------------------------
def remove_stale_temporaries(target: str | os.PathLike[str]) -> list[Path]:
    """Remove temporaries of target left by killed writes; returns those removed.

    Only names this module makes; only if older than STALE_SECONDS and not locked by a
    live writer (on Windows an open file cannot be removed at all).
    """
    t = Path(target)
    prefix = _tmp_prefix(t)
    removed = []
    try:
        entries = list(os.scandir(t.parent if str(t.parent) else "."))
    except OSError:
        return removed
    now = time.time()
    for entry in entries:
        if not (entry.name.startswith(prefix) and entry.name.endswith(_TMP_SUFFIX)):
            continue
        try:
            info = entry.stat(follow_symlinks=False)
            if not stat.S_ISREG(info.st_mode) or now - info.st_mtime < STALE_SECONDS:
                continue
            if _writer_alive(entry.path):
                continue
            os.unlink(entry.path)
            removed.append(Path(entry.path))
        except OSError:
            continue
    return removed


def _writer_alive(path: str) -> bool:
    if os.name == "nt":  # pragma: no cover - a live writer's file cannot be removed there
        return False
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0))
    try:
        if not _try_lock(fd):
            return True
        _unlock(fd)
        return False
    finally:
        os.close(fd)


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> None:
    """Write data to path so readers see the old file or the new one, never a torn one."""
    target = Path(path)
    with contextlib.suppress(FileNotFoundError):
        if not stat.S_ISREG(os.stat(target).st_mode):  # a FIFO, a device, a folder: leave it
            raise NotRegularFileError(errno.EINVAL, "not a regular file", str(target))
    remove_stale_temporaries(target)
    fd, tmp = tempfile.mkstemp(
        prefix=_tmp_prefix(target), suffix=_TMP_SUFFIX, dir=target.parent or None
    )
    try:
        if os.name != "nt":
            _try_lock(fd)  # marks the temporary as in use (remove_stale_temporaries)
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        # mkstemp makes a private file; give it the mode a plain open() would have.
        os.chmod(tmp, _mode_for(target))
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _mode_for(target: Path) -> int:
    """The existing file's permissions, else 0o666 less the umask."""
    try:
        return target.stat().st_mode & 0o777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def atomic_write_text(path: str | os.PathLike[str], text: str) -> None:
    """Text (UTF-8) version of atomic_write_bytes."""
    atomic_write_bytes(path, text.encode("utf-8"))


# -- reading user files ---------------------------------------------------------------------------
def read_user_bytes(path: str | os.PathLike[str], max_bytes: int) -> bytes:
    """The whole file, never blocking: NotRegularFileError for a FIFO, device or folder,
    FileTooLargeError above max_bytes, FileNotFoundError and other OSErrors as they come.
    """
    p = Path(path)
    if not stat.S_ISREG(os.stat(p).st_mode):
        raise NotRegularFileError(errno.EINVAL, "not a regular file", str(p))
    # O_NONBLOCK: if a FIFO took the file's place since the stat, open does not wait.
    fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise NotRegularFileError(errno.EINVAL, "not a regular file", str(p))
        chunks = []
        size = 0
        while size <= max_bytes:
            chunk = os.read(fd, min(1 << 20, max_bytes + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    finally:
        os.close(fd)
    if size > max_bytes:
        raise FileTooLargeError(f"larger than {max_bytes} bytes")
    return b"".join(chunks)


def read_user_text(path: str | os.PathLike[str], max_bytes: int) -> str:
    """read_user_bytes decoded as UTF-8 (UnicodeDecodeError, a ValueError, if it is not)."""
    return read_user_bytes(path, max_bytes).decode("utf-8")


def set_aside(path: str | os.PathLike[str]) -> Path:
    """Rename a corrupt file to '<name>.corrupt-<timestamp>' beside it; returns the new path."""
    src = Path(path)
    stamp = time.strftime("%Y%m%d-%H%M%S")
    dst = src.with_name(f"{src.name}.corrupt-{stamp}")
    n = 1
    while dst.exists():
        dst = src.with_name(f"{src.name}.corrupt-{stamp}-{n}")
        n += 1
    os.replace(src, dst)
    return dst


def warn(text: str) -> None:
    """A notice on stderr too, so that headless runs show it (issue 18)."""
    with contextlib.suppress(OSError, ValueError):
        print(f"evapcool: {text}", file=sys.stderr, flush=True)


# -- output paths ---------------------------------------------------------------------------
def check_writable(path: str | os.PathLike[str], name: str) -> None:
    """ValueError naming the option unless a file can be written at path (before a run).

    Refuses a name too long for the file system, a missing folder, a directory or a
    non-regular file at path, and any folder that will not take a new file (tried by
    creating and removing a probe there: permissions, read-only or virtual file systems).
    """
    p = Path(path)
    where = f"(got {str(p)!r})"
    folder = p.parent if str(p.parent) else Path(".")
    if not p.name or "\x00" in str(p):
        raise ParameterError(name, f"must name a file {where}")
    if len(p.name.encode("utf-8", "surrogateescape")) > _name_max(folder):
        raise ParameterError(
            name, f"must be a file name of at most {_name_max(folder)} bytes {where}"
        )
    folder_info = _stat(folder, name, where)
    if folder_info is None or not stat.S_ISDIR(folder_info.st_mode):
        raise ParameterError(name, f"must be in an existing folder {where}")
    info = _stat(p, name, where)
    if info is not None and stat.S_ISDIR(info.st_mode):
        raise ParameterError(name, f"must be a file path, not a directory {where}")
    if info is not None and not stat.S_ISREG(info.st_mode):
        raise ParameterError(name, f"must be a regular file (this is a device or a pipe) {where}")
    try:
        fd, probe = tempfile.mkstemp(prefix=_tmp_prefix(p), suffix=_TMP_SUFFIX, dir=folder)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        reason = exc.strerror.lower() if exc.strerror else type(exc).__name__
        raise ParameterError(
            name, f"cannot be written: {folder} takes no new file ({reason}) {where}"
        ) from None


def _stat(path: Path, name: str, where: str) -> os.stat_result | None:
    """os.stat(path), None if nothing is there; ValueError for a path the system refuses
    (a folder name too long, a file where a folder should be, no permission)."""
    try:
        return os.stat(path)
    except FileNotFoundError:
        return None
    except OSError as exc:
        if exc.errno == errno.ENOTDIR:
            return None
        reason = exc.strerror.lower() if exc.strerror else type(exc).__name__
        raise ParameterError(name, f"cannot be written there ({reason}) {where}") from None
