"""The class data's SQL, common to SQLite (storage/sqlite.py) and PostgreSQL (pgstore.py):
one store made of its aggregates, one committed transaction per call."""

from __future__ import annotations

from evapcool.classroom.storage.challenges import ChallengesStore
from evapcool.classroom.storage.classes import ClassesStore
from evapcool.classroom.storage.entries import EntriesStore
from evapcool.classroom.storage.players import PlayersStore


class SqlStore(ClassesStore, ChallengesStore, PlayersStore, EntriesStore):
    """The class data, one committed transaction per call; the SQL is common to both
    databases (subclasses give the connection, the transaction and the row locks)."""
