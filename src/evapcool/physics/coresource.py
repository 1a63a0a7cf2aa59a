"""The compiled core's sources and their hash: a build records it, an import compares it.

setup.py loads this file on its own (no package import) and compiles the hash into the
extension as `SOURCE_HASH`; physics/core.py compares it with the sources beside an
extension built in place, so an edited core is never used stale (issue 47).
"""

from __future__ import annotations

import hashlib
from pathlib import Path

#: The files the extension is compiled from, relative to the checkout's root.
PATTERNS = (
    "core/*.c",
    "core/*.h",
    "src/evapcool/physics/_coremodule.c",
    "src/evapcool/physics/_*.h",
)
#: What rebuilds the extension in place in a source checkout.
REBUILD = "python -m pip install --no-deps -e ."


def source_files(root: Path) -> list[Path]:
    """The core's source files under checkout `root`, in a fixed order."""
    return sorted({p for pattern in PATTERNS for p in root.glob(pattern)})


def source_hash(root: Path) -> str:
    """SHA-256 of the sources' names and texts (line ends as LF), 16 hex digits."""
    digest = hashlib.sha256()
    for path in source_files(root):
        digest.update(path.relative_to(root).as_posix().encode() + b"\0")
        digest.update(path.read_bytes().replace(b"\r\n", b"\n") + b"\0")
    return digest.hexdigest()[:16]


def checkout_of(extension: Path) -> Path | None:
    """The source checkout an extension file was built in place in, or None (an install)."""
    parents = extension.resolve().parents  # root/src/evapcool/physics/_core*.so
    if len(parents) < 4:
        return None
    root = parents[3]
    if (root / "core" / "evapcool_core.h").is_file() and (root / "setup.py").is_file():
        return root
    return None
