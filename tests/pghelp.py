"""A real PostgreSQL for the tests: initdb in a temporary folder, a Unix socket there (no
TCP), started and stopped with pg_ctl; one new database per test."""

from __future__ import annotations

import glob
import itertools
import os
import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

#: Why PostgreSQL tests are skipped (only when its programs are not installed).
MISSING = "PostgreSQL's initdb and pg_ctl are not installed (Debian: apt-get install postgresql)"


def pg_bin() -> Path | None:
    """The folder of initdb and pg_ctl (Debian's versioned one, else PATH), or None."""
    found = sorted(glob.glob("/usr/lib/postgresql/*/bin/initdb"))
    if found:
        return Path(found[-1]).parent
    initdb = shutil.which("initdb")
    return Path(initdb).parent if initdb and shutil.which("pg_ctl") else None


def _as_owner(cmd: list[str]) -> list[str]:
    """The command as the `postgres` user when run by root (PostgreSQL refuses root)."""
    return ["runuser", "-u", "postgres", "--", *cmd] if os.geteuid() == 0 else cmd


@dataclass
class Postgres:
    """A running PostgreSQL listening on a socket in `folder`."""

    folder: Path
    bin: Path
    user: str
    names: itertools.count[int] = field(default_factory=itertools.count)

    def url(self, database: str = "postgres") -> str:
        return f"postgresql://{self.user}@/{database}?host={self.folder}"

    def new_database(self) -> str:
        """A new empty database's URL."""
        import psycopg

        name = f"t{os.getpid()}_{next(self.names)}"
        with psycopg.connect(self.url(), autocommit=True) as conn:
            conn.execute(f"CREATE DATABASE {name}")
        return self.url(name)

    def stop(self) -> None:
        cmd = [str(self.bin / "pg_ctl"), "-D", str(self.folder / "data"), "-m", "fast", "-w"]
        subprocess.run(_as_owner([*cmd, "stop"]), capture_output=True, check=False, timeout=60)

    def start(self) -> None:
        """Start it (again): on its socket only, no TCP; returns once it takes connections."""
        options = f"-k {self.folder} -c listen_addresses='' -c max_connections=200"
        data, log = str(self.folder / "data"), str(self.folder / "log")
        cmd = [str(self.bin / "pg_ctl"), "-D", data, "-l", log, "-o", options, "-w", "start"]
        subprocess.run(_as_owner(cmd), capture_output=True, check=True, timeout=120)


def start_postgres(folder: Path) -> Postgres:
    """initdb and start PostgreSQL in `folder` (trust on its socket only; no TCP). Run by
    root, the folder is given to the postgres user (its parents must let it through)."""
    binaries = pg_bin()
    assert binaries is not None, MISSING
    user = "postgres" if os.geteuid() == 0 else os.environ.get("USER", "postgres")
    folder.mkdir(parents=True, exist_ok=True)
    if os.geteuid() == 0:
        shutil.chown(folder, "postgres")
    data = folder / "data"
    run = {"capture_output": True, "check": True, "timeout": 120}
    subprocess.run(
        _as_owner([str(binaries / "initdb"), "-D", str(data), "-A", "trust", "-U", user]), **run
    )
    running = Postgres(folder, binaries, user)
    running.start()
    return running


@contextmanager
def running_postgres(prefix: str) -> Iterator[Postgres]:
    """A PostgreSQL in a new temporary folder, stopped afterwards; the test is skipped where
    PostgreSQL or psycopg is not installed."""
    import pytest

    if pg_bin() is None:
        pytest.skip(MISSING)
    extra = "the department extra: pip install 'evapcool[department]'"
    pytest.importorskip("psycopg", reason=extra)
    with tempfile.TemporaryDirectory(prefix=prefix) as folder:
        running = start_postgres(Path(folder))
        try:
            yield running
        finally:
            running.stop()
