"""Settings: round trip, validation, fallback with notices, corrupt files, overrides."""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from evapcool import Simulation
from evapcool.game.settings import (
    ATOMS_MAX,
    DEFAULTS,
    RADIUS_MAX,
    RADIUS_MIN,
    TC_LAWS,
    Settings,
    cup_capacity,
    describe,
    from_mapping,
    load_settings,
    max_atoms,
    save_settings,
    step,
    validate,
    with_overrides,
)
from evapcool.physics.loading import cell_centres
from evapcool.physics.simulation import TC_EXPONENT_CUP, TC_EXPONENT_SEED


def test_defaults_are_the_original_applet() -> None:
    assert Settings(n_atoms=49, radius=12.0, tc_law="seed", escape="rim") == DEFAULTS
    assert DEFAULTS.tc_exponent == TC_EXPONENT_SEED
    assert TC_LAWS["cup"] == TC_EXPONENT_CUP


def test_missing_file_gives_defaults_without_notice(tmp_path: Path) -> None:
    assert load_settings(tmp_path / "nope" / "settings.json") == (DEFAULTS, [])


def test_round_trip(tmp_path: Path) -> None:
    path = tmp_path / "cfg" / "settings.json"
    s = Settings(n_atoms=200, radius=5.0, tc_law="cup", escape="knife")
    assert save_settings(s, path) == []
    assert load_settings(path) == (s, [])
    assert json.loads(path.read_text(encoding="utf-8"))["escape"] == "knife"


def test_bad_values_fall_back_with_a_notice_each(tmp_path: Path) -> None:
    path = tmp_path / "settings.json"
    data = {"n_atoms": "many", "radius": 7, "tc_law": "cubic", "escape": "knife"}
    path.write_text(json.dumps(data), encoding="utf-8")
    s, notices = load_settings(path)
    assert s == Settings(n_atoms=DEFAULTS.n_atoms, radius=7.0, tc_law="seed", escape="knife")
    assert len(notices) == 2
    assert any("n_atoms" in n and "'many'" in n for n in notices)
    assert any("tc_law" in n and "cubic" in n for n in notices)


def test_too_many_atoms_for_the_radius_falls_back(tmp_path: Path) -> None:
    path = tmp_path / "settings.json"
    path.write_text(json.dumps({"n_atoms": 500, "radius": 12}), encoding="utf-8")
    s, notices = load_settings(path)
    assert s.n_atoms == DEFAULTS.n_atoms and s.radius == 12.0
    assert len(notices) == 1 and "n_atoms" in notices[0]


def test_bad_radius_falls_back_and_atoms_are_checked_against_the_default(tmp_path: Path) -> None:
    path = tmp_path / "settings.json"
    path.write_text(json.dumps({"n_atoms": 60, "radius": float("nan")}), encoding="utf-8")
    s, notices = load_settings(path)
    assert s == Settings(n_atoms=60, radius=DEFAULTS.radius)
    assert len(notices) == 1 and "radius" in notices[0]


def test_unknown_keys_are_reported_and_ignored() -> None:
    s, notices = from_mapping({"n_atoms": 30, "colour": "red"})
    assert s == Settings(n_atoms=30)
    assert len(notices) == 1 and "colour" in notices[0]


@pytest.mark.parametrize("content", ["{oops", "[49, 12]", '"seed"'])
def test_corrupt_file_is_set_aside(tmp_path: Path, content: str) -> None:
    path = tmp_path / "settings.json"
    path.write_text(content, encoding="utf-8")
    s, notices = load_settings(path)
    assert s == DEFAULTS
    assert len(notices) == 1 and "damaged" in notices[0]
    assert not path.exists()
    assert len(list(tmp_path.glob("settings.json.corrupt-*"))) == 1


def test_unwritable_config_folder_gives_a_notice(tmp_path: Path) -> None:
    blocker = tmp_path / "evapcool"
    blocker.write_text("", encoding="utf-8")  # a file where the folder should be
    notices = save_settings(DEFAULTS, blocker / "settings.json")
    assert len(notices) == 1 and "could not be saved" in notices[0]
    assert load_settings(blocker / "settings.json") == (DEFAULTS, [])


def test_overrides_apply_for_one_run_without_saving(tmp_path: Path) -> None:
    path = tmp_path / "settings.json"
    save_settings(DEFAULTS, path)
    before = path.read_bytes()
    s = with_overrides(DEFAULTS, n_atoms=20, radius=None, escape="knife")
    assert s == Settings(n_atoms=20, escape="knife")
    assert path.read_bytes() == before
    assert load_settings(path)[0] == DEFAULTS


@pytest.mark.parametrize(
    ("overrides", "word"),
    [
        ({"n_atoms": 0}, "n_atoms"),
        ({"n_atoms": 2.5}, "n_atoms"),
        ({"radius": 0.0}, "radius"),
        ({"radius": -1.0}, "radius"),
        ({"radius": float("inf")}, "radius"),
        ({"tc_law": "3d"}, "tc_law"),
        ({"escape": "door"}, "escape"),
        ({"speed": 3}, "speed"),
    ],
)
def test_bad_overrides_raise_value_error_naming_the_parameter(
    overrides: dict[str, object], word: str
) -> None:
    with pytest.raises(ValueError, match=word):
        with_overrides(DEFAULTS, **overrides)


