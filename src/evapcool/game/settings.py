"""Game settings saved as JSON in the user config folder (platformdirs).

No pygame here. Loading never raises: a bad value falls back to its default
and a corrupt file is set aside, each with a notice string for the UI (and on
stderr). Command-line flags go through `with_overrides`, which validates against
the same ranges as the settings screen (limits.APPLET_*) but never saves. Saving
takes the file's lock and re-reads it, so two windows do not undo each other's choices.
"""

from __future__ import annotations

import json
import numbers
import os
from collections.abc import Callable
from dataclasses import asdict, dataclass, fields, replace
from functools import lru_cache
from pathlib import Path
from typing import Any

from evapcool import limits
from evapcool.about import APP_NAME
from evapcool.fileio import (
    NotRegularFileError,
    atomic_write_text,
    locked,
    read_user_text,
    set_aside,
    warn,
)
from evapcool.i18n import PSEUDO, language_name, shipped_locales, t
from evapcool.physics.config import check_choice
from evapcool.physics.loading import capacity
from evapcool.physics.room import CLASSIC_ROOM
from evapcool.physics.simulation import (
    ATOM_RADIUS,
    CURVATURE,
    N_ATOMS,
    TC_LAWS,
    TRAP_HEIGHT,
)
from evapcool.physics.world import ESCAPE_RULES

FILE_NAME = "settings.json"
FORMAT_VERSION = 1

#: The applet's ranges (limits.APPLET_RADIUS, limits.APPLET_ATOMS): the settings screen,
#: the settings file and the command line all use them.
RADIUS_MIN = limits.APPLET_RADIUS.low
RADIUS_MAX = limits.APPLET_RADIUS.high
#: Hard cap whatever the radius; max_atoms also caps by what fits in the cup.
ATOMS_MAX = int(limits.APPLET_ATOMS.high)
#: The play area's top border (SPEC 1), px: the settings screen's atoms all start below
#: it, in view (the view draws it: view/screen.BORDER_TOP).
SHOWN_BELOW_TOP = 48.0


@dataclass(frozen=True)
class Settings:
    """What Restart applies. Defaults are the original applet."""

    n_atoms: int = N_ATOMS
    radius: float = ATOM_RADIUS
    tc_law: str = "seed"
    escape: str = "rim"
    #: The applet's language: a shipped catalog's tag, or "auto" (the system's).
    language: str = "auto"
    #: The colours: "dark" (the original's) or "projector" (light, high contrast; issue 48).
    theme: str = "dark"
    #: Sound on or off (key M mutes this run only), and its volume in percent.
    sound: str = "on"
    volume: int = 60

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
THEMES = ("dark", "projector")
SOUNDS = ("on", "off")
#: The volume's range and the settings screen's step, percent.
VOLUME_MAX = 100
VOLUME_STEP = 10


@lru_cache(maxsize=64)
def cup_capacity(radius: float) -> int:
    """How many atoms of this radius start wholly inside the cup, below its rim.

    The rim starts at TRAP_HEIGHT, below the play area's top border, so every atom of
    such a start is trapped and in view (`loading.capacity`, the loader's own rows).
    """
    play_top = CLASSIC_ROOM.top(radius) - SHOWN_BELOW_TOP  # trap y of the border's edge
    return capacity(radius, CURVATURE, min(TRAP_HEIGHT, play_top))


def max_atoms(radius: float) -> int:
    """Largest atom count the settings allow for this radius: all trapped, all in view."""
    return min(ATOMS_MAX, cup_capacity(float(radius)))


@lru_cache(maxsize=64)
def command_line_max_atoms(radius: float) -> int:
    """Largest --atoms for this radius: what the loading fits below the window's top, as
    `Simulation` loads it (some may start above the rim)."""
    return min(ATOMS_MAX, capacity(radius, CURVATURE, CLASSIC_ROOM.top(radius)))


# -- validation -------------------------------------------------------------------
def _check_n_atoms(value: object, radius: float, cap: Callable[[float], int] = max_atoms) -> int:
    top = cap(radius)
    if isinstance(value, float) and value.is_integer():
        value = int(value)  # 49.0 from a hand-edited file is fine; 49.5 is not
    if (
        isinstance(value, bool)
        or not isinstance(value, numbers.Integral)
        or not 1 <= int(value) <= top
    ):
        where = "below the rim" if cap is max_atoms else "below the window's top"
        raise limits.ParameterError(
            "n_atoms",
            f"must be a whole number from 1 to {top} for radius {radius:g}, "
            f"what fits {where} (got {limits.shown(value)})",
        )
    return int(value)


