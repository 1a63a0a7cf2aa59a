"""Optional features and the extra that installs each (pyproject.toml's optional dependencies).

A feature whose extra is missing says so in one line naming what to install, before any
work starts, never with a traceback: `require` raises `MissingExtraError` with that line
and the command line prints it.
"""

from __future__ import annotations

import importlib
import importlib.util
from types import ModuleType

#: import name -> the extra that installs it.
EXTRA_OF = {
    "matplotlib": "lab",
    "pandas": "cluster",
    "pyarrow": "cluster",
    "optuna": "cluster",
    "cmaes": "cluster",
    "dask": "cluster",
    "distributed": "cluster",
    "tqdm": "cluster",
    "tomli": "cluster",
}

#: From this many atoms the NumPy engine is slower than real time (docs/benchmarks.md:
#: about 18 ms a frame at 300 atoms, growing faster than N): without the compiled core, say so.
SLOW_REFERENCE_ATOMS = 400


class MissingExtraError(ImportError):
    """An optional dependency is not installed; the message says which extra installs it."""


class CoreMissingWarning(UserWarning):
    """No compiled engine core in this install: the reference engine plays (said once)."""


class SlowEngineWarning(UserWarning):
    """Many atoms and no compiled core: the NumPy engine runs them, slower than real time."""


def install_hint(extra: str) -> str:
    """The pip line that adds `extra` to this install: a clone's folder (editable), else by
    name, which keeps the installed evapcool (a wheel's, an index's) and adds the extra's
    packages; a wheel's path would fail once the file is gone (docs/releasing.md)."""
    folder = _editable_folder()
    if folder is not None:
        return f"pip install -e '{folder}[{extra}]'"
    return f"pip install 'evapcool[{extra}]'"


def _editable_folder() -> str | None:
    """The clone an editable install points at (PEP 610's direct_url.json), else None."""
    import json
    from importlib import metadata
    from urllib.parse import unquote, urlparse

    try:
        text = metadata.distribution("evapcool").read_text("direct_url.json")
        doc = json.loads(text) if text else {}
    except (metadata.PackageNotFoundError, ValueError):
        return None
    url = urlparse(str(doc.get("url", "")))
    if url.scheme != "file" or not doc.get("dir_info", {}).get("editable"):
        return None
    return unquote(url.path)


def available(module: str) -> bool:
    """Whether `module` can be imported, without importing it (some take seconds)."""
    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):
        return False


def check(module: str, feature: str, hint: str | None = None) -> None:
    """MissingExtraError naming the extra (or `hint`) if `module` is not installed.

    Nothing is imported: some packages (pandas, dask) take seconds.
    """
    if not available(module):
        raise MissingExtraError(missing_message(module, feature, hint))


def require(module: str, feature: str) -> ModuleType:
    """Import `module` for `feature`, or MissingExtraError: 'FEATURE needs M: pip install ...'."""
    check(module, feature)
    try:
        return importlib.import_module(module)
    except ImportError as exc:  # installed but broken (e.g. built for another numpy)
        raise MissingExtraError(f"{missing_message(module, feature)} ({exc})") from exc


def missing_message(module: str, feature: str, hint: str | None = None) -> str:
    """'FEATURE needs MODULE, which is not installed: pip install ...'."""
    if hint is None:
        extra = EXTRA_OF.get(module)
        hint = install_hint(extra) if extra else f"pip install {module}"
    return f"{feature} needs {module}, which is not installed: {hint}"


def slow_engine_message(n_atoms: int) -> str:
    return (
        f"{n_atoms} atoms without the compiled engine core: the NumPy engine runs them slower "
        "than real time (seconds a frame at a few thousand); reinstall evapcool where a C "
        "compiler is at hand (or from a wheel)"
    )
