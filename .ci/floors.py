"""Print constraints that pin every requirement of pyproject.toml to its declared floor.

`pip install -c` (or `uv pip install -c`) with this output installs the lowest versions
the project claims to support, so CI proves the floors (issue 16). A requirement without
a floor is left free; one for another Python (a marker) keeps its marker. Where an extra
asks more of a package than the applet does (the tests need a newer pygame-ce), the
higher floor is pinned; `--dependencies` pins the applet's own requirements alone (the
lean install is checked at those).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

REQUIREMENT = re.compile(r"^\s*([A-Za-z0-9_.-]+)(\[[^\]]*\])?\s*>=\s*([^,;\s]+)\s*(;.*)?$")


def _release(version: str) -> tuple[int, ...]:
    return tuple(int(part) for part in re.findall(r"\d+", version))


def floors(pyproject: Path, extras: bool = True) -> list[str]:
    project = tomllib.loads(pyproject.read_text(encoding="utf-8"))["project"]
    requirements = list(project["dependencies"])
    if extras:
        for extra in project.get("optional-dependencies", {}).values():
            requirements += extra
    pins: dict[str, tuple[str, str]] = {}
    for requirement in requirements:
        match = REQUIREMENT.match(requirement)
        if match:
            name, _, version, marker = match.groups()
            key = name.lower()
            if key not in pins or _release(version) > _release(pins[key][0]):
                pins[key] = (version, f"{name}=={version}" + (f" {marker}" if marker else ""))
    return sorted(pin for _, pin in pins.values())


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--dependencies"]
    root = Path(args[0]) if args else Path(__file__).resolve().parents[1]
    print("\n".join(floors(root / "pyproject.toml", extras="--dependencies" not in sys.argv)))
