"""The copy check across the whole server: a game's moves up to its win (verifier.moves_key)
are refused when any verified game from the same start (seed and settings; any class, any
challenge) already has them, except the same student's in the same challenge (a resend).
Index-backed: entry(moves), then each hit's challenge by its key."""

from __future__ import annotations

from evapcool.classroom.storage.base import Query

#: The entries with these moves from a challenge of the same start, other than the
#: sender's own in this challenge.
COPY_QUERY = (
    "SELECT 1 FROM entry e JOIN challenge c ON c.id = e.challenge "
    "JOIN challenge mine ON mine.id = ? "
    "WHERE e.moves = ? AND c.seed = mine.seed AND c.settings = mine.settings "
    "AND NOT (e.challenge = mine.id AND e.player = ?) LIMIT 1"
)


def is_copy(q: Query, challenge: int, token: str, moves: str) -> bool:
    """Whether another verified game from the same start as `challenge` has these moves."""
    return q(COPY_QUERY, (challenge, moves, token)).fetchone() is not None
