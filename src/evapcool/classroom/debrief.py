"""The debrief after a challenge (issue 36): every student's best game's path, the
archetypes a lecturer picks from, and two games' paths frame by frame for the projector.

Pure functions of the store's rows: the server decides who may see what (the lecturer
while the challenge is open, everyone once it is closed) and whether names are shown.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

from evapcool.game.path import game_path
from evapcool.game.replay import Settings, decode

#: The archetypes, in the order the lecturer's page lists them.
ARCHETYPES = ("best", "fastest", "most_lost", "never_won")


@dataclass(frozen=True)
class Law:
    """The challenge's critical line Tc(N) = tc0 (N / n0)^exponent and its start's T0."""

    n0: int
    tc0: float
    exponent: float
    t0: float

    def to_json(self) -> dict[str, Any]:
        return {"n0": self.n0, "tc0": self.tc0, "exponent": self.exponent, "t0": self.t0}


def law_of(settings: dict[str, Any], seed: int) -> Law:
    """The critical line of a challenge, from its start (every game of it starts alike)."""
    from evapcool.game.rules import Game

    s = Settings(**settings)
    sim = Game(s.game_config(seed)).sim
    return Law(s.n_atoms, float(sim.critical_temperature), s.tc_exponent, sim.temperature)


def _won(game: dict[str, Any]) -> bool:
    path = game.get("path")
    return bool(path["won"]) if path else int(game["score"]) > 0


def _closeness(game: dict[str, Any], law: Law) -> float:
    """How near a game that never won ended to the line: T / Tc(N) at its last point."""
    path = game.get("path")
    if not path or not path["n"]:
        return float("inf")
    n, t = path["n"][-1], path["t"][-1]
    return float(t / (law.tc0 * (n / law.n0) ** law.exponent))


def archetypes(games: list[dict[str, Any]], law: Law, lost: bool) -> dict[str, int | None]:
    """Entry ids of the best game, the fastest win, the win that lost the most atoms, and
    (lost games taken) the game that never won ending nearest the line; None where none."""
    won = [g for g in games if _won(g)]
    never = [g for g in games if not _won(g)] if lost else []

    def pick(rows: list[dict[str, Any]], key: Any) -> int | None:
        return int(min(rows, key=key)["entry"]) if rows else None

    return {
        "best": pick(won, lambda g: (g["rank"], g["entry"])),
        "fastest": pick(won, lambda g: (g["frames"], -g["score"], g["entry"])),
        "most_lost": pick(won, lambda g: (g["score"], -g["frames"], g["entry"])),
        "never_won": pick(never, lambda g: (_closeness(g, law), g["entry"])),
    }


def debrief_doc(
    challenge: dict[str, Any],
    rows: list[dict[str, Any]],
    law: Law,
    anonymous: bool,
    viewer: str | None = None,
) -> dict[str, Any]:
    """The debrief document (docs/class.md): the law, one game a student (best first) with
    its path, the archetypes, and `you` (the viewer's entry and place, if a student)."""
    games = []
    you = None
    for row in rows:
        path = json.loads(row["path"]) if row.get("path") else None
        game = {
            "entry": row["entry"],
            "name": None if anonymous else row["name"],
            "rank": row["rank"],
            "score": row["score"],
            "frames": row["frames"],
            "path": path,
        }
        game["won"] = _won(game)
        games.append(game)
        if viewer is not None and row["player"] == viewer:
            you = {"entry": row["entry"], "rank": row["rank"]}
    return {
        "challenge": challenge["id"],
        "anonymous": anonymous,
        "law": law.to_json(),
        "max_score": law.n0,
        "lost": bool(challenge.get("lost")),
        "games": games,
        "archetypes": archetypes(games, law, bool(challenge.get("lost"))),
        "you": you,
    }


def every_frame(code: str) -> dict[str, Any]:
    """A game's path at every whole frame (two games played side by side, in step)."""
    return game_path(decode(code), stride=1).to_json()


@dataclass
class Showing:
    """What the lecturer set the debrief to show: names or not, a game picked, a pair."""

    anonymous: bool = False
    pick: int | None = None
    pair: tuple[int, int] | None = None

    def to_json(self) -> dict[str, Any]:
        pair = list(self.pair) if self.pair else None
        return {"anonymous": self.anonymous, "pick": self.pick, "pair": pair}


def without_names(board: dict[str, Any]) -> dict[str, Any]:
    """The leaderboard document with no student's name (the debrief's anonymous mode)."""
    entries = [{**e, "name": None} for e in board.get("entries", [])]
    replay = board.get("replay")
    if replay is not None:
        replay = {**replay, "name": None}
    return {**board, "entries": entries, "replay": replay}
