"""The class server's fixtures: a fresh `evapcool class` on a new SQLite file, and on a new
database of a real PostgreSQL (started once per session in a temporary folder)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from classhelp import Server, start_server
from pghelp import Postgres, running_postgres

STORES = ["sqlite", "postgresql"]


@pytest.fixture(scope="session")
def postgres() -> Iterator[Postgres]:
    """A PostgreSQL for the session, stopped afterwards (skipped if not installed)."""
    with running_postgres("evapcool-pg-") as running:
        yield running


@pytest.fixture(params=STORES)
def store_at(request: pytest.FixtureRequest, tmp_path: Path) -> Path | str:
    """Where a new store is: a SQLite file, or a new PostgreSQL database's URL."""
    if request.param == "sqlite":
        return tmp_path / "class.sqlite"
    postgres: Postgres = request.getfixturevalue("postgres")
    return postgres.new_database()


@pytest.fixture
def server(store_at: Path | str) -> Iterator[Server]:
    """A fresh server on a new store (each test runs on SQLite and on PostgreSQL)."""
    running = start_server(store_at)
    yield running
    running.stop()
