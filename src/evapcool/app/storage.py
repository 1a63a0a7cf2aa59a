"""Where the applet keeps its files: the user folders, or folders named for this run.

An explicit folder (App/CLI argument) wins over the environment variable, which
wins over the platformdirs default; tests and classroom setups point both
somewhere of their own so they never touch a user's real files.
"""

from __future__ import annotations

import os
from pathlib import Path

from evapcool.app.words import t
from evapcool.game import highscores, settings

DATA_ENV = "EVAPCOOL_DATA_DIR"
CONFIG_ENV = "EVAPCOOL_CONFIG_DIR"

PathLike = str | os.PathLike[str]


def _folder(explicit: PathLike | None, env: str) -> Path | None:
    if explicit is not None:
        return Path(explicit)
    value = os.environ.get(env)
    return Path(value) if value else None


def scores_path(data_dir: PathLike | None = None) -> Path:
    """The high-score file: in data_dir, else $EVAPCOOL_DATA_DIR, else the user data folder."""
    folder = _folder(data_dir, DATA_ENV)
    return folder / highscores.FILE_NAME if folder else highscores.default_path()


def settings_path(config_dir: PathLike | None = None) -> Path:
    """The settings file: in config_dir, else $EVAPCOOL_CONFIG_DIR, else the user config folder."""
    folder = _folder(config_dir, CONFIG_ENV)
    return folder / settings.FILE_NAME if folder else settings.default_path()


def folder_problem(path: Path) -> str | None:
    """Why the folder of path cannot hold files (checked at start), or None if it looks fine.

    Only what can be seen without writing: something that is not a folder in the
    way, or a folder we may not write to. Saving still reports anything else.
    """
    for parent in (path.parent, *path.parent.parents):
        try:
            os.stat(parent)
        except FileNotFoundError:
            continue
        except OSError as exc:  # a name too long, a file in the way, ...
            return t("storage.cannot_use", path=parent, problem=exc.strerror or exc)
        if parent.exists():
            if not parent.is_dir():
                return t("storage.is_file", path=parent)
            if not os.access(parent, os.W_OK | os.X_OK):
                return t("storage.read_only", path=parent)
            return None
    return None
