"""What the program is called, its version, where it lives, and how its commands word a message.

One place for each: the package metadata reads the version from here (pyproject.toml), the
folders for scores and settings use APP_NAME, and every command line prints its errors
through `error_line` so they all look alike.
"""

from __future__ import annotations

import platform

#: The one source of the version: pyproject.toml, `evapcool --version`, lab metadata.
__version__ = "0.1.0"
#: The program's name: the command, the per-user folders, the window.
APP_NAME = "evapcool"
HOMEPAGE = "https://evapcool.github.io/evapcool/"
REPOSITORY = "https://github.com/evapcool/evapcool"


def one_line(message: str) -> str:
    """message with line breaks and other control characters escaped: one line on stderr."""
    return "".join(ch if ch.isprintable() or ch == " " else repr(ch)[1:-1] for ch in message)


def error_line(command: str | None, message: str) -> str:
    """'evapcool lab: error: message' (command None: 'evapcool: error: message'), one line."""
    prog = APP_NAME if not command else f"{APP_NAME} {command}"
    return f"{prog}: error: {one_line(message)}"


def note_line(command: str | None, message: str) -> str:
    """'evapcool: note: message': something the user should know, not an error."""
    prog = APP_NAME if not command else f"{APP_NAME} {command}"
    return f"{prog}: note: {message}"


def versions() -> dict[str, str | None]:
    """Versions of Python, evapcool and the numeric libraries (None: not installed).

    Read from the installed packages' metadata (nothing heavy is imported for this).
    """
    from importlib import metadata

    found: dict[str, str | None] = {
        "python": platform.python_version(),
        "evapcool": __version__,
    }
    for dist in ("numpy", "matplotlib", "pygame-ce"):
        try:
            found[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            found[dist] = None
    return found
