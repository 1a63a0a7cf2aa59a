"""Local top-10 high-score table, stored as JSON in the user data folder.

No pygame here: the applet shows `entries` and `notices`; this module only
keeps the table sound. Problems with the file (corrupt, unreadable, folder
read-only, not a regular file) never raise: they become notice strings (also
on stderr when a file is set aside) and the game goes on. Several processes may
share the file (two windows, a shared home folder): every write takes the file's
lock, re-reads the table and merges this session's new results into it.
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
from evapcool.fileio import (
    NotRegularFileError,
    atomic_write_text,
    locked,
    read_user_text,
    set_aside,
    warn,
)
from evapcool.i18n import t
from evapcool.limits import SCORE_SECONDS_MAX, USER_FILE_MAX_BYTES, shown

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
        or not 0.0 <= float(seconds) <= SCORE_SECONDS_MAX
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
        #: Results of this session not yet written (the folder refused them so far).
        self._unsaved: list[Entry] = []
        self.notices: list[str] = []
        self.load()

    # -- reading ----------------------------------------------------------
    @property
    def entries(self) -> list[Entry]:
        """The rows, best first (a copy)."""
        return list(self._entries)

    def load(self) -> None:
        """(Re)read the file. Missing: empty table. Corrupt: set aside, empty table, notice."""
        rows = self._read()
        if rows is not None:  # unreadable: keep the table this session knows
            self._entries = sorted_entries([*rows, *self._unsaved])

    def _read(self) -> list[Entry] | None:
        """The rows on disk ([] if none or set aside); None if the file cannot be read."""
        try:
            text = read_user_text(self.path, USER_FILE_MAX_BYTES)
        except (FileNotFoundError, NotADirectoryError):
            return []  # no table yet; if the folder is unusable, saving will say so
        except NotRegularFileError:
            self.notices.append(t("notice.scores_not_regular", path=self.path))
            return None
        except OSError as exc:
            self.notices.append(t("notice.scores_unreadable", path=self.path, problem=_reason(exc)))
            return None
        except ValueError as exc:  # not UTF-8, or far too large for a score table
            self._set_aside(getattr(exc, "reason", None) or str(exc))
            return []
        try:
            data = json.loads(text)
            if not isinstance(data, dict) or not isinstance(data.get("entries"), list):
                raise ValueError("no 'entries' list")
            return [_entry_from_json(row) for row in data["entries"]]
        except (ValueError, RecursionError) as exc:  # JSONDecodeError is a ValueError
            self._set_aside("nested too deeply" if isinstance(exc, RecursionError) else str(exc))
            return []

    def _set_aside(self, why: str) -> None:
        try:
            moved = set_aside(self.path)
        except OSError as exc:
            text = t("notice.scores_damaged_kept", path=self.path, why=why, problem=_reason(exc))
        else:
            text = t("notice.scores_damaged", why=why, name=moved.name)
        self.notices.append(text)
        warn(text)

    def qualifies(self, score: int, seconds: float) -> bool:
        """Would this result enter the table (so it is worth asking for a name)?

        Re-reads the file first: another window may have filled the table meanwhile.
        """
        self.load()
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

        Under the file's lock the table is re-read and the result merged into it, so
        results stored by other processes meanwhile are kept. The table in memory is
        updated even if saving fails (a notice says so).
        ValueError for a negative or non-integer score or a bad time.
        """
        if isinstance(score, bool) or not isinstance(score, numbers.Integral) or score < 0:
            raise ValueError(f"score must be a whole number >= 0 (got {shown(score)})")
        if (
            isinstance(seconds, bool)
            or not isinstance(seconds, numbers.Real)
            or not 0.0 <= float(seconds) <= SCORE_SECONDS_MAX
        ):
            raise ValueError(
                f"seconds must be a number from 0 to {SCORE_SECONDS_MAX:g} (got {shown(seconds)})"
            )
        when = when or datetime.now()
        # Stored to 0.01 s so the order in memory equals the order after a reload.
        entry = Entry(
            name=clean_name(name) or DEFAULT_NAME,
            score=int(score),
            seconds=round(float(seconds), 2),
            date=when.strftime(DATE_FORMAT),
        )
        self._unsaved.append(entry)
        self._write(merge=True)
        rank = next((i + 1 for i, e in enumerate(self._entries) if e is entry), None)
        if rank is None:
            self._unsaved = [e for e in self._unsaved if e is not entry]
        return rank

    def reset(self) -> bool:
        """Empty the table and save (the UI asks for confirmation first)."""
        self._entries = []
        self._unsaved = []
        return self._write(merge=False)

    def _write(self, merge: bool) -> bool:
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            with locked(self.path):
                if merge:
                    on_disk = self._read()
                    base = self._known_rows() if on_disk is None else on_disk
                    self._entries = sorted_entries([*base, *self._unsaved])
                payload = {
                    "version": FORMAT_VERSION,
                    "entries": [asdict(e) for e in self._entries],
                }
                text = json.dumps(payload, indent=2, ensure_ascii=False) + "\n"
                atomic_write_text(self.path, text)
        except OSError as exc:
            self._entries = sorted_entries([*self._known_rows(), *self._unsaved])
            self.notices.append(
                t("notice.scores_unsaved", path=self.path.parent, problem=_reason(exc))
            )
            return False
        self._unsaved = []
        return True

    def _known_rows(self) -> list[Entry]:
        """The rows in memory that came from the file (not this session's unsaved ones)."""
        return [e for e in self._entries if not any(e is u for u in self._unsaved)]


def _reason(exc: BaseException) -> str:
    """Short cause of an OS error for a notice line."""
    if isinstance(exc, OSError) and exc.strerror:
        return exc.strerror.lower()
    return type(exc).__name__