def test_command_line_overrides_share_the_settings_ranges() -> None:
    # Issue 4: `evapcool --atoms 10000 --radius 1` must play; issue 14.13: the command
    # line, its help and the settings screen share one range per parameter.
    run = with_overrides(DEFAULTS, n_atoms=10_000, radius=1.0)
    assert (run.n_atoms, run.radius) == (10_000, 1.0)
    Simulation(**run.simulation_kwargs(), seed=1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"n_atoms .* 1 to 93 for radius 12"):
        with_overrides(DEFAULTS, n_atoms=94)  # 93 atoms of radius 12 fit, not 94
    with pytest.raises(ValueError, match="radius must be a number from 1 to 20 px"):
        with_overrides(DEFAULTS, radius=0.5)


@pytest.mark.parametrize("radius", [3.0, 12.0, 16.0, 20.0])
def test_capacity_is_what_starts_below_the_rim(radius: float) -> None:
    """Issue 14, item 7: every start the settings allow is wholly in the cup, under the rim."""
    cap = cup_capacity(radius)
    assert cap >= 1
    for seed in range(3):
        sim = Simulation(n_atoms=cap, radius=radius, seed=seed, engine="reference")
        tops = sim.positions[:, 1] + radius
        assert tops.max() <= sim.trap_height and sim.n_trapped == cap
        assert np.all(np.abs(sim.positions[:, 0]) < sim.rim_half_width)
    # One more atom would need a cell reaching above the rim.
    with pytest.raises(ValueError):
        cell_centres(cap + 1, radius, 0.01, 400.0)


def test_every_allowed_radius_fits_at_least_the_default_count_or_says_so() -> None:
    # The top of the range still holds a playable gas.
    assert max_atoms(RADIUS_MAX) >= 20
    assert max_atoms(RADIUS_MIN) == min(ATOMS_MAX, cup_capacity(RADIUS_MIN))


def test_simulation_kwargs_build_a_simulation() -> None:
    s = Settings(n_atoms=30, radius=10.0, tc_law="cup", escape="knife")
    sim = Simulation(**s.simulation_kwargs(), seed=1, engine="reference")  # type: ignore[arg-type]
    assert sim.n_atoms == 30
    assert sim.tc_exponent == pytest.approx(0.4)
    assert sim.escape_rule == "knife"


def test_step_clamps_and_cycles() -> None:
    s = DEFAULTS
    assert step(s, "n_atoms", +1).n_atoms == 54
    assert step(Settings(n_atoms=20), "n_atoms", -1).n_atoms == 19
    assert step(Settings(n_atoms=1), "n_atoms", -1).n_atoms == 1
    top = Settings(n_atoms=max_atoms(12.0))
    assert step(top, "n_atoms", +1).n_atoms == max_atoms(12.0)
    big = step(Settings(n_atoms=90, radius=12.0), "radius", +1)
    assert big.radius == 13.0 and big.n_atoms == min(90, max_atoms(13.0))
    assert step(Settings(radius=RADIUS_MAX, n_atoms=10), "radius", +1).radius == RADIUS_MAX
    assert step(s, "tc_law", +1).tc_law == "cup"
    assert step(step(s, "escape", +1), "escape", +1).escape == "rim"
    with pytest.raises(ValueError):
        step(s, "colour", +1)
    assert (
        len(describe(s)) == 8
    )  # atoms, radius, Tc law, escape rule, language, theme, sound, volume
    assert step(s, "language", +1).language == "ar"  # after "auto", the shipped tags
    assert step(s, "language", -1).language == "en-XA"


_any_value = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-10, max_value=5000),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=6),
    st.sampled_from(["seed", "cup", "rim", "knife"]),
    st.lists(st.integers(), max_size=2),
)


@settings(max_examples=150, deadline=None)
@given(
    st.dictionaries(st.sampled_from(["n_atoms", "radius", "tc_law", "escape", "other"]), _any_value)
)
def test_any_file_content_gives_valid_settings(data: dict[str, object]) -> None:
    s, notices = from_mapping(data)
    assert validate(s) == s  # always playable
    # Every key kept as given is exactly the value from the file; anything else was noticed.
    changed = [k for k in ("n_atoms", "radius", "tc_law", "escape") if k in data]
    for k in changed:
        if getattr(s, k) != data[k] or type(data[k]) is bool:
            assert any(k in n for n in notices)


_valid = st.floats(min_value=RADIUS_MIN, max_value=RADIUS_MAX).flatmap(
    lambda r: st.builds(
        Settings,
        n_atoms=st.integers(min_value=1, max_value=max_atoms(r)),
        radius=st.just(r),
        tc_law=st.sampled_from(sorted(TC_LAWS)),
        escape=st.sampled_from(["rim", "knife"]),
    )
)


@settings(max_examples=40, deadline=None)
@given(_valid)
def test_valid_settings_round_trip_exactly(s: Settings) -> None:
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "settings.json"
        assert save_settings(s, path) == []
        assert load_settings(path) == (s, [])


def test_theme_sound_and_volume_step_and_load() -> None:
    """Issue 48's settings: the theme and sound cycle, the volume moves by 10 and clamps; a bad
    saved value falls back with a notice."""
    s = Settings()
    assert (s.theme, s.sound, s.volume) == ("dark", "on", 60)
    assert step(s, "theme", +1).theme == "projector" and step(s, "sound", +1).sound == "off"
    assert step(s, "volume", +1).volume == 70 and step(s, "volume", -1).volume == 50
    assert step(Settings(volume=100), "volume", +1).volume == 100
    assert step(Settings(volume=0), "volume", -1).volume == 0
    loaded, notices = from_mapping({"theme": "projector", "volume": 500})
    assert loaded.theme == "projector" and loaded.volume == 60
    assert len(notices) == 1 and "volume" in notices[0]
