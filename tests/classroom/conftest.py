"""The class server's fixture: a fresh `evapcool class` on a new SQLite file."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from classhelp import Server, start_server


@pytest.fixture
def server(tmp_path: Path) -> Iterator[Server]:
    """A fresh server on a new SQLite file, stopped after the test."""
    running = start_server(tmp_path / "class.sqlite")
    yield running
    running.stop()
