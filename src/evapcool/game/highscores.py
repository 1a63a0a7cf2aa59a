"""Local top-10 high-score table, stored as JSON in the user data folder.

No pygame here: the applet shows `entries` and `notices`; this module only
keeps the table sound. Problems with the file (corrupt, unreadable, folder
read-only) never raise: they become notice strings and the game goes on.
"""

from __future__ import annotations

import json
import math
import numbers
import os
from dataclasses import asdict, dataclass
from datetime import datetime
from pathlib import Path

from evapcool.about import APP_NAME
from evapcool.fileio import atomic_write_text, set_aside

FILE_NAME = "highscores.json"
FORMAT_VERSION = 1
MAX_ENTRIES = 10
NAME_MAX = 16
DEFAULT_NAME = "Anonymous"
DATE_FORMAT = "%Y-%m-%d %H:%M:%S"  # fixed width, so string order is time order


@dataclass(frozen=True)
class Entry:
    """One row: who, atoms left, seconds taken, and when (local time, DATE_FORMAT)."""

    name: str
    score: int
    seconds: float
    date: str

    def sort_key(self) -> tuple[int, float, str]:
        # More atoms first; on a tie the faster player; then whoever got there first.
        return (-self.score, self.seconds, self.date)


def default_path() -> Path:
    """The score file in the per-user data folder (platformdirs)."""
    from platformdirs import user_data_dir

    return Path(user_data_dir(APP_NAME, appauthor=False)) / FILE_NAME


def clean_name(raw: str, max_length: int = NAME_MAX) -> str:
    """Printable characters only, runs of whitespace made one space, trimmed to max_length.

    Returns "" when nothing usable is left; `HighScoreTable.add` then uses DEFAULT_NAME.
    """
    kept = "".join(ch if ch.isprintable() else " " for ch in str(raw))
    return " ".join(kept.split())[:max_length].rstrip()


def format_seconds(seconds: float) -> str:
    """Seconds as m:ss.s for the table (e.g. 83.25 -> '1:23.3')."""
    tenths = math.floor(max(0.0, float(seconds)) * 10 + 0.5)  # half up, not half even
    minutes, tenths = divmod(tenths, 600)
    return f"{minutes}:{tenths // 10:02d}.{tenths % 10}"


def sorted_entries(entries: list[Entry], limit: int = MAX_ENTRIES) -> list[Entry]:
    """Table order, cut to the best `limit` rows (stable for exact ties)."""
    return sorted(entries, key=Entry.sort_key)[:limit]


def _entry_from_json(obj: object) -> Entry:
    """Parse one stored row; ValueError if anything about it is off."""
    if not isinstance(obj, dict):
        raise ValueError("row is not an object")
    name, score, seconds, date = (obj.get(k) for k in ("name", "score", "seconds", "date"))
    if not isinstance(name, str) or clean_name(name) != name or not name:
        raise ValueError(f"bad name {name!r}")
    if isinstance(score, bool) or not isinstance(score, int) or score < 0:
        raise ValueError(f"bad score {score!r}")
    if (
        isinstance(seconds, bool)
        or not isinstance(seconds, numbers.Real)
        or not math.isfinite(seconds)
        or seconds < 0
    ):
        raise ValueError(f"bad seconds {seconds!r}")
    if not isinstance(date, str):
        raise ValueError(f"bad date {date!r}")
    datetime.strptime(date, DATE_FORMAT)  # raises ValueError if malformed
    return Entry(name=name, score=score, seconds=float(seconds), date=date)


