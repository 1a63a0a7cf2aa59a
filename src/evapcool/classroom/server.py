"""`evapcool class`'s web server (Starlette): classes, challenges, students, verified games.

Games are replayed in worker processes, shared fairly between addresses (fairqueue); a
submission is answered 200 only after its entry is committed to the store (SQLite, or
PostgreSQL for a department). SQLite's calls run one at a time on a thread of their own,
PostgreSQL's on a few threads with a pool of connections. Tokens are kept only as digests.

A single-class server serves its one class at /, /projector, /lecturer and /api/...; every
class of a department's server has the same under /c/{code}/. With PostgreSQL several
processes serve one department: a changed board is announced through the database
(LISTEN/NOTIFY) and each process sends it to its own streams.

The server is built of rooms, one module per resource (docs/architecture.md): hub.py (the
state, limits, workers), tokens.py (digests and keys), boards.py (what the pages show),
and under views/ play, board, lecturer, debrief, exports and department, with common and
answers; app.py routes them. This module keeps their public names importable.
"""

from __future__ import annotations

from evapcool.classroom.app import CLASS_ROUTES
from evapcool.classroom.boards import challenge_info, showing_of
from evapcool.classroom.hub import (
    BUCKET_SWEEP,
    CLIENT_RATE,
    JOIN_RATE,
    SHARED_DB_THREADS,
    STORE_RETRY,
    SUBMIT_RATE,
    WINDOW_CHECK,
    Hub,
    Limits,
    Listener,
    T,
    open_store,
)
from evapcool.classroom.tokens import (
    ADMIN_SECRET,
    LECTURER_SECRET,
    PROJECTOR_SECRET,
    digest,
    matches_digest,
    new_lecturer_token,
    projector_key,
    room_projector_key,
)
from evapcool.classroom.views.answers import DATA_POLICY, SAFE_HEADERS
from evapcool.classroom.views.board import KEEP_ALIVE, leaderboard, projector, stream
from evapcool.classroom.views.common import (
    address,
    bearer_token,
    debrief_state,
    guard,
    hub_of,
    join_url_of,
    keyed,
    lecturer,
    moves_summary,
    room_of,
)
from evapcool.classroom.views.debrief import debrief, debrief_pair, set_debrief
from evapcool.classroom.views.exports import export_csv
from evapcool.classroom.views.lecturer import (
    challenges,
    close_challenge,
    entries,
    hide,
    lecturer_page,
    open_challenge,
    rename,
    show,
)
from evapcool.classroom.views.play import game, get_challenge, join, me, submit

__all__ = [
    "ADMIN_SECRET",
    "BUCKET_SWEEP",
    "CLASS_ROUTES",
    "CLIENT_RATE",
    "DATA_POLICY",
    "JOIN_RATE",
    "KEEP_ALIVE",
    "LECTURER_SECRET",
    "PROJECTOR_SECRET",
    "SAFE_HEADERS",
    "SHARED_DB_THREADS",
    "STORE_RETRY",
    "SUBMIT_RATE",
    "WINDOW_CHECK",
    "Hub",
    "Limits",
    "Listener",
    "T",
    "address",
    "bearer_token",
    "challenge_info",
    "challenges",
    "close_challenge",
    "debrief",
    "debrief_pair",
    "debrief_state",
    "digest",
    "entries",
    "export_csv",
    "game",
    "get_challenge",
    "guard",
    "hide",
    "hub_of",
    "join",
    "join_url_of",
    "keyed",
    "leaderboard",
    "lecturer",
    "lecturer_page",
    "matches_digest",
    "me",
    "moves_summary",
    "new_lecturer_token",
    "open_challenge",
    "open_store",
    "projector",
    "projector_key",
    "rename",
    "room_of",
    "room_projector_key",
    "set_debrief",
    "show",
    "showing_of",
    "stream",
    "submit",
]
