"""Exports: a challenge's games as CSV for the lecturer (token as Bearer or ?token=)."""

from __future__ import annotations

from starlette.requests import Request
from starlette.responses import Response

from evapcool.classroom.errors import RefusedError
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.views.common import _challenge_asked, lecturer


async def export_csv(request: Request) -> Response:
    """The current (or ?challenge=) challenge's games as CSV (token as Bearer or ?token=)."""
    hub, room = await lecturer(request, query=True)
    row = await _challenge_asked(request, hub, room)
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    text = await hub.db(hub.store.results_csv, row["id"])
    name = f"evapcool-class-{row['id']}.csv"
    if room["id"] != DEFAULT_ROOM:
        name = f"evapcool-class-{room['code']}-{row['id']}.csv"
    return Response(
        text,
        media_type="text/csv; charset=utf-8",
        headers={
            "Content-Disposition": f'attachment; filename="{name}"',
            "Cache-Control": "no-store",
        },
    )
