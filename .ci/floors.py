"""Print constraints that pin every requirement of pyproject.toml to its declared floor.

`pip install -c` (or `uv pip install -c`) with this output installs the lowest versions
the project claims to support, so CI proves the floors (issue 16). A requirement without
a floor is left free; one for another Python (a marker) keeps its marker.
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


def floors(pyproject: Path) -> list[str]:
    project = tomllib.loads(pyproject.read_text(encoding="utf-8"))["project"]
    requirements = list(project["dependencies"])
    for extra in project.get("optional-dependencies", {}).values():
        requirements += extra
    pins: dict[str, str] = {}
    for requirement in requirements:
        match = REQUIREMENT.match(requirement)
        if match:
            name, _, version, marker = match.groups()
            pins[name.lower()] = f"{name}=={version}" + (f" {marker}" if marker else "")
    return sorted(pins.values())


if __name__ == "__main__":
    root = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[1]
    print("\n".join(floors(root / "pyproject.toml")))