def languages() -> tuple[str, ...]:
    """What the language setting may be: "auto", then every shipped catalog and en-XA."""
    return ("auto", *shipped_locales(), PSEUDO)


def choices() -> dict[str, tuple[str, ...]]:
    """The settings that are a choice among names, with their options in screen order."""
    return {
        "tc_law": tuple(TC_LAWS),
        "escape": ESCAPE_RULES,
        "language": languages(),
        "theme": THEMES,
        "sound": SOUNDS,
    }


def _check_volume(value: object) -> int:
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= VOLUME_MAX:
        raise limits.ParameterError(
            "volume", f"must be a whole number from 0 to {VOLUME_MAX} (got {limits.shown(value)})"
        )
    return value


def validate(settings: Settings, cap: Callable[[float], int] = max_atoms) -> Settings:
    """The same settings with canonical types; ValueError naming the first bad field.

    cap(radius): the most atoms allowed, by default the settings screen's (all below the
    rim); the command line allows what the loading fits (command_line_max_atoms).
    """
    radius = limits.APPLET_RADIUS.check("radius", settings.radius)
    n_atoms = _check_n_atoms(settings.n_atoms, radius, cap)
    chosen = {k: check_choice(k, getattr(settings, k), v) for k, v in choices().items()}
    volume = _check_volume(settings.volume)
    return Settings(n_atoms=n_atoms, radius=radius, volume=volume, **chosen)


def from_mapping(data: dict[str, object]) -> tuple[Settings, list[str]]:
    """Settings from a parsed file: each bad or missing-typed value falls back with a notice."""
    notices: list[str] = []
    unknown = sorted(k for k in data if k not in FIELD_NAMES and k != "version")
    if unknown:
        notices.append(t("notice.settings_unknown", names=", ".join(unknown)))

    def take(name: str, check: Callable[[object], Any], default: Any) -> Any:
        if name not in data:
            return default
        try:
            return check(data[name])
        except ValueError as exc:
            notices.append(t("notice.settings_bad_value", problem=exc, default=repr(default)))
            return default

    radius = take("radius", lambda v: limits.APPLET_RADIUS.check("radius", v), DEFAULTS.radius)
    # The atom count is checked against the capacity of the radius actually used.
    fallback_n = min(DEFAULTS.n_atoms, max_atoms(radius))
    n_atoms = take("n_atoms", lambda v: _check_n_atoms(v, radius), fallback_n)

    def choice(name: str, options: tuple[str, ...]) -> Any:
        return take(name, lambda v: check_choice(name, v, options), getattr(DEFAULTS, name))

    chosen = {name: choice(name, options) for name, options in choices().items()}
    volume = take("volume", _check_volume, DEFAULTS.volume)
    return Settings(n_atoms=n_atoms, radius=radius, volume=volume, **chosen), notices


def with_overrides(settings: Settings, **overrides: Any) -> Settings:
    """Settings for one run with command-line values on top (None = not given). Not saved.

    ValueError (naming the parameter and what is allowed) for an unknown name or bad value.
    """
    given = {k: v for k, v in overrides.items() if v is not None}
    bad = [k for k in given if k not in FIELD_NAMES]
    if bad:
        raise ValueError(f"unknown setting {bad[0]!r}; known: {', '.join(FIELD_NAMES)}")
    # The same radius range as the screen; atoms up to what the loading fits (issue 4).
    return validate(replace(settings, **given), cap=command_line_max_atoms)


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
    if name == "volume":
        return replace(s, volume=max(0, min(VOLUME_MAX, s.volume + d * VOLUME_STEP)))
    if name in choices():
        options = choices()[name]
        i = options.index(getattr(s, name))
        changed: dict[str, Any] = {name: options[(i + d) % len(options)]}
        return replace(s, **changed)
    raise ValueError(f"unknown setting {name!r}; known: {', '.join(FIELD_NAMES)}")


