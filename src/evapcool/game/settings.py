"""Game settings saved as JSON in the user config folder (platformdirs).

No pygame here. Loading never raises: a bad value falls back to its default
and a corrupt file is set aside, each with a notice string for the UI.
Command-line flags go through `with_overrides`, which validates but never saves.
"""

from __future__ import annotations

import json
import math
import numbers
import os
from dataclasses import asdict, dataclass, fields, replace
from functools import lru_cache
from pathlib import Path

from evapcool.about import APP_NAME
from evapcool.fileio import atomic_write_text, set_aside
from evapcool.physics.loading import capacity
from evapcool.physics.simulation import (
    ATOM_RADIUS,
    BORDER_TOP,
    CURVATURE,
    N_ATOMS,
    TC_LAWS,
    TRAP_HEIGHT,
    WINDOW,
    cup_vertex,
)
from evapcool.physics.world import ESCAPE_RULES

FILE_NAME = "settings.json"
FORMAT_VERSION = 1

#: Below 3 px an atom is a speck on a projector; above 20 px fewer than 49 fit.
RADIUS_MIN = 3.0
RADIUS_MAX = 20.0
#: Hard cap whatever the radius: beyond this the frame loop cannot keep 30 fps.
ATOMS_MAX = 2000


@dataclass(frozen=True)
class Settings:
    """What Restart applies. Defaults are the original applet."""

    n_atoms: int = N_ATOMS
    radius: float = ATOM_RADIUS
    tc_law: str = "seed"
    escape: str = "rim"

    @property
    def tc_exponent(self) -> float:
        return TC_LAWS[self.tc_law]

    def simulation_kwargs(self) -> dict[str, object]:
        """Keyword arguments for `Simulation(**kwargs, seed=...)`."""
        return {
            "n_atoms": self.n_atoms,
            "radius": self.radius,
            "tc_exponent": self.tc_exponent,
            "escape": self.escape,
        }


DEFAULTS = Settings()
FIELD_NAMES = tuple(f.name for f in fields(Settings))


@lru_cache(maxsize=64)
def cup_capacity(radius: float) -> int:
    """How many atoms of this radius start wholly inside the cup, below its rim.

    The rim starts at TRAP_HEIGHT, below the play area's top border, so every atom of
    such a start is trapped and in view (`loading.capacity`, the loader's own rows).
    """
    play_top = cup_vertex(WINDOW)[1] - radius - BORDER_TOP  # trap y of the border's edge
    return capacity(radius, CURVATURE, min(TRAP_HEIGHT, play_top))


def max_atoms(radius: float) -> int:
    """Largest allowed atom count for this radius."""
    return min(ATOMS_MAX, cup_capacity(float(radius)))


# -- validation -------------------------------------------------------------------
def _check_radius(value: object, *, ranged: bool = True) -> float:
    allowed = (
        f"a number from {RADIUS_MIN:g} to {RADIUS_MAX:g} px" if ranged else "a positive number"
    )
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"radius must be {allowed} (got {value!r})")
    v = float(value)
    ok = RADIUS_MIN <= v <= RADIUS_MAX if ranged else v > 0.0
    if not (math.isfinite(v) and ok):
        raise ValueError(f"radius must be {allowed} (got {value!r})")
    return v


def _check_n_atoms(value: object, radius: float, *, ranged: bool = True) -> int:
    top = max_atoms(radius) if ranged else None
    msg = (
        f"n_atoms must be a whole number from 1 to {top} for radius {radius:g}"
        if ranged
        else "n_atoms must be a whole number >= 1"
    )
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        # 49.0 from a hand-edited file is fine; 49.5 is not.
        if isinstance(value, float) and value.is_integer():
            value = int(value)
        else:
            raise ValueError(f"{msg} (got {value!r})")
    if int(value) < 1 or (top is not None and int(value) > top):
        raise ValueError(f"{msg} (got {value!r})")
    return int(value)


def _check_choice(name: str, value: object, allowed: tuple[str, ...]) -> str:
    if not isinstance(value, str) or value not in allowed:
        raise ValueError(f"{name} must be one of {', '.join(allowed)} (got {value!r})")
    return value


def validate(settings: Settings, *, ranged: bool = True) -> Settings:
    """The same settings with canonical types; ValueError naming the first bad field.

    ranged=False (command-line values) asks only what the physics needs; whether the
    atoms fit is then left to `Simulation`, which says so in one line.
    """
    radius = _check_radius(settings.radius, ranged=ranged)
    return Settings(
        n_atoms=_check_n_atoms(settings.n_atoms, radius, ranged=ranged),
        radius=radius,
        tc_law=_check_choice("tc_law", settings.tc_law, tuple(TC_LAWS)),
        escape=_check_choice("escape", settings.escape, ESCAPE_RULES),
    )


