"""Exports of a round for the lecturer (token as Bearer or ?token=): CSV (every game
accepted, with its path's summary and the archetypes it is) and JSON (every entry with its
path), of the current challenge or a past one (?challenge=)."""

from __future__ import annotations

import csv
import io
import json
from typing import Any

from starlette.requests import Request
from starlette.responses import JSONResponse, Response

from evapcool.classroom.challenge import challenge_doc
from evapcool.classroom.debrief import archetypes
from evapcool.classroom.errors import RefusedError
from evapcool.classroom.hub import Hub
from evapcool.classroom.rooms import DEFAULT_ROOM
from evapcool.classroom.views.common import _challenge_asked, lecturer
from evapcool.classroom.views.debrief import _law

#: The columns the CSV adds to the store's: the archetypes a game is (space-separated),
#: and its path's summary (won, points kept, atoms and temperature at its first and last).
PATH_COLUMNS = ("archetype", "won", "path_points", "start_atoms", "end_atoms", "end_temperature")


async def _round(request: Request) -> tuple[Hub, dict[str, Any], dict[str, Any]]:
    hub, room = await lecturer(request, query=True)
    row = await _challenge_asked(request, hub, room)
    if row is None:
        raise RefusedError(404, "challenge", "class.error.no_challenge")
    return hub, room, row


def _file_name(room: dict[str, Any], row: dict[str, Any], ext: str) -> str:
    if room["id"] == DEFAULT_ROOM:
        return f"evapcool-class-{row['id']}.{ext}"
    return f"evapcool-class-{room['code']}-{row['id']}.{ext}"


def _headers(name: str) -> dict[str, str]:
    return {"Content-Disposition": f'attachment; filename="{name}"', "Cache-Control": "no-store"}


async def _paths_and_kinds(
    hub: Hub, row: dict[str, Any]
) -> tuple[dict[int, Any], dict[int, list[str]]]:
    """Every entry's path (parsed) and the archetypes each entry is."""
    stored = await hub.db(hub.store.entry_paths, row["id"])
    paths = {e: json.loads(p) if p else None for e, p in stored.items()}
    games = [
        {**g, "path": paths.get(g["entry"])}  # type: ignore[call-overload]
        for g in await hub.db(hub.store.best_games, row["id"])
    ]
    kinds: dict[int, list[str]] = {}
    for kind, entry in archetypes(games, await _law(hub, row), bool(row.get("lost"))).items():
        if entry is not None:
            kinds.setdefault(entry, []).append(kind)
    return paths, kinds


def path_summary(path: dict[str, Any] | None) -> list[object]:
    """won, points, first and last atoms, last temperature ('' without a stored path)."""
    if not path or not path.get("n"):
        return ["", "", "", "", ""]
    won = "yes" if path["won"] else "no"
    return [won, len(path["n"]), path["n"][0], path["n"][-1], path["t"][-1]]


async def export_csv(request: Request) -> Response:
    """A round's games as CSV: the store's columns, then PATH_COLUMNS."""
    hub, room, row = await _round(request)
    paths, kinds = await _paths_and_kinds(hub, row)
    lines = list(csv.reader(io.StringIO(await hub.db(hub.store.results_csv, row["id"]))))
    entry_col = lines[0].index("entry")
    out = io.StringIO()
    writer = csv.writer(out)
    writer.writerow([*lines[0], *PATH_COLUMNS])
    for line in lines[1:]:
        entry = int(line[entry_col])
        writer.writerow([*line, " ".join(kinds.get(entry, [])), *path_summary(paths.get(entry))])
    return Response(
        out.getvalue(),
        media_type="text/csv; charset=utf-8",
        headers=_headers(_file_name(room, row, "csv")),
    )


async def export_json(request: Request) -> Response:
    """A round as JSON: the challenge, and every entry (hidden ones marked) with its place,
    the archetypes it is and its path."""
    hub, room, row = await _round(request)
    paths, kinds = await _paths_and_kinds(hub, row)
    entries = []
    for e in await hub.db(hub.store.entries, row["id"]):
        entry = e["entry"]
        assert isinstance(entry, int)
        entries.append({**e, "archetypes": kinds.get(entry, []), "path": paths.get(entry)})
    doc = {"challenge": challenge_doc(row), "class": room["code"], "entries": entries}
    return JSONResponse(doc, headers=_headers(_file_name(room, row, "json")))