def describe(settings: Settings) -> list[tuple[str, str]]:
    """(label, value) rows for an options screen."""
    s = settings
    law = t("settings.law_seed") if s.tc_law == "seed" else t("settings.law_cup")
    rule = t("settings.escape_rim") if s.escape == "rim" else t("settings.escape_knife")
    auto = s.language == "auto"
    return [
        (t("settings.atoms"), t("settings.atoms_value", n=s.n_atoms, max=max_atoms(s.radius))),
        (t("settings.radius"), t("settings.radius_value", radius=s.radius)),
        (t("settings.tc_law"), law),
        (t("settings.escape"), rule),
        (
            t("settings.language"),
            t("settings.language_auto") if auto else language_name(s.language),
        ),
        (t("theme.row"), t(f"theme.{s.theme}")),
        (t("sound.row"), t(f"sound.{s.sound}")),
        (t("sound.volume"), t("sound.volume_value", percent=s.volume)),
    ]


# -- the file ---------------------------------------------------------------------
def default_path() -> Path:
    """The settings file in the per-user config folder (platformdirs)."""
    from platformdirs import user_config_dir

    return Path(user_config_dir(APP_NAME, appauthor=False)) / FILE_NAME


def load_settings(path: str | os.PathLike[str] | None = None) -> tuple[Settings, list[str]]:
    """Saved settings (defaults if none) and notices about anything that was wrong."""
    p = Path(path) if path is not None else default_path()
    data, notices = _read_file(p)
    if data is None:
        return DEFAULTS, notices
    s, more = from_mapping(data)
    return s, notices + more


def _read_file(p: Path) -> tuple[dict[str, object] | None, list[str]]:
    """The file's object, or None (missing, unreadable or set aside) with the notices."""
    try:
        text = read_user_text(p, limits.USER_FILE_MAX_BYTES)
    except (FileNotFoundError, NotADirectoryError):
        return None, []
    except NotRegularFileError:
        return None, [t("notice.settings_not_regular", path=p)]
    except OSError as exc:
        return None, [t("notice.settings_unreadable", path=p, problem=exc)]
    except ValueError as exc:  # not UTF-8, or far too large for a settings file
        return None, [_set_aside(p, getattr(exc, "reason", None) or str(exc))]
    try:
        data = json.loads(text)
    except RecursionError:
        return None, [_set_aside(p, "not valid JSON: nested too deeply")]
    except ValueError as exc:
        return None, [_set_aside(p, f"not valid JSON: {exc}")]
    if not isinstance(data, dict):
        return None, [_set_aside(p, "not a JSON object")]
    return data, []


def _set_aside(path: Path, why: str) -> str:
    try:
        moved = set_aside(path)
    except OSError as exc:
        text = t("notice.settings_damaged_kept", path=path, why=why, problem=exc)
    else:
        text = t("notice.settings_damaged", why=why, name=moved.name)
    warn(text)
    return text


def save_settings(
    settings: Settings,
    path: str | os.PathLike[str] | None = None,
    base: Settings | None = None,
) -> list[str]:
    """Validate and write atomically; returns notices (empty on success). Never raises OSError.

    base: the settings this session read or last saved. Given, only the fields that
    differ from it are written over the file's current ones, so choices another window
    saved meanwhile stay; without it every field is written.
    """
    s = validate(settings)
    p = Path(path) if path is not None else default_path()
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        with locked(p):
            if base is not None:
                s = _merged(s, base, p)
            payload = {"version": FORMAT_VERSION, **asdict(s)}
            atomic_write_text(p, json.dumps(payload, indent=2) + "\n")
    except OSError as exc:
        return [t("notice.settings_unsaved", path=p.parent, problem=exc)]
    return []


def _merged(mine: Settings, base: Settings, p: Path) -> Settings:
    """The file's settings with the fields this session changed (mine != base) on top."""
    data, _ = _read_file(p)
    if data is None:
        return mine
    theirs, _ = from_mapping(data)
    changed = {f: getattr(mine, f) for f in FIELD_NAMES if getattr(mine, f) != getattr(base, f)}
    merged = replace(theirs, **changed)
    try:
        return validate(merged)
    except ValueError:  # their atom count does not fit my new radius, or the like
        return mine