def from_mapping(data: dict[str, object]) -> tuple[Settings, list[str]]:
    """Settings from a parsed file: each bad or missing-typed value falls back with a notice."""
    notices: list[str] = []
    unknown = sorted(k for k in data if k not in FIELD_NAMES and k != "version")
    if unknown:
        notices.append(f"Settings: ignored unknown entries {', '.join(unknown)}.")

    def take(name: str, check, default):
        if name not in data:
            return default
        try:
            return check(data[name])
        except ValueError as exc:
            notices.append(f"Settings: {exc}; using the default {default!r}.")
            return default

    radius = take("radius", _check_radius, DEFAULTS.radius)
    # The atom count is checked against the capacity of the radius actually used.
    fallback_n = min(DEFAULTS.n_atoms, max_atoms(radius))
    n_atoms = take("n_atoms", lambda v: _check_n_atoms(v, radius), fallback_n)
    tc_law = take("tc_law", lambda v: _check_choice("tc_law", v, tuple(TC_LAWS)), DEFAULTS.tc_law)
    escape = take("escape", lambda v: _check_choice("escape", v, ESCAPE_RULES), DEFAULTS.escape)
    return Settings(n_atoms=n_atoms, radius=radius, tc_law=tc_law, escape=escape), notices


def with_overrides(settings: Settings, **overrides: object) -> Settings:
    """Settings for one run with command-line values on top (None = not given). Not saved.

    ValueError (naming the parameter and what is allowed) for an unknown name or bad value.
    """
    given = {k: v for k, v in overrides.items() if v is not None}
    bad = [k for k in given if k not in FIELD_NAMES]
    if bad:
        raise ValueError(f"unknown setting {bad[0]!r}; known: {', '.join(FIELD_NAMES)}")
    # The overlay's ranges are for the overlay; a physicist may ask for 10 000 tiny atoms.
    return validate(replace(settings, **given), ranged=False)


def step(settings: Settings, name: str, direction: int) -> Settings:
    """The options screen's +/- on one field: numbers move and clamp, choices cycle.

    Changing the radius clamps the atom count to what then fits.
    """
    s = settings
    d = 1 if direction > 0 else -1
    if name == "n_atoms":
        # Coarser steps for big counts; going down uses the band below so 20 -> 19.
        n = s.n_atoms if d > 0 else s.n_atoms - 1
        inc = 1 if n < 20 else 5 if n < 100 else 50 if n < 500 else 100
        return replace(s, n_atoms=max(1, min(max_atoms(s.radius), s.n_atoms + d * inc)))
    if name == "radius":
        r = max(RADIUS_MIN, min(RADIUS_MAX, round(s.radius) + d))
        return replace(s, radius=float(r), n_atoms=min(s.n_atoms, max_atoms(r)))
    if name in ("tc_law", "escape"):
        options = tuple(TC_LAWS) if name == "tc_law" else ESCAPE_RULES
        i = options.index(getattr(s, name))
        return replace(s, **{name: options[(i + d) % len(options)]})
    raise ValueError(f"unknown setting {name!r}; known: {', '.join(FIELD_NAMES)}")


def describe(settings: Settings) -> list[tuple[str, str]]:
    """(label, value) rows for an options screen."""
    law = "2/3 (original)" if settings.tc_law == "seed" else "2/5 (this cup)"
    rule = "fly over the rim" if settings.escape == "rim" else "energy knife"
    return [
        ("Number of atoms", f"{settings.n_atoms}  (1 to {max_atoms(settings.radius)})"),
        ("Atom radius", f"{settings.radius:g} px"),
        ("Tc law: Tc ~ N^p, p =", law),
        ("Escape rule", rule),
    ]


# -- the file ---------------------------------------------------------------------
def default_path() -> Path:
    """The settings file in the per-user config folder (platformdirs)."""
    from platformdirs import user_config_dir

    return Path(user_config_dir(APP_NAME, appauthor=False)) / FILE_NAME


def load_settings(path: str | os.PathLike[str] | None = None) -> tuple[Settings, list[str]]:
    """Saved settings (defaults if none) and notices about anything that was wrong."""
    p = Path(path) if path is not None else default_path()
    try:
        text = p.read_text(encoding="utf-8")
    except (FileNotFoundError, NotADirectoryError):
        return DEFAULTS, []
    except OSError as exc:
        return DEFAULTS, [f"Settings could not be read from {p} ({exc}); using defaults."]
    except UnicodeDecodeError:
        return DEFAULTS, [_set_aside(p, "not valid UTF-8")]
    try:
        data = json.loads(text)
    except ValueError as exc:
        return DEFAULTS, [_set_aside(p, f"not valid JSON: {exc}")]
    if not isinstance(data, dict):
        return DEFAULTS, [_set_aside(p, "not a JSON object")]
    return from_mapping(data)


def _set_aside(path: Path, why: str) -> str:
    try:
        moved = set_aside(path)
    except OSError as exc:
        return f"The settings file {path} is damaged ({why}); using defaults ({exc})."
    return f"The settings file was damaged ({why}); it was kept as {moved.name}; using defaults."


def save_settings(settings: Settings, path: str | os.PathLike[str] | None = None) -> list[str]:
    """Validate and write atomically; returns notices (empty on success). Never raises OSError."""
    s = validate(settings)
    p = Path(path) if path is not None else default_path()
    payload = {"version": FORMAT_VERSION, **asdict(s)}
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(p, json.dumps(payload, indent=2) + "\n")
    except OSError as exc:
        return [f"Settings could not be saved to {p.parent} ({exc}); they apply to this session."]
    return []