class HighScoreTable:
    """The top-10 table bound to one file. Construct it to load; `add` and `reset` save.

    `notices` collects human-readable messages for the UI (corrupt file set aside,
    folder not writable, ...); `take_notices()` hands them over once.
    """

    def __init__(self, path: str | os.PathLike[str] | None = None) -> None:
        self.path = Path(path) if path is not None else default_path()
        self._entries: list[Entry] = []
        self.notices: list[str] = []
        self.load()

    # -- reading ----------------------------------------------------------
    @property
    def entries(self) -> list[Entry]:
        """The rows, best first (a copy)."""
        return list(self._entries)

    def load(self) -> None:
        """(Re)read the file. Missing: empty table. Corrupt: set aside, empty table, notice."""
        self._entries = []
        try:
            text = self.path.read_text(encoding="utf-8")
        except (FileNotFoundError, NotADirectoryError):
            return  # no table yet; if the folder is unusable, saving will say so
        except (OSError, UnicodeDecodeError) as exc:
            if isinstance(exc, UnicodeDecodeError):
                self._set_aside(f"not valid UTF-8 ({exc.reason})")
            else:
                self.notices.append(
                    f"High scores could not be read from {self.path} ({_reason(exc)}); "
                    "starting an empty table."
                )
            return
        try:
            data = json.loads(text)
            if not isinstance(data, dict) or not isinstance(data.get("entries"), list):
                raise ValueError("no 'entries' list")
            rows = [_entry_from_json(row) for row in data["entries"]]
        except ValueError as exc:  # json.JSONDecodeError is a ValueError
            self._set_aside(str(exc))
            return
        self._entries = sorted_entries(rows)

    def _set_aside(self, why: str) -> None:
        try:
            moved = set_aside(self.path)
        except OSError as exc:
            self.notices.append(
                f"The high-score file {self.path} is damaged ({why}) and could not be "
                f"renamed ({_reason(exc)}); starting an empty table."
            )
            return
        self.notices.append(
            f"The high-score file was damaged ({why}); it was kept as {moved.name} "
            "and a new table was started."
        )

    def qualifies(self, score: int, seconds: float) -> bool:
        """Would this result enter the table (so it is worth asking for a name)?"""
        if len(self._entries) < MAX_ENTRIES:
            return True
        probe = Entry("", int(score), float(seconds), "9999-12-31 23:59:59")
        return probe.sort_key() < self._entries[-1].sort_key()

    def take_notices(self) -> list[str]:
        """Return the pending notices and clear them."""
        out, self.notices = self.notices, []
        return out

    # -- writing ----------------------------------------------------------
    def add(
        self, name: str, score: int, seconds: float, when: datetime | None = None
    ) -> int | None:
        """Store a result; returns its 1-based rank, or None if it did not make the top 10.

        The table in memory is updated even if saving fails (a notice says so).
        ValueError for a negative or non-integer score or a bad time.
        """
        if isinstance(score, bool) or not isinstance(score, numbers.Integral) or score < 0:
            raise ValueError(f"score must be a whole number >= 0 (got {score!r})")
        if (
            isinstance(seconds, bool)
            or not isinstance(seconds, numbers.Real)
            or not math.isfinite(seconds)
            or seconds < 0
        ):
            raise ValueError(f"seconds must be a finite number >= 0 (got {seconds!r})")
        when = when or datetime.now()
        # Stored to 0.01 s so the order in memory equals the order after a reload.
        entry = Entry(
            name=clean_name(name) or DEFAULT_NAME,
            score=int(score),
            seconds=round(float(seconds), 2),
            date=when.strftime(DATE_FORMAT),
        )
        table = sorted_entries([*self._entries, entry])
        rank = next((i + 1 for i, e in enumerate(table) if e is entry), None)
        if rank is not None:
            self._entries = table
            self.save()
        return rank

    def reset(self) -> bool:
        """Empty the table and save (the UI asks for confirmation first)."""
        self._entries = []
        return self.save()

    def save(self) -> bool:
        """Write the table atomically; False (and a notice) if the folder is not writable."""
        payload = {"version": FORMAT_VERSION, "entries": [asdict(e) for e in self._entries]}
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            atomic_write_text(self.path, json.dumps(payload, indent=2, ensure_ascii=False) + "\n")
        except OSError as exc:
            self.notices.append(
                f"High scores could not be saved to {self.path.parent} ({_reason(exc)}); "
                "they are kept for this session only."
            )
            return False
        return True


def _reason(exc: BaseException) -> str:
    """Short cause of an OS error for a notice line."""
    if isinstance(exc, OSError) and exc.strerror:
        return exc.strerror.lower()
    return type(exc).__name__
